"""[analysis] kind = "fatal_shock": the minimal fatal shock of one solution
(``analysis.fatal_shock``): the smallest kick of the state, at some phase of its orbit,
that sends the system to another attractor."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..analysis.engine import Problem, record_trajectory
from ..analysis.fatal_shock import fatal_shock_dataset, unit_directions
from ..config.axes import GRID_AXES
from ..config.limits import MAX_SEED
from ..config.reader import ConfigError, positive
from ..report.fatal_shock import fatal_shock_lines, fatal_shock_summary
from ..store.catalogues import scene_catalogue
from ..sweep import label_states
from .base import AnalysisKind, PlotSpec, Sections


@dataclass(frozen=True)
class FatalShockAnalysis:
    """The [analysis] keys, each described in :data:`KEYS`."""

    kind: str
    solution: str
    phases: int = 8
    directions: int = 48
    max_shock: float = 5.0
    scan: int = 12
    tol: float = 1e-3
    seed: int = 0


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "solution": 'the solution to knock off, by name ("L1^1 R1-0^1")',
    "phases": "points of its orbit (over one period) where kicks are tried",
    "directions": "unit directions of the kick (random on the sphere; evenly spaced angles for "
                  "one body)",
    "max_shock": "largest kick magnitude scanned",
    "scan": "magnitudes scanned up to max_shock before the bisection",
    "tol": "bisection tolerance of the fatal magnitude",
    "seed": "seed of the random directions",
}


def read(sec, ctx) -> FatalShockAnalysis:
    if not sec.has("solution"):
        raise sec.fail("solution", "is required: the label name of the solution to shake, "
                                   "e.g. \"L1^1 R1-0^1\" (`softimpact sweep` of a catalogue "
                                   "scene lists them)")
    solution = sec.raw("solution")
    if not isinstance(solution, str) or not solution.strip():
        raise sec.fail("solution", f"must be a label name like \"L1^1 R1-0^1\", got "
                                   f"{solution!r}")
    return FatalShockAnalysis(
        kind="fatal_shock", solution=solution.strip(),
        phases=sec.integer("phases", 8, 1, 1000),
        directions=sec.integer("directions", 48, 1, 100_000),
        max_shock=sec.number("max_shock", 5.0, positive),
        scan=sec.integer("scan", 12, 1, 10_000),
        tol=sec.number("tol", 1e-3, positive),
        seed=sec.integer("seed", 0, 0, MAX_SEED))


def sections(analysis, ctx) -> Sections:
    ctx.refuse("grid", "initial_conditions")
    return Sections(analysis, catalogue=ctx.read_catalogue())


# --quick: at most this many phases and directions (the first of the scene's directions:
# the same seed draws them first; the scan and the bisection's tolerance stay)
QUICK_PHASES, QUICK_DIRECTIONS = 4, 16


def shrink(analysis, grid, axis: int):
    return (replace(analysis, phases=min(analysis.phases, QUICK_PHASES),
                    directions=min(analysis.directions, QUICK_DIRECTIONS)), grid,
            f", at most {QUICK_PHASES} phases x {QUICK_DIRECTIONS} directions")


def solution_orbit(scene, catalogue) -> np.ndarray:
    """The section points (t = 0 mod T) of the scene's solution in its catalogue."""
    found = catalogue.orbits
    name = scene.analysis.solution
    if name not in found:
        raise ConfigError(f"{scene.source}: [analysis] solution: {name!r} is not in the "
                          f"catalogue at this point; one of {', '.join(map(repr, found))}")
    return np.asarray(found[name], dtype=float)


def run(scene, progress=None, workers=None, **_):
    a = scene.analysis
    catalogue = scene_catalogue(scene)
    start = solution_orbit(scene, catalogue)[0]
    problem = Problem(scene.system, scene.values, scene.integrator)
    T = problem.period
    traj = record_trajectory(problem, start, 0.0, 1, a.phases)
    orbit, times = traj.y[: a.phases], traj.t[: a.phases]
    names = tuple(scene.system.state_names)
    directions = unit_directions(a.directions, len(names),
                                 None if len(names) == 2 else a.seed)
    point = {k: float(scene.values[k]) for k in GRID_AXES if k in scene.values}
    tick = progress(a.phases) if progress else None

    def label(states, k):
        return label_states(scene, point, states, float(times[k]), workers)

    ds = fatal_shock_dataset(orbit, times, a.solution, label, directions, a.max_shock,
                             a.scan, a.tol, names, tick)
    ds.attrs["forcing_period"] = T
    return ds


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    return (f"fatal_shock: {a.solution}: {a.phases} phases x {a.directions} directions, "
            f"{a.scan} magnitudes up to {a.max_shock:g}, bisection to {a.tol:g}")


KINDS = (AnalysisKind(
    "fatal_shock", "minimal fatal shock: the smallest kick that sends a solution elsewhere",
    read, plan, sections=sections, shrink=shrink, run=run, summary=fatal_shock_summary,
    info_lines=fatal_shock_lines,
    info_catalogue=False, options=("workers",), progress_unit="phases",
    keys=KEYS,
    variables=("shock_destination",),
    plot=PlotSpec("The fatal shocks of a fatal_shock RESULT against the phase of the "
                  "orbit: the smallest over directions, the median and the quartiles.")),)
