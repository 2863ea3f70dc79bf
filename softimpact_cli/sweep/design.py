"""Run a design scene: the catalogue, then ``analysis.design`` with its basin-stability
samples classified on the sweep executors (local pool or Dask), like any sweep.

Not resumable: a design is a few thousand trajectories; the result is written whole at
the end by the caller.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np
import xarray as xr

from ..analysis.catalogue import (
    BodySearch,
    Catalogue,
    catalogue_dataset,
    catalogue_states,
    extend_catalogue,
)
from ..analysis.design import AXES, NoRegion, design
from ..config import ConfigError, Grid, Scene, forcing_period
from ..config.axes import catalogue_key
from ..store.catalogues import scene_body_attractors
from ..store.provenance import provenance
from .chunks import CELL_BLOCK
from .executors import make_executor
from .plan import default_chunk_size
from .runner import sweep_context
from .second_stage import relabel, unpack


def pair_catalogue(scene: Scene, search: BodySearch, phi: float) -> Catalogue:
    """The pair's catalogue at phi from the left body's search (as the sweeps build
    theirs in ``prepare_catalogues``, without searching the left body again)."""
    return extend_catalogue(scene.system, {**scene.values, "phi": phi}, scene.integrator,
                            *search)


def classify(scene: Scene, executor, grid: Grid, catalogues: dict, names: tuple[str, ...],
             t0_per_sample: np.ndarray | None, start: int, stop: int,
             progress: Callable[[int], Callable[[int], None]] | None = None) -> np.ndarray:
    """Label codes (points, stop - start) of the samples [start, stop) of [initial_conditions]
    at each point of the panels ``grid`` (``catalogues`` by catalogue key, ``names`` their
    names in code order), classified on ``executor`` as a sweep's chunks are."""
    context = sweep_context(replace(scene, grid=grid), catalogues, names, t0_per_sample)
    context = replace(context, states=context.states[start:stop], t0=context.t0[start:stop])
    points = grid.size
    total = points * (stop - start)
    block = CELL_BLOCK if scene.integrator.cell_size > 0.0 else 1
    size = default_chunk_size(total, getattr(executor, "workers", 8), block)
    chunks = [(i, lo, min(lo + size, total)) for i, lo in enumerate(range(0, total, size))]
    labels = np.empty(total, dtype=np.int32)
    recurrent: list = []
    tick = progress(total) if progress else None
    for index, result in executor.run(context, chunks):
        lo = chunks[index][1]
        labels[lo: lo + len(result["label"])] = result["label"]
        recurrent += unpack(result)
        if tick:
            tick(len(result["label"]))
    # the second stage's attractors, named over this batch in flat-index order
    relabel(context, labels, {}, recurrent, tuple(scene.system.state_names))
    return labels.reshape(points, stop - start)


def run_design(scene: Scene, workers: int | None = None, scheduler: str | None = None,
               echo: Callable[[str], None] = lambda s: None,
               progress: Callable[[int], Callable[[int], None]] | None = None) -> xr.Dataset:
    """Run the design scene; return its dataset (with the catalogue at the pick's phase
    and provenance). User errors (no target, a target not in the catalogue, no region)
    raise ConfigError before anything is written."""
    a = scene.analysis
    if a.target is None:
        raise ConfigError(f"{scene.source}: [analysis] target: is required (a name like "
                          "'L1^1 R1-0^1'), or pass --target")
    started, t_start = time.time(), time.perf_counter()
    say = echo

    def echo(message: str) -> None:  # each stage with the time since the start
        say(f"[{time.perf_counter() - t_start:6.1f} s] {message}")

    states = catalogue_states(scene)
    echo(f"catalogue: searching {len(states)} initial conditions of one body")
    search = scene_body_attractors(scene, states=states)
    echo(f"catalogue: {search.source}")
    first = pair_catalogue(scene, search, a.bounds["phi"][0])
    names = first.names
    if a.target not in names:
        raise ConfigError(f"{scene.source}: [analysis] target: {a.target!r} is not in the "
                          f"catalogue; its non-impacting combinations: {', '.join(names)}")
    executor = make_executor(workers, scheduler)
    echo(f"executor: {executor.describe()}")
    ic = scene.initial_conditions
    t0_per_sample = ic.random_t0(forcing_period(scene.values)) if ic.t0 is None \
        else None
    catalogues: dict[float, Catalogue] = {}

    def evaluate(points: list[dict], start: int, stop: int) -> np.ndarray:
        """Label codes (len(points), stop - start) of samples [start, stop) per point."""
        for p in points:
            if float(p["phi"]) not in catalogues:
                catalogues[float(p["phi"])] = pair_catalogue(scene, search, float(p["phi"]))
        axes = {x: tuple(float(p[x]) for p in points) for x in AXES}
        grid = Grid({**axes, "t0": (0.0,) * len(points)}, AXES, panels=True)
        batch = {catalogue_key(scene.system, {**scene.values, "phi": float(p["phi"])}):
                 catalogues[float(p["phi"])] for p in points}
        return classify(scene, executor, grid, batch, names, t0_per_sample, start, stop,
                        progress)

    try:
        ds = design(scene.system, dict(scene.values), search.attractors, a, ic.count,
                    evaluate, echo)
    except NoRegion as exc:
        raise ConfigError(f"{scene.source}: [analysis] target: {exc}") from None
    pick = {x: float(ds[f"point_{x}"].values[0]) for x in AXES}
    cat = pair_catalogue(scene, search, pick["phi"])
    ds = xr.merge([ds, catalogue_dataset(cat, scene.system, scene.integrator)],
                  combine_attrs="override", compat="override", join="exact")
    ds.attrs.update(provenance(scene, started, time.time(), time.perf_counter() - t_start))
    chosen = {**scene.values, **pick}  # "parameters" names the pick, not [coupling]
    ds.attrs.update({"analysis": "design", "executor": executor.describe(),
                     "parameters": ", ".join(f"{k}={v}" for k, v in chosen.items()),
                     "t0_mode": "random" if ic.t0 is None else "fixed",
                     "t0": float(ic.t0) if ic.t0 is not None else -1.0,
                     "forcing_period": forcing_period(scene.values),
                     "sample_box": ", ".join(f"{k}=[{lo:g}, {hi:g}]"
                                             for k, (lo, hi) in ic.box.items()),
                     "sample_seed": ic.seed, "catalogue_source": search.source})
    return ds
