"""[analysis] kind = "atlas": the two-parameter atlas, every fold, period-doubling,
Neimark-Sacker and grazing curve of the catalogue's orbits (stable and unstable) in a
rectangle of two parameters, with their codimension-two points and criticality
(``analysis/atlas*.py``)."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from pathlib import Path

from ..analysis.atlas import AtlasSettings, atlas_dataset, find_seeds, trace_curves
from ..config.axes import allowed_axes
from ..config.expressions import parse_multiple
from ..config.reader import ConfigError, positive
from ..config.sweep import read_catalogue
from ..plot.atlas_figure import draw_atlas
from ..report.atlas import atlas_info, format_atlas
from ..store.catalogues import scene_catalogue
from ..store.h5netcdf_ import open_result
from .base import AnalysisKind, PlotOption, PlotSpec, Sections

QUICK_POINTS = 40  # --quick: points per direction of a branch or curve
MAX_POINTS = 100_000


@dataclass(frozen=True)
class AtlasAnalysis:
    """[analysis] kind = "atlas": :class:`analysis.atlas.AtlasSettings` as read."""

    kind: str
    settings: AtlasSettings


def _range(sec, name: str, raw) -> tuple[float, float]:
    if not isinstance(raw, list) or len(raw) != 2:
        raise sec.fail("ranges", f"{name} must be [low, high], got {raw!r}")
    try:
        low, high = (parse_multiple(v, "pi", math.pi) for v in raw)
    except ValueError as exc:
        raise sec.fail("ranges", f"{name}: {exc}") from None
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise sec.fail("ranges", f"{name} must be [low, high] with low < high, got {raw!r}")
    return low, high


def read(sec, ctx) -> AtlasAnalysis:
    # any model parameter the scene has (the model's own names, not a fixed list)
    allowed = tuple(a for a in allowed_axes(ctx.system) if a != "t0" and a in ctx.values)
    raw = sec.raw("parameters")
    if not isinstance(raw, list) or len(raw) != 2 or not all(isinstance(p, str) for p in raw):
        raise sec.fail("parameters", f"must be two parameter names like [\"phi\", \"d\"], "
                                     f"got {raw!r}")
    for p in raw:
        if p not in allowed:
            raise sec.fail("parameters", f"{p!r} is not a parameter of the model "
                                         f"(allowed: {', '.join(allowed)})")
    if raw[0] == raw[1]:
        raise sec.fail("parameters", f"the two parameters must differ, got {raw!r}")
    ranges_raw = sec.raw("ranges")
    if not isinstance(ranges_raw, dict) or set(ranges_raw) != set(raw):
        raise sec.fail("ranges", f"must give [low, high] for exactly {raw[0]} and {raw[1]}, "
                                 f"like {{ {raw[0]} = [0.0, 1.0], {raw[1]} = [0.0, 1.0] }}, "
                                 f"got {ranges_raw!r}")
    ranges = tuple(_range(sec, p, ranges_raw[p]) for p in raw)
    for p, (low, high) in zip(raw, ranges, strict=True):
        value = float(ctx.values[p])
        if not low <= value <= high:
            raise sec.fail("ranges", f"the rectangle holds no catalogue orbit: the catalogue "
                                     f"is searched at the scene's {p} = {value!r}, outside "
                                     f"[{low!r}, {high!r}]")
    step = sec.number("step", 0.05, positive)
    settings = AtlasSettings(
        (raw[0], raw[1]), ranges, step=step,
        min_step=sec.number("min_step", min(1e-6, step), positive),
        max_step=sec.number("max_step", max(0.3, step), positive),
        max_points=sec.integer("max_points", 300, 2, MAX_POINTS),
        tolerance=sec.number("tolerance", 1e-9, positive),
        max_period=sec.integer("max_period", 2, 1, 16),
        slices=sec.integer("slices", 2, 0, 64),
        switch_depth=sec.integer("switch_depth", 1, 0, 4))
    if not settings.min_step <= settings.step <= settings.max_step:
        raise sec.fail("step", f"must lie in [min_step, max_step] = [{settings.min_step!r}, "
                               f"{settings.max_step!r}], got {step!r}")
    return AtlasAnalysis("atlas", settings)


def sections(analysis, ctx) -> Sections:
    ctx.refuse("grid", "initial_conditions")
    return Sections(analysis, catalogue=read_catalogue(ctx.source, ctx.doc,
                                                       ctx.system.extra["catalogue_box"]))


def shrink(analysis, grid, axis: int):
    s = analysis.settings
    return (replace(analysis, settings=replace(s, max_points=min(s.max_points, QUICK_POINTS),
                                               slices=min(s.slices, 1))), grid,
            f", at most {QUICK_POINTS} points per direction, at most one slice")


def run(scene, progress=None, **_):
    s = scene.analysis.settings
    values = dict(scene.values)
    cat = scene_catalogue(scene)
    starts = [(name, orbit[0], orbit.shape[0]) for name, orbit in cat.orbits.items()
              if orbit.shape[0] <= s.max_period]
    if not starts:
        raise ConfigError(f"{scene.source}: [analysis] ranges: the rectangle holds no "
                          f"catalogue orbit of at most max_period = {s.max_period} periods "
                          f"(the catalogue has {len(cat.names)}: {', '.join(cat.names)})")
    tick = progress(2 + s.slices) if progress else None
    seeds = find_seeds(scene.system, values, s, starts, tick)
    # a second count: one per seed (traced, or found on a curve already traced)
    curves = trace_curves(scene.system, values, s, seeds,
                          progress(len(seeds)) if progress else None)
    ds = atlas_dataset(scene.system, s, curves, len(seeds))
    ds.attrs["catalogue_names"] = list(cat.names)
    return ds


def plan(scene, workers=None, chunk_size=None) -> str:
    s = scene.analysis.settings
    (a, b), ((a0, a1), (b0, b1)) = s.parameters, s.ranges
    return (f"atlas: fold, period-doubling, Neimark-Sacker and grazing curves of every "
            f"catalogue orbit of at most {s.max_period} periods in {a} [{a0:g}, {a1:g}] x "
            f"{b} [{b0:g}, {b1:g}], seeded by continuation in {b}, in {a} and in {b} at "
            f"{s.slices} more {a} values; steps {s.min_step:g}..{s.max_step:g}, at most "
            f"{s.max_points} points per direction")


KEYS = {
    "parameters": 'the two parameters of the plane, like ["phi", "d"] (any of the model\'s)',
    "ranges": "the rectangle: [low, high] of each parameter (numbers or \"a*pi/b\"); it "
              "must hold the scene's point, where the catalogue is searched",
    "step": "the first arclength step of branches and curves",
    "min_step": "the smallest step before a branch or curve ends",
    "max_step": "the largest step",
    "max_points": "points per direction of each branch and curve at most",
    "tolerance": "Newton tolerance of the curves' corrector",
    "max_period": "the longest orbit (forcing periods) whose curves are followed",
    "slices": "one-parameter runs in the second parameter at that many values of the first, "
              "besides the scene's (more seeds)",
    "switch_depth": "period doublings switched onto along the seeding branches",
}



def _over(path: str, ds):
    """The map or dcrit result at ``path`` after checking it covers the atlas's plane:
    ConfigError naming --over otherwise."""
    if not Path(path).is_file():
        raise ConfigError(f"--over: {path}: no such file")
    over = open_result(path)
    a, b = json.loads(ds.attrs["atlas_parameters"])
    kind = over.attrs.get("analysis")
    if kind == "dcrit":
        if {a, b} != {"phi", "d"}:
            raise ConfigError(f"--over: {path} is a dcrit result (d_crit over phi); the atlas "
                              f"is in ({a}, {b}), not (phi, d)")
        return over
    if kind != "map":
        raise ConfigError(f"--over: {path} is a {kind!r} result; a map or dcrit result is "
                          f"expected")
    swept = {name for name, size in over.sizes.items() if size > 1 and name in over.coords}
    if not {a, b} <= swept:
        raise ConfigError(f"--over: {path} is a map over {', '.join(sorted(swept))}; the "
                          f"atlas is in ({a}, {b})")
    return over


def draw(ds, over=None):
    """``plot.atlas``, over a map or dcrit result (``--over``) when given."""
    return draw_atlas(ds, None if over is None else _over(over, ds))


KINDS = (AnalysisKind("atlas", "fold, period-doubling, Neimark-Sacker and grazing curves of "
                      "every catalogue orbit in two parameters, with codimension-two points",
                      read, plan, sections=sections, shrink=shrink, run=run,
                      summary=atlas_info, report=format_atlas,
                      info_after=lambda ds: format_atlas(ds).splitlines(),
                      progress_unit="runs (seeding, then one per seed)", keys=KEYS,
                      variables=("pair", "curve_kind", "codim2_kind"),
                      plot=PlotSpec("The curves in the parameter plane (fold, PD, NS, grazing; "
                                    "solid where the orbit is stable beside its critical "
                                    "multipliers, criticality marked), codimension-two points, "
                                    "optionally over a map or dcrit result of the rectangle.",
                                    draw=f"{__name__}:draw",
                                    options=(PlotOption("--over", "over",
                                                        "A map or dcrit result (.h5) of the "
                                                        "same rectangle to draw under the "
                                                        "curves."),))),)
