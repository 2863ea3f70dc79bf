"""Run a chain's design scene: the chain's catalogue at every body grid point (through the
catalogue cache), then ``analysis.chain_design`` with its basin-stability samples
classified on the sweep executors, as the pair's design (``sweep.design``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np
import xarray as xr

from ..analysis.chain_catalogue import (
    ChainCatalogue,
    at_values,
    chain_catalogue_dataset,
    extend_chain_catalogue,
)
from ..analysis.chain_design import chain_design
from ..analysis.design import NoRegion
from ..config import ConfigError, Grid, Scene, forcing_period
from ..config.axes import GRID_AXES, catalogue_key
from ..store.catalogues import scene_chain_searches
from ..store.provenance import provenance
from .design import classify
from .executors import make_executor


def run_chain_design(scene: Scene, workers: int | None = None, scheduler: str | None = None,
                     echo: Callable[[str], None] = lambda s: None,
                     progress: Callable[[int], Callable[[int], None]] | None = None
                     ) -> xr.Dataset:
    """Run the chain's design scene; return its dataset (with the chain's catalogue at the
    pick and provenance). User errors (no target, a target that is no product, no region)
    raise ConfigError before anything is written."""
    a, system = scene.analysis, scene.system
    if a.target is None:
        raise ConfigError(f"{scene.source}: [analysis] target: is required (a product's "
                          "name like 'B1:P1^1 B2:P1-0^1 B3:P1-0^1'), or pass --target")
    started, t_start = time.time(), time.perf_counter()
    say = echo

    def echo(message: str) -> None:  # each stage with the time since the start
        say(f"[{time.perf_counter() - t_start:6.1f} s] {message}")

    catalogues: dict[tuple, ChainCatalogue] = {}
    names: dict[str, None] = {}  # every product met, in code order (codes only append)

    def catalogue_at(point: dict) -> ChainCatalogue:
        """The chain's catalogue at the scene's values with ``point``'s (cached by the
        parameters the bodies depend on)."""
        values = {**scene.values, **point}
        key = catalogue_key(system, values)
        if key not in catalogues:
            at = replace(scene, values=values)
            catalogues[key] = extend_chain_catalogue(system, values, scene_chain_searches(at))
            names.update(dict.fromkeys(catalogues[key].names))
        return catalogues[key]

    executor = make_executor(workers, scheduler)
    echo(f"executor: {executor.describe()}")
    ic = scene.initial_conditions
    t0_per_sample = ic.random_t0(forcing_period(scene.values)) if ic.t0 is None else None
    axes = tuple(a.bounds)

    def evaluate(points: list[dict], start: int, stop: int) -> np.ndarray:
        """Label codes (len(points), stop - start) of samples [start, stop) per point."""
        batch = {}
        for p in points:
            cat = catalogue_at(p)
            batch[catalogue_key(system, {**scene.values, **p})] = cat
        grid = Grid({**{x: tuple(float(p[x]) for p in points) for x in axes},
                     **{g: (0.0,) * len(points) for g in GRID_AXES}}, axes, panels=True,
                    parameters=axes)
        return classify(scene, executor, grid, batch, tuple(names), t0_per_sample, start,
                        stop, progress)

    try:
        ds = chain_design(system, dict(scene.values), a, ic.count, evaluate, catalogue_at,
                          lambda: tuple(names), echo)
    except NoRegion as exc:
        raise ConfigError(f"{scene.source}: [analysis] target: {exc}") from None
    pick = {x: float(ds[f"point_{x}"].values[0]) for x in axes}
    chosen = {**scene.values, **pick}
    cat = at_values(catalogue_at(pick), system, chosen)
    ds = xr.merge([ds, chain_catalogue_dataset(cat, system)], combine_attrs="override",
                  compat="override", join="exact")
    ds.attrs.update(provenance(scene, started, time.time(), time.perf_counter() - t_start))
    ds.attrs.update({"analysis": "design", "model": "chain", "bodies": system.bodies,
                     "executor": executor.describe(),
                     "parameters": ", ".join(f"{k}={v}" for k, v in chosen.items()),
                     "t0_mode": "random" if ic.t0 is None else "fixed",
                     "t0": float(ic.t0) if ic.t0 is not None else -1.0,
                     "forcing_period": forcing_period(scene.values),
                     "sample_box": ", ".join(f"{k}=[{lo:g}, {hi:g}]"
                                             for k, (lo, hi) in ic.box.items()),
                     "sample_seed": ic.seed, "catalogue_source": cat.source})
    return ds
