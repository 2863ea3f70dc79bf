"""Run a validated scene: pick its analysis, time it, attach provenance."""

from __future__ import annotations

import time

import xarray as xr

from .config import Scene
from .engine import Problem


def problem_of(scene: Scene) -> Problem:
    return Problem(scene.system, scene.values, scene.integrator)


def run_scene(scene: Scene, progress=None) -> xr.Dataset:
    """Run the scene's analysis and return its dataset with provenance attributes.

    ``progress(total)`` may return a callable that is called with the number of units
    done (the CLI passes a tqdm bar); analyses never print.
    """
    from .store import provenance

    started = time.time()
    t0 = time.perf_counter()
    a = scene.analysis
    if a.kind == "trajectory":
        from .analysis.trajectory import trajectory_dataset

        ds = trajectory_dataset(problem_of(scene), a.state, a.t0, a.periods,
                                a.samples_per_period)
    elif a.kind == "catalogue":
        from .analysis.catalogue import build_catalogue, catalogue_dataset, sample_states

        states = sample_states(a.box, a.grid, a.random, a.seed)
        tick = progress(len(states)) if progress else None
        cat = build_catalogue(scene.system, dict(scene.values), scene.integrator, states, a.t0,
                              a.match_tol, tick)
        ds = catalogue_dataset(cat, scene.system, scene.integrator)
    elif a.kind == "dcrit":
        ds = critical_distance_dataset(scene, progress)
    elif a.kind == "bifurcation":
        ds = bifurcation_result(scene, progress)
    elif a.kind == "design":
        from .sweep.design import run_design

        ds = run_design(scene, progress=progress)
    else:  # config only admits known kinds
        raise AssertionError(f"unhandled analysis kind {a.kind!r}")
    wall = time.perf_counter() - t0
    ds.attrs.update(provenance(scene, started, time.time(), wall))
    return ds


def scene_catalogue(scene: Scene):
    """The [catalogue] search of a dcrit or bifurcation scene; one line (ConfigError) and
    nothing further computed when it finds no attractor."""
    from .analysis.catalogue import build_catalogue, require_attractors, sample_states

    c = scene.catalogue
    cat = build_catalogue(scene.system, dict(scene.values), scene.integrator,
                          sample_states(c.box, c.grid, c.random, c.seed), 0.0, c.match_tol)
    require_attractors(cat, scene.analysis.kind, str(scene.source))
    return cat


def critical_distance_dataset(scene: Scene, progress=None) -> xr.Dataset:
    """d_crit(phi) of every combination, the traces of fig. 5 (b-d), and the catalogue."""
    import numpy as np

    from .analysis.catalogue import catalogue_dataset
    from .analysis.critical_distance import critical_distances, traces

    a = scene.analysis
    values = dict(scene.values)
    cat = scene_catalogue(scene)
    tick = progress(len(a.phis)) if progress else None
    ds = critical_distances(scene.system, values, list(cat.attractors), np.array(a.phis),
                            a.samples, tick)
    if a.traces:
        ds = xr.merge([ds, traces(scene.system, values, cat, a.traces, a.samples)],
                      combine_attrs="override")
    ds = xr.merge([ds, catalogue_dataset(cat, scene.system, scene.integrator)
                   .drop_vars(["combination_orbit"]).drop_dims("joint_point")],
                  combine_attrs="override", compat="override")
    ds.attrs["analysis"] = "dcrit"
    ds.attrs["forcing_period"] = 2 * np.pi / float(values["w"])
    return ds


def bifurcation_result(scene: Scene, progress=None) -> xr.Dataset:
    """Follow the scene's branches along d (figure 7), with the catalogue attached."""
    from .analysis.bifurcation import bifurcation_dataset, d_values
    from .analysis.catalogue import catalogue_dataset
    from .config import ConfigError

    a = scene.analysis
    values = dict(scene.values)
    cat = scene_catalogue(scene)
    branches = list(a.branches) or list(cat.names)
    for b in branches:
        if b not in cat.names:
            raise ConfigError(f"{scene.source}: [analysis] branches: {b!r} is not in the "
                              f"catalogue ({', '.join(cat.names)})")
    tick = progress(len(branches)) if progress else None
    ds = bifurcation_dataset(scene.system, values, scene.integrator, cat, branches,
                             d_values(a.start, a.stop, a.step), tick)
    ds = xr.merge([ds, catalogue_dataset(cat, scene.system, scene.integrator)],
                  combine_attrs="override", compat="override")
    ds.attrs["analysis"] = "bifurcation"
    ds.attrs["forcing_period"] = 2 * 3.141592653589793 / float(values["w"])
    return ds


def plan_text(scene: Scene, workers: int | None = None, chunk_size: int | None = None) -> str:
    """What running ``scene`` will compute, as text (``sweep --dry-run``); runs nothing."""
    import os

    from .config import SWEEP_KINDS

    a = scene.analysis
    lines = []
    if a.kind in SWEEP_KINDS:
        from .sweep.plan import Plan, default_chunk_size

        n_total = scene.grid.size * scene.initial_conditions.count
        size = chunk_size or default_chunk_size(n_total, workers or os.cpu_count() or 1)
        lines.append(f"{a.kind}: " + Plan(scene, size).describe())
    elif a.kind == "trajectory":
        state = ", ".join(f"{x:g}" for x in a.state)
        lines.append(f"trajectory: {a.periods} periods from ({state}) at t0 = {a.t0:g}, "
                     f"{a.samples_per_period} samples per period")
    elif a.kind == "catalogue":
        lines.append(f"catalogue: {a.grid} x {a.grid} grid + {a.random} random initial "
                     f"conditions of one body at t0 = {a.t0:g}")
    elif a.kind == "dcrit":
        lines.append(f"dcrit: d_crit of every combination at {len(a.phis)} phases"
                     + (f", x1 - x2 traces at {len(a.traces)}" if a.traces else "")
                     + f", {a.samples} samples per joint orbit")
    elif a.kind == "bifurcation":
        from .analysis.bifurcation import d_values

        branches = f"{len(a.branches)} branches" if a.branches else \
            "every combination of the catalogue"
        lines.append(f"bifurcation: {branches} x {d_values(a.start, a.stop, a.step).size} "
                     f"steps of d from {a.start:g} to {a.stop:g} by {a.step:g}")
    elif a.kind == "design":
        free = 4  # d, phi, k_c and c_c are each moved by +-perturbation_steps
        lines.append(f"design: target {a.target or '(give --target)'}; {a.candidates} "
                     f"candidates screened on {a.screen_n} samples, the best {a.refine} rerun "
                     f"on {scene.initial_conditions.count}; {2 * a.perturbation_steps * free} "
                     f"perturbed points on {a.robust_n or scene.initial_conditions.count} "
                     f"samples; d_crit over {a.phi_points} phases")
    if scene.catalogue is not None:
        c = scene.catalogue
        lines.append(f"catalogue: {c.grid} x {c.grid} grid + {c.random} random initial "
                     "conditions of one body")
    lines.append(f"output: {scene.output}")
    return "\n".join(lines)
