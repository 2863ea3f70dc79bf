"""[analysis] kind = "trajectory": one trajectory, recorded and classified."""

from __future__ import annotations

from dataclasses import dataclass

from ..analysis.engine import Problem
from ..analysis.trajectory import trajectory_dataset
from ..config.limits import MAX_TRAJECTORY_SAMPLES
from .base import AnalysisKind, PlotOption, PlotSpec, read_state, read_t0


@dataclass(frozen=True)
class TrajectoryAnalysis:
    """[analysis] kind = "trajectory": one trajectory, recorded and classified."""

    kind: str
    state: tuple[float, ...]
    periods: int = 200
    t0: float = 0.0
    samples_per_period: int = 64


def read(sec, ctx) -> TrajectoryAnalysis:
    if not sec.has("state"):
        raise sec.fail("state", f"is required: the initial {', '.join(ctx.system.state_names)}")
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


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    state = ", ".join(f"{x:g}" for x in a.state)
    return (f"trajectory: {a.periods} periods from ({state}) at t0 = {a.t0:g}, "
            f"{a.samples_per_period} samples per period")


PLOT = PlotSpec(
    "Time series, phase portraits and Poincare points of a trajectory RESULT.",
    options=(PlotOption("--last-periods", "last_periods", "Periods drawn strongly as the "
                        "steady state (default: a quarter, <= 20).", kind="int>=1"),))

KINDS = (AnalysisKind("trajectory", "one trajectory, recorded and classified", read, plan,
                      run=run, plot=PLOT),)
