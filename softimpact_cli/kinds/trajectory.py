"""[analysis] kind = "trajectory": one trajectory, recorded and classified."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analysis.engine import Problem
from ..analysis.trajectory import trajectory_dataset
from ..config.limits import MAX_TRAJECTORY_SAMPLES
from ..config.reader import ConfigError
from ..config.space import OVERHEAD_BYTES, size_text
from .base import AnalysisKind, PlotOption, PlotSpec, read_state, read_t0


@dataclass(frozen=True)
class TrajectoryAnalysis:
    """[analysis] kind = "trajectory": one trajectory, recorded and classified."""

    kind: str
    state: tuple[float, ...]
    periods: int = 200
    t0: float = 0.0
    samples_per_period: int = 64


def _missing_state(sec, ctx):
    """The error of a trajectory without its start: a scene without [analysis], or without
    its ``kind``, is one trajectory (the default kind), which needs ``state``."""
    names = ", ".join(ctx.system.state_names)
    if "analysis" not in ctx.doc:
        sweep = "initial_conditions" in ctx.doc or "grid" in ctx.doc
        return ConfigError(
            f"{ctx.source}: [analysis]: missing; a scene without it is one trajectory "
            f"(kind = \"trajectory\"), which needs [analysis] state = [{names}] (the "
            "initial state)" + ("; for a sweep over [initial_conditions] set [analysis] "
                                "kind = \"basins\", \"stability\" or \"map\"" if sweep
                                else "; or set [analysis] kind (softimpact example lists "
                                     "the kinds)"))
    if not sec.has("kind"):
        return sec.fail("state", f"is required: the initial {names} (no kind is set: the "
                                 "scene is one trajectory, the default kind)")
    return sec.fail("state", f"is required: the initial {names}")


def read(sec, ctx) -> TrajectoryAnalysis:
    if not sec.has("state"):
        raise _missing_state(sec, ctx)
    analysis = TrajectoryAnalysis(
        kind="trajectory",
        state=read_state(sec, "state", ctx.system),
        periods=sec.integer("periods", 200, 1, 10_000_000),
        t0=read_t0(sec, ctx.period),
        samples_per_period=sec.integer("samples_per_period", 64, 1, 100_000),
    )
    samples = analysis.periods * analysis.samples_per_period
    if samples > MAX_TRAJECTORY_SAMPLES:  # the recorded states: samples x dim floats
        raise sec.fail("periods", f"periods x samples_per_period = {samples} recorded "
                                  f"samples; at most {MAX_TRAJECTORY_SAMPLES}")
    return analysis


def run(scene, progress=None, **_):
    a = scene.analysis
    return trajectory_dataset(Problem(scene.system, scene.values, scene.integrator), a.state,
                              a.t0, a.periods, a.samples_per_period)


def result_bytes(scene) -> int:
    """Upper estimate of the stored trajectory, uncompressed: the dense samples (time and
    state; one period more than asked when t0 falls between sections), the section
    points (time, state, contacts, max contact function), the classified orbit and a
    fixed overhead."""
    a = scene.analysis
    dim = len(scene.system.state_names)
    samples = (a.periods + 1) * a.samples_per_period + 1
    sections = a.periods + 1
    orbit = scene.integrator.max_orbit_period * dim
    return 8 * (samples * (1 + dim) + sections * (3 + dim) + orbit) + OVERHEAD_BYTES


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    state = ", ".join(f"{x:g}" for x in a.state)
    return (f"trajectory: {a.periods} periods from ({state}) at t0 = {a.t0:g}, "
            f"{a.samples_per_period} samples per period; result at most "
            f"{size_text(result_bytes(scene))}")


def summary(ds) -> dict:
    """A chain's part of ``info``: each stop's max compression on the final orbit."""
    if "stop_max_penetration" not in ds:
        return {}
    values = ds["stop_max_penetration"].values
    return {"max_penetration_by_stop": {
        f"stop {stop} ({between})": None if not np.isfinite(v) else float(v)
        for stop, between, v in zip(ds["stop"].values.tolist(),
                                    ds["stop_between"].values.tolist(), values, strict=True)}}


PLOT = PlotSpec(
    "Time series, phase portraits and Poincare points of a trajectory RESULT.",
    options=(PlotOption("--last-periods", "last_periods", "Periods drawn strongly as the "
                        "steady state (default: a quarter, <= 20).", kind="int>=1"),))


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "state": "the initial state: [x1, v1, x2, v2] ([x, v] for one body)",
    "periods": "forcing periods integrated",
    "t0": 'the time at which the state is imposed: a number or "a*T/b" (the section stays at t = '
          '0 mod T)',
    "samples_per_period": "points recorded per forcing period",
}

KINDS = (AnalysisKind("trajectory", "one trajectory, recorded and classified", read, plan,
                      keys=KEYS,
                      run=run, result_bytes=result_bytes, plot=PLOT, summary=summary,
                      variables=("state", "time", "section_state", "section_time", "variable")),)
