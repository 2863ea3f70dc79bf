"""Run a sweep scene into a resumable result file."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import xarray as xr

from ..analysis.catalogue import (
    Catalogue,
    body_catalogue,
    body_problem,
    catalogue_dataset,
    combinations,
    require_attractors,
    right_attractors,
    sample_states,
)
from ..config import ConfigError, Scene
from ..store.provenance import provenance
from ..store.sweep_store import SweepStore
from .chunks import RESULT_FIELDS, SweepContext
from .executors import make_executor
from .plan import Plan, default_chunk_size
from .result import sweep_dataset


def prepare_catalogues(scene: Scene, progress=None) -> tuple[dict, tuple[str, ...]]:
    """The one-body catalogue, extended to the right body at every phi of the grid.

    Returns ({phi: Catalogue}, names in code order).
    """
    s = scene.catalogue
    system = scene.system
    problem = body_problem(system, scene.values, scene.integrator)
    states = sample_states(s.box, s.grid, s.random, s.seed)
    left, counts = body_catalogue(problem, states, 0.0, s.match_tol, progress)
    catalogues = {}
    phis = scene.grid.distinct("phi") if system.bodies == 2 else (0.0,)
    for phi in phis:
        right, combos = [], []
        if system.bodies == 2:
            right = right_attractors(problem, left, phi, system.extra["right_sign"],
                                     system.extra["right_phase"])
            combos = combinations(left, right)
        values = {**scene.values, "phi": phi} if system.bodies == 2 else dict(scene.values)
        catalogues[float(phi)] = Catalogue(system.model, values, tuple(left), tuple(right),
                                           tuple(combos), counts, len(states))
    names = next(iter(catalogues.values())).names
    return catalogues, names


def capturable_orbits(scene: Scene, catalogues: dict) -> dict | None:
    """Per phi, the stable non-impacting orbits a trajectory may be captured by, each as
    (section points (q, dim) in time order, d_crit); None when capture is off.

    One body: every stable attractor (d_crit = -inf, there is no stop). A pair: every
    combination of two stable attractors with its critical distance, located on the flow
    (``analysis.critical_distance``); which of them exist depends on d, decided per grid
    point by ``SweepContext.known_orbits``.
    """
    if scene.integrator.capture_tol <= 0.0:
        return None
    from ..analysis.critical_distance import critical_distance, uncoupled_pair

    known = {}
    for phi, cat in catalogues.items():
        if scene.system.bodies == 1:
            known[phi] = [(a.points, -np.inf) for a in cat.attractors if a.stable]
            continue
        problem = uncoupled_pair(scene.system, dict(scene.values), phi)
        known[phi] = [(c.orbit, critical_distance(problem, c.orbit[0], len(c.orbit), 256)[0])
                      for c in cat.combinations if c.left.stable and c.right.stable]
    return known


def sweep_context(scene: Scene, catalogues: dict, names: tuple[str, ...],
                  t0_per_sample: np.ndarray | None) -> SweepContext:
    """What every worker needs: the scene's grid, states, catalogues and capture orbits."""
    ic = scene.initial_conditions
    if t0_per_sample is not None:
        t0 = t0_per_sample
    elif "t0" in scene.grid.swept:
        t0 = None
    else:
        t0 = np.full(ic.count, float(ic.t0))
    return SweepContext(
        model=scene.system.model, bodies=scene.system.bodies, values=dict(scene.values),
        integrator=scene.integrator, grid=scene.grid, states=ic.array(), t0=t0,
        catalogues=catalogues, names=names, label_tol=scene.analysis.label_tol,
        known=capturable_orbits(scene, catalogues),
    )


def _header(scene: Scene, plan: Plan, catalogue: Catalogue) -> xr.Dataset:
    ds = catalogue_dataset(catalogue, scene.system, scene.integrator)
    ds.attrs.update(provenance(scene, time.time(), time.time(), 0.0))
    ds.attrs.update({"complete": 0, "analysis": scene.analysis.kind, "n": plan.n_total,
                     "n_chunks": plan.n_chunks, "chunk_size": plan.chunk_size,
                     "plan": plan.describe()})
    return ds


