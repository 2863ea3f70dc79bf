"""[analysis] kind = "lyapunov": Lyapunov exponents of a trajectory, of every catalogue
solution, or along a parameter ([grid]); see ``analysis/lyapunov.py`` for the method."""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..analysis.engine import Problem
from ..analysis.lyapunov_scans import (
    Averaging,
    catalogue_spectra,
    parameter_spectra,
    trajectory_spectrum,
)
from ..config.chain_scene import CHAIN
from ..config.reader import ConfigError
from ..config.scene import thin
from ..config.sweep import read_grid
from ..report.lyapunov import format_lyapunov, lyapunov_summary
from ..store.catalogues import scene_catalogue
from .base import AnalysisKind, PlotSpec, Sections, read_start, read_t0

STARTS = ("state", "catalogue")
QUICK_PERIODS = 100  # --quick: at most this many averaged periods (and 20 transient)
MAX_PERIODS = 10_000_000


@dataclass(frozen=True)
class LyapunovAnalysis:
    """[analysis] kind = "lyapunov".

    start : "state" (the trajectory from ``state`` at ``t0``; with [grid], one spectrum
        per value of its one swept axis: a chain's by name) or "catalogue" (every solution
        of the [catalogue] search: one body's attractors, a pair's combinations or a
        chain's products, with their Floquet exponents beside)
    periods, transient, segments : forcing periods averaged, discarded before, and the
        segments whose spread gives the standard error (periods a multiple of segments)
    per_period : Gram-Schmidt re-orthonormalisations per period
    saltation : apply the saltation matrix at switches (false: for comparison only)
    follow : along a grid, start each value from the previous value's end state
    """

    kind: str
    start: str = "state"
    state: tuple[float, ...] | None = None
    t0: float = 0.0
    periods: int = 500
    transient: int = 50
    segments: int = 10
    per_period: int = 8
    saltation: bool = True
    follow: bool = True
    axis: str | None = None
    values: tuple[float, ...] = ()


def read(sec, ctx) -> LyapunovAnalysis:
    start, state = read_start(sec, ctx.system, STARTS, unused=" (the solutions' own "
                              "section points are the starts)")
    analysis = LyapunovAnalysis(
        kind="lyapunov", start=start, state=state, t0=read_t0(sec, ctx.period),
        periods=sec.integer("periods", 500, 2, MAX_PERIODS),
        transient=sec.integer("transient", 50, 0, MAX_PERIODS),
        segments=sec.integer("segments", 10, 2, 10_000),
        per_period=sec.integer("per_period", 8, 1, 10_000),
        saltation=sec.boolean("saltation", True),
        follow=sec.boolean("follow", True),
    )
    if not analysis.saltation and ctx.system.extra.get("rigid"):  # (kernels/impacts.py)
        raise sec.fail("saltation", "false is not offered with a rigid stop: its impacts "
                                    "always carry the tangent vectors by their saltation "
                                    "matrix (leaving them out would not be a comparison "
                                    "of anything); remove the key")
    if analysis.periods % analysis.segments:
        raise sec.fail("segments", f"must divide periods ({analysis.periods}) into equal "
                                   f"segments, got {analysis.segments}")
    return analysis


def sections(analysis, ctx) -> Sections:
    if analysis.start == "catalogue":
        ctx.refuse("grid", "initial_conditions")
        return Sections(analysis, catalogue=ctx.read_catalogue())
    ctx.refuse("initial_conditions", "catalogue")
    if "grid" not in ctx.doc:
        return Sections(analysis)
    chain = ctx.system.model == CHAIN
    grid = read_grid(ctx.source, ctx.doc, ctx.values, ctx.system.bodies, ctx.period,
                     ctx.check_axis, ctx.system.parameter_names if chain else (), chain)
    if len(grid.swept) != 1 or grid.panels:
        allowed = ("any of the chain's parameters by name (w, F.2, stop.1.d, ...) or t0"
                   if chain else "one of d, phi, k_c, c_c, t0")
        raise ConfigError(f"{ctx.source}: [grid]: lyapunov follows one parameter; give one "
                          f"axis ({allowed}), got {', '.join(grid.swept) or 'panels'}")
    axis = grid.swept[0]
    return Sections(replace(analysis, axis=axis, values=tuple(grid.axes[axis])), grid)


def shrink(analysis, grid, axis: int):
    seg = min(analysis.segments, 10)
    periods = max(seg, min(analysis.periods, QUICK_PERIODS) // seg * seg)
    out = replace(analysis, periods=periods, segments=seg,
                  transient=min(analysis.transient, 20))
    if grid is not None and analysis.axis is not None:
        values = thin(grid.axes[analysis.axis], axis)
        grid = replace(grid, axes={**grid.axes, analysis.axis: values})
        out = replace(out, values=values)
    return out, grid, f", at most {QUICK_PERIODS} averaged periods"


def _averaging(a):
    return Averaging(a.periods, a.transient, a.segments, a.per_period, a.saltation)


def run(scene, progress=None, **_):
    a = scene.analysis
    problem = Problem(scene.system, scene.values, scene.integrator)
    avg = _averaging(a)
    if a.start == "catalogue":
        cat = scene_catalogue(scene)
        tick = progress(len(cat.names)) if progress else None
        return catalogue_spectra(problem, cat, avg, tick)
    if a.axis is not None:
        tick = progress(len(a.values)) if progress else None
        return parameter_spectra(problem, a.state, a.t0, a.axis, a.values, avg, a.follow,
                                 tick)
    return trajectory_spectrum(problem, a.state, a.t0, avg)


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    what = "every catalogue solution" if a.start == "catalogue" else \
        f"the trajectory from ({', '.join(f'{x:g}' for x in a.state)}) at t0 = {a.t0:g}"
    if a.axis is not None:
        what += f", at {len(a.values)} values of {a.axis}" + \
            (" (each from the last end state)" if a.follow else "")
    salt = "" if a.saltation else " WITHOUT saltation matrices"
    return (f"lyapunov: {what}; {a.transient} + {a.periods} periods in {a.segments} "
            f"segments, {a.per_period} re-orthonormalisations per period{salt}")


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "start": '"state" (from state) or "catalogue" (every catalogue solution, Floquet exponents '
             'beside)',
    "state": 'start = "state": the initial state: [x1, v1, x2, v2] ([x, v] for one body)',
    "t0": 'the time at which the state is imposed: a number or "a*T/b" (the section stays at t = '
          '0 mod T)',
    "transient": "forcing periods discarded (state and tangent vectors settle)",
    "periods": "periods averaged, in segments equal segments",
    "segments": "their spread gives the standard error (periods a multiple of it)",
    "per_period": "Gram-Schmidt re-orthonormalisations per period",
    "saltation": "apply the saltation matrix at switches (false: wrong; for comparison)",
    "follow": "with [grid]: each value starts from the last one's end state",
}

KINDS = (AnalysisKind("lyapunov", "Lyapunov exponents (Benettin, saltation at switches) of "
                      "a trajectory, of catalogue solutions or along a parameter", read, plan,
                      sections=sections, shrink=shrink, run=run, summary=lyapunov_summary,
                      report=format_lyapunov,
                      info_after=lambda ds: format_lyapunov(ds).splitlines(),
                      progress_unit="spectra", variables=("exponent",), keys=KEYS,
                      plot=PlotSpec("Lyapunov exponents with their standard errors (against "
                                    "the parameter, beside the section states, for a grid "
                                    "run).")),)
