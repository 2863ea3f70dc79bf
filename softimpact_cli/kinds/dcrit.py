"""[analysis] kind = "dcrit": the critical distance d_crit(phi) of every combination; on a
chain, each stop's critical value for every non-impacting product against any parameter
(``analysis.chain_dcrit``)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from ..analysis.catalogue import sample_states
from ..analysis.chain_dcrit import chain_critical_gaps
from ..analysis.critical_distance import TIGHT, critical_distances, traces
from ..config.chain_scene import CHAIN
from ..config.expressions import parse_multiple
from ..config.reader import ConfigError
from ..config.scene import forcing_period, thin
from ..config.sweep import flat_grid, read_grid, read_parameter_axis
from ..plot import dcrit
from ..report.compare import compare_dcrit, dcrit_comparison_text, dcrit_curves
from ..store.catalogues import scene_catalogue, with_catalogue
from ..sweep.check import tightened
from .base import AnalysisKind, PlotOption, PlotSpec, Sections

QUICK_PHIS = 64  # --quick: largest number of phases of a critical-distance curve
DEFAULT_PHIS = 256  # phases over [0, 2 pi) without [grid] phi


@dataclass(frozen=True)
class CriticalDistanceAnalysis:
    """[analysis] kind = "dcrit": d_crit(phi) of every combination, at the phi values of
    [grid] (default 256 points over [0, 2 pi)), plus x1 - x2 traces at ``traces``."""

    kind: str
    phis: tuple[float, ...]
    traces: tuple[float, ...] = ()
    samples: int = 512


@dataclass(frozen=True)
class ChainCriticalGapsAnalysis:
    """[analysis] kind = "dcrit" on a chain: every stop's critical value for every
    non-impacting product of the bodies' attractors, at the values ``phis`` of the
    parameter ``axis`` ([grid], one parameter by its name; default: the scene's w alone)."""

    kind: str
    axis: str = "w"
    phis: tuple[float, ...] = ()  # the values of ``axis`` (the name ``shrink`` thins)
    samples: int = 512


# a stop's own parameters leave every non-impacting solution as it is: nothing to sweep
STOP_PREFIXES = ("stop.",)


def read(sec, ctx) -> CriticalDistanceAnalysis | ChainCriticalGapsAnalysis:
    if ctx.system.model == CHAIN:
        if sec.has("traces"):
            raise sec.fail("traces", "x1 - x2 traces are a pair's; a chain's result holds "
                                     "each stop's critical value")
        return ChainCriticalGapsAnalysis(
            kind="dcrit", samples=sec.integer("samples", 512, 16, 1_000_000))
    if ctx.system.bodies != 2:
        raise sec.fail("kind", "critical distances need a pair ([system] bodies = 2)")
    raw = sec.raw("traces", [])
    if not isinstance(raw, list):
        raise sec.fail("traces", f"must be a list of phases, got {raw!r}")
    traces = []
    for v in raw:
        try:
            traces.append(parse_multiple(v, "pi", math.pi))
        except ValueError as exc:
            raise sec.fail("traces", str(exc)) from None
    return CriticalDistanceAnalysis(kind="dcrit", phis=(), traces=tuple(traces),
                                    samples=sec.integer("samples", 512, 16, 1_000_000))


def chain_parameters(system):
    """The parameters a chain's critical values can be followed in: all but the stops'."""
    return tuple(p for p in system.parameters if not p.name.startswith(STOP_PREFIXES))


def _chain_sections(analysis, ctx) -> Sections:
    for key in flat_grid(ctx.doc.get("grid", {})):
        if key.startswith(STOP_PREFIXES):
            raise ConfigError(f"{ctx.source}: [grid] {key}: a stop's own parameters do not "
                              "change a non-impacting solution; sweep a body's or w")
    read = read_parameter_axis(ctx.source, ctx.doc, chain_parameters(ctx.system), "dcrit")
    axis, points = read if read else ("w", (float(ctx.values["w"]),))
    catalogue = ctx.read_catalogue()
    return Sections(replace(analysis, axis=axis, phis=tuple(points)), None, None, catalogue)


def sections(analysis, ctx) -> Sections:
    if ctx.system.model == CHAIN:
        return _chain_sections(analysis, ctx)
    grid_doc = ctx.doc.get("grid", {})
    if set(grid_doc) - {"phi"}:
        raise ConfigError(f"{ctx.source}: [grid] {sorted(set(grid_doc) - {'phi'})[0]}: "
                          "critical distances sweep phi only")
    grid = None
    if "phi" in grid_doc:
        grid = read_grid(ctx.source, ctx.doc, ctx.values, ctx.system.bodies, ctx.period,
                         ctx.check_axis)
        phis = grid.axes["phi"]
    else:
        phis = tuple(np.linspace(0.0, 2 * np.pi, DEFAULT_PHIS, endpoint=False).tolist())
    return Sections(replace(analysis, phis=phis), grid, None, ctx.read_catalogue())


def shrink(analysis, grid, axis: int):
    return (replace(analysis, phis=thin(analysis.phis, QUICK_PHIS)), grid,
            f", at most {QUICK_PHIS} phases")


def run(scene, progress=None, **_):
    """d_crit(phi) of every combination, the traces of fig. 5 (b-d), and the catalogue
    (a chain: every stop's critical value of every product, :func:`run_chain`)."""
    a = scene.analysis
    values = dict(scene.values)
    if isinstance(a, ChainCriticalGapsAnalysis):
        return run_chain(scene, progress)
    cat = scene_catalogue(scene)
    tick = progress(len(a.phis)) if progress else None
    ds = critical_distances(scene.system, values, list(cat.attractors), np.array(a.phis),
                            a.samples, tick)
    if a.traces:
        ds = xr.merge([ds, traces(scene.system, values, cat, a.traces, a.samples)],
                      combine_attrs="override")
    return with_catalogue(ds, cat, scene, joints=False)


def run_chain(scene, progress=None):
    """Each stop's critical value of every non-impacting product, along the scene's axis;
    the bodies' attractors are searched from the [catalogue] states at each value."""
    a, c = scene.analysis, scene.catalogue
    tick = progress(len(a.phis)) if progress else None
    ds = chain_critical_gaps(scene.system, dict(scene.values),
                             sample_states(c.box, c.grid, c.random, c.seed), a.axis,
                             a.phis, a.samples, tick)
    ds.attrs["analysis"] = "dcrit"
    ds.attrs["forcing_period"] = forcing_period(scene.values)
    return ds


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    if isinstance(a, ChainCriticalGapsAnalysis):
        return (f"dcrit: every stop's critical value of every non-impacting product at "
                f"{len(a.phis)} values of {a.axis}, {a.samples} samples per joint orbit")
    return (f"dcrit: d_crit of every combination at {len(a.phis)} phases"
            + (f", x1 - x2 traces at {len(a.traces)}" if a.traces else "")
            + f", {a.samples} samples per joint orbit")


def _check_chain(scene, phis: np.ndarray, settings) -> dict[str, np.ndarray]:
    """A chain's critical values at the points ``phis`` of its axis, flows at
    ``settings``: {"stop s: product": values}."""
    a, c = scene.analysis, scene.catalogue
    ds = chain_critical_gaps(scene.system, dict(scene.values),
                             sample_states(c.box, c.grid, c.random, c.seed), a.axis, phis,
                             a.samples, integrator=settings)
    ds.attrs["axis"] = a.axis
    return dcrit_curves(ds)[2]


def check(scene, sample: int, seed: int, result=None) -> dict:
    """``softimpact check``: d_crit at up to 16 random phases of the scene (a chain: values
    of its axis), at its settings and at tightened ones."""
    rng = np.random.default_rng(seed)
    phis = np.sort(rng.choice(np.array(scene.analysis.phis),
                              size=min(sample, 16, len(scene.analysis.phis)), replace=False))
    chain = isinstance(scene.analysis, ChainCriticalGapsAnalysis)
    cat = None if chain else scene_catalogue(scene)
    out = {}
    for key, settings in (("scene", TIGHT), ("tight", tightened(TIGHT))):
        start = time.perf_counter()
        if chain:
            curves = _check_chain(scene, phis, settings)
        else:
            ds = critical_distances(scene.system, dict(scene.values), list(cat.attractors),
                                    phis, scene.analysis.samples, integrator=settings)
            curves = dict(enumerate(ds["d_crit"].values))
        out[key] = (curves, time.perf_counter() - start)
    (scene_curves, _), (tight_curves, _) = out["scene"], out["tight"]
    both = [k for k in scene_curves if k in tight_curves]
    diff = max((float(np.nanmax(np.abs(scene_curves[k] - tight_curves[k])))
                for k in both if np.isfinite(scene_curves[k] - tight_curves[k]).any()),
               default=0.0)
    return {"kind": "d_crit", "sample": int(phis.size), "max_change": diff,
            "wall_s": out["scene"][1], "tight_wall_s": out["tight"][1],
            "wall_ratio": out["tight"][1] / max(out["scene"][1], 1e-12)}


def compare_text(report: dict, max_points: int) -> list[str]:
    return dcrit_comparison_text(report)


def draw(ds, combination=None):
    """``plot.dcrit``, refusing a combination the result does not hold."""
    names = [str(n) for n in ds["combination_label"].values]
    if combination is not None and combination not in names:
        raise ConfigError(f"--combination: {combination!r} is not one of {', '.join(names)}")
    return dcrit(ds, combination=combination)


PLOT = PlotSpec(
    "Critical-distance curves, surviving-combination regions and x1 - x2 traces.",
    draw=f"{__name__}:draw",
    options=(PlotOption("--combination", "combination",
                        "Draw only this combination's x1 - x2 traces (default: all)."),))


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "traces": 'phases at which x1 - x2 over one period is stored, e.g. ["pi/4", "pi"]',
    "samples": "points per period of the stored traces",
}

KINDS = (AnalysisKind("dcrit", "critical distance d_crit(phi) of every combination", read,
                      plan, sections=sections, shrink=shrink, run=run, check=check,
                      compare=compare_dcrit, compare_text=compare_text, progress_unit="phases",
                      keys=KEYS,
                      variables=("d_crit", "combination_label"),
                      plot=PLOT),)
