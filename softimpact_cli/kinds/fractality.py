"""[analysis] kind = "fractality": how fractal the basins of a plane are.

The scene is a basins scene ([grid], [initial_conditions] kind = "plane", [catalogue])
with ``kind = "fractality"``: the plane is swept in memory (and verified, as every sweep)
and measured by ``analysis.fractality``: basin entropy S_b and S_bb against the box
size, the uncertainty exponent alpha with D = 2 - alpha, the Wada merging test. A basins
result already on disk is measured without sweeping again by ``softimpact measure``
(the same dataset). Keys, all optional:

    box_sizes = [2, 5, 10]   # basin-entropy boxes, in cells (default 2 .. min(20, side/4))
    radii = [1, 2, 4, 8]     # uncertainty radii, in cells (default ~12 in 1 .. side/10)
    wada_radius = 5          # largest fattening of the merged boundaries (cells)
    wada_tol = 0.05          # largest mismatch share still called Wada
    label_tol = 1e-3         # as for basins
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..analysis.fractality import fractality
from ..config.reader import ConfigError, positive
from ..report.fractality import fractality_lines, fractality_summary
from ..sweep import sweep_in_memory
from ..sweep.executors import make_executor
from ..sweep.verification import verify_sweep
from .base import AnalysisKind, PlotOption, PlotSpec, Sections
from .sweeps import SweepAnalysis
from .sweeps import plan as sweep_plan
from .sweeps import sections as sweep_sections


@dataclass(frozen=True)
class FractalityAnalysis:
    """[analysis] kind = "fractality" (see the module docstring)."""

    kind: str
    box_sizes: tuple[int, ...] | None = None
    radii: tuple[int, ...] | None = None
    wada_radius: int = 5
    wada_tol: float = 0.05
    label_tol: float = 1e-3


def _cells(sec, key: str, smallest: int) -> tuple[int, ...] | None:
    value = sec.raw(key)
    if value is None:
        return None
    if not isinstance(value, list) or not value or any(
            isinstance(v, bool) or not isinstance(v, int) or v < smallest for v in value):
        raise sec.fail(key, f"must be a non-empty list of whole numbers of cells >= "
                            f"{smallest}, got {value!r}")
    return tuple(sorted(set(value)))


def read(sec, ctx) -> FractalityAnalysis:
    return FractalityAnalysis(
        kind="fractality", box_sizes=_cells(sec, "box_sizes", 2),
        radii=_cells(sec, "radii", 1),
        wada_radius=sec.integer("wada_radius", 5, 1, 100),
        wada_tol=sec.number("wada_tol", 0.05, lambda v: None if 0 <= v < 1
                            else "must be in [0, 1)"),
        label_tol=sec.number("label_tol", 1e-3, positive))


def sections(analysis, ctx) -> Sections:
    read_ = sweep_sections(analysis, ctx)
    ic = read_.initial_conditions
    if ic.kind != "plane":
        raise ConfigError(f"{ctx.source}: [initial_conditions] kind: fractality measures a "
                          f"plane (kind = \"plane\"), got {ic.kind!r}")
    side = min(ic.resolution)
    for key, values, fits in (("box_sizes", analysis.box_sizes, lambda n: n <= side),
                              ("radii", analysis.radii, lambda r: 2 * r + 1 <= side)):
        if values and not all(fits(v) for v in values):
            raise ConfigError(f"{ctx.source}: [analysis] {key}: {list(values)} does not fit "
                              f"a plane of {side} cells per side (box <= side, 2 r + 1 <= "
                              "side)")
    return read_


def basins_scene(scene):
    """The basins sweep a fractality scene measures."""
    return replace(scene, analysis=SweepAnalysis("basins", scene.analysis.label_tol))


def run(scene, progress=None, workers=None, scheduler=None, echo=None, **_):
    echo = echo or (lambda s: None)
    plane = basins_scene(scene)
    ds = sweep_in_memory(plane, workers, scheduler, None, echo, progress)
    ds = verify_sweep(plane, ds, lambda tighter, _: sweep_in_memory(
        tighter, workers, scheduler, None, echo, progress), None,
        make_executor(workers, scheduler), echo)
    a = scene.analysis
    return fractality(ds, a.box_sizes, a.radii, a.wada_radius, a.wada_tol)


def plan(scene, workers=None, chunk_size=None) -> str:
    line = sweep_plan(basins_scene(scene), workers, chunk_size)
    return ("fractality: basin entropy, uncertainty exponent and Wada test of a basins "
            + line.removeprefix("basins: ").removeprefix("plan: "))


def report(ds) -> str:
    return "\n".join(fractality_lines(ds))



# what each [analysis] key means (the scene-key reference)
KEYS = {
    "box_sizes": "box sizes (cells) of the basin entropy (default: from the plane)",
    "radii": "perturbation radii (cells) of the uncertainty exponent (default: from the plane)",
    "wada_radius": "cells a basin is grown by in the Wada merging test",
    "wada_tol": "share of boundary cells allowed to miss a basin in the Wada test",
    "label_tol": "a trajectory whose section points lie this close to a catalogue orbit takes its "
                 "label",
}

KINDS = (AnalysisKind(
    "fractality", "basin entropy, uncertainty exponent and Wada test of a plane",
    read, plan, sections=sections, run=run, summary=fractality_summary, report=report,
    info_after=fractality_lines, info_catalogue=False, progress_unit="trajectories",
    variables=("label_share", "n_basins"),
    options=("workers", "scheduler", "echo"),
    keys=KEYS,
    plot=PlotSpec("S_b and S_bb against the box size, the uncertainty fit and the Wada map "
                  "of a fractality RESULT (softimpact measure), one row per plane.",
                  options=(PlotOption("--max-panels", "max_panels", "Largest number of "
                                      "planes drawn.", kind="int>=1", default=8),))),)
