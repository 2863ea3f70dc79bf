"""Run a validated scene: pick its analysis, time it, attach provenance."""

from __future__ import annotations

import time

import xarray as xr

from .config import Scene
from .engine import Problem


def problem_of(scene: Scene) -> Problem:
    return Problem(scene.system, scene.values, scene.integrator)


def run_scene(scene: Scene) -> xr.Dataset:
    """Run the scene's analysis and return its dataset with provenance attributes."""
    from .store import provenance

    started = time.time()
    t0 = time.perf_counter()
    a = scene.analysis
    if a.kind == "trajectory":
        from .analysis.trajectory import trajectory_dataset

        ds = trajectory_dataset(problem_of(scene), a.state, a.t0, a.periods,
                                a.samples_per_period)
    else:  # config only admits known kinds
        raise AssertionError(f"unhandled analysis kind {a.kind!r}")
    wall = time.perf_counter() - t0
    ds.attrs.update(provenance(scene, started, time.time(), wall))
    return ds