def run_sweep(scene: Scene, out: Path, workers: int | None = None, scheduler: str | None = None,
              resume: bool = False, overwrite: bool = False, chunk_size: int | None = None,
              echo: Callable[[str], None] = lambda s: None,
              progress: Callable[[int, int], Callable[[int], None]] | None = None
              ) -> xr.Dataset:
    """Run (or resume) a sweep scene into ``out``; return the complete dataset.

    ``progress(total, initial)`` may return a callable fed with the trajectories done.
    """
    store = SweepStore(out)
    executor = make_executor(workers, scheduler)
    n_total = scene.grid.size * scene.initial_conditions.count
    size = chunk_size or default_chunk_size(n_total, getattr(executor, "workers", 8))
    if resume:
        header = store.header()
        if header is None:
            raise ConfigError(f"{out}: nothing to resume (no such result)")
        if int(header.attrs.get("complete", 0)) == 1:
            raise ConfigError(f"{out}: is complete already; nothing to resume")
        if header.attrs.get("scene_sha256") != scene.sha256:
            raise ConfigError(f"{out}: was started from another scene (hash differs); "
                              "resume with the same scene, or --overwrite")
        size = int(header.attrs["chunk_size"])
    elif store.exists():
        if not overwrite:
            raise ConfigError(f"{out}: result exists; pass --overwrite to replace it, or "
                              "--resume to finish an interrupted run")
    plan = Plan(scene, size)
    plan.check_resources(out, str(scene.source))
    echo(plan.describe())
    echo(f"executor: {executor.describe()}")

    started = time.time()
    t_start = time.perf_counter()
    catalogues, names = prepare_catalogues(scene)
    if scene.analysis.kind == "map":  # counts need d_crit: stop before any chunk or file
        require_attractors(next(iter(catalogues.values())), "map", str(scene.source))
    echo(f"catalogue: {len(names)} solutions: {', '.join(names)}")
    ic = scene.initial_conditions
    t0_per_sample = None
    if ic.t0 is None:
        t0_per_sample = ic.random_t0(2 * np.pi / float(scene.values["w"]))
    context = sweep_context(scene, catalogues, names, t0_per_sample)
    if not resume:
        first = next(iter(catalogues.values()))
        if overwrite:
            store.remove()
        store.start(_header(scene, plan, first))
    done = store.done()
    todo = [(i, *plan.chunk(i)) for i in range(plan.n_chunks) if i not in done]
    if done:
        echo(f"resuming: {len(done)} of {plan.n_chunks} chunks already done")
    tick = progress(plan.n_total, sum(plan.chunk(i)[1] - plan.chunk(i)[0] for i in done)) \
        if progress else None
    for index, result in executor.run(context, todo):
        store.write_chunk(index, result)
        if tick:
            tick(len(result["label"]))

    arrays = {k: np.empty(plan.n_total, dtype=t) for k, t in RESULT_FIELDS.items()}
    orbits: dict = {}
    for index in range(plan.n_chunks):
        start, stop = plan.chunk(index)
        chunk = store.read_chunk(index)
        for key in RESULT_FIELDS:
            arrays[key][start:stop] = chunk[key]
        for key, (flat, pts) in chunk["orbits"].items():
            if key not in orbits or flat < orbits[key][0]:
                orbits[key] = (flat, pts)
    ds = sweep_dataset(scene, arrays, orbits, names, t0_per_sample)
    if scene.analysis.kind == "map":
        from ..analysis.maps import add_map_counts

        first = next(iter(catalogues.values()))
        ds = add_map_counts(ds, scene.system, dict(scene.values), list(first.attractors))
    catalogue_vars = catalogue_dataset(next(iter(catalogues.values())), scene.system,
                                       scene.integrator)
    ds = xr.merge([ds, catalogue_vars], combine_attrs="override", compat="override")
    wall = time.perf_counter() - t_start
    ds.attrs.update(provenance(scene, started, time.time(), wall))
    ds.attrs.update({"n": plan.n_total, "n_chunks": plan.n_chunks, "chunk_size": plan.chunk_size,
                     "plan": plan.describe(), "executor": executor.describe(),
                     "resumed": int(bool(done)), "complete": 1})
    store.finish(ds)
    return ds
