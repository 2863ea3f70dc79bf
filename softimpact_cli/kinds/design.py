"""[analysis] kind = "design": (d, phi, k_c, c_c) where only the target solution survives;
on a chain, any of its parameters by name where only the target product survives.

The [analysis] keys are read by ``kinds.design_settings`` (shared with ``design --target``); the
method is ``analysis.design`` (a chain: ``analysis.chain_design``), run through the sweep
executors by ``sweep.design`` (``sweep.chain_design``).
"""

from __future__ import annotations

import math
from dataclasses import replace

from ..config.chain_scene import CHAIN
from ..config.limits import MAX_TRAJECTORIES, design_trajectories
from ..config.reader import ConfigError
from ..config.sweep import read_initial_conditions
from ..report.info import design_summary, format_design
from ..report.outcomes import design_counts
from ..sweep.chain_design import run_chain_design
from ..sweep.design import run_design
from .base import AnalysisKind, PlotSpec, Sections
from .design_settings import read_chain_design, read_design
from .fatal_shock import FatalShockAnalysis
from .fatal_shock import run as fatal_shock_run


def read(sec, ctx):
    if ctx.system.model == CHAIN:
        return read_chain_design(sec, ctx.system, ctx.values, ctx.check_axis)
    if ctx.system.bodies != 2:
        raise sec.fail("kind", "a design needs a pair ([system] bodies = 2)")
    return read_design(sec, ctx.values, ctx.check_axis)


def sections(analysis, ctx) -> Sections:
    source, doc = ctx.source, ctx.doc
    if "grid" in doc:
        raise ConfigError(f"{source}: [grid]: not used by kind 'design' (its search box "
                          "is [analysis] bounds)")
    if "initial_conditions" not in doc:
        raise ConfigError(f"{source}: [initial_conditions]: is required for a design "
                          "(kind = \"random\", box, n, seed: the basin-stability samples)")
    ic_kind = doc["initial_conditions"].get("kind", "plane")
    if ic_kind != "random":
        raise ConfigError(f"{source}: [initial_conditions] kind: a design's basin "
                          f"stability needs kind = \"random\", got {ic_kind!r}")
    # a chain's design may move w: one start time would be another phase at each point
    w_moves = "w" in analysis.bounds and ctx.system.model == CHAIN
    initial = read_initial_conditions(source, doc, ctx.system.state_names, ctx.period,
                                      False, w_swept=w_moves)
    for key in ("screen_n", "robust_n"):
        if (getattr(analysis, key) or 0) > initial.count:
            raise ConfigError(f"{source}: [analysis] {key}: must be <= [initial_conditions]"
                              f" n = {initial.count}, got {getattr(analysis, key)}")
    total = design_trajectories(analysis, initial.count)
    if total > MAX_TRAJECTORIES:
        raise ConfigError(f"{source}: [analysis]/[initial_conditions]: the design runs up "
                          f"to {total} trajectories (candidates x screen_n + refine x n + "
                          f"perturbed points x robust_n + n); at most {MAX_TRAJECTORIES}")
    return Sections(analysis, None, initial, ctx.read_catalogue())


def run(scene, progress=None, workers=None, scheduler=None, echo=None, **_):
    options = {} if echo is None else {"echo": echo}
    runner = run_chain_design if scene.system.model == CHAIN else run_design
    ds = runner(scene, workers=workers, scheduler=scheduler, progress=progress, **options)
    if scene.analysis.shock_directions > 0:
        ds.attrs.update(fatal_shocks(scene, ds, workers))
    return ds


SHOCK_PHASES, SHOCK_SCAN, SHOCK_TOL = 4, 16, 1e-2  # a second robustness measure, kept cheap

# --quick: at most this many candidates screened, best ones refined, samples per screened
# or perturbed point, and fatal-shock directions (every stage still runs; the catalogue,
# the region and the samples stay)
QUICK_CANDIDATES, QUICK_REFINE, QUICK_POINT_SAMPLES, QUICK_SHOCK_DIRECTIONS = 6, 2, 50, 4


def shrink(analysis, grid, axis: int):
    """--quick: fewer candidates, refined points, samples per point and fatal-shock
    directions."""
    a = analysis
    robust_n = min(a.robust_n, QUICK_POINT_SAMPLES) if a.robust_n else a.robust_n
    return (replace(a, candidates=min(a.candidates, QUICK_CANDIDATES),
                    refine=min(a.refine, QUICK_REFINE),
                    screen_n=min(a.screen_n, QUICK_POINT_SAMPLES), robust_n=robust_n,
                    shock_directions=min(a.shock_directions, QUICK_SHOCK_DIRECTIONS)), grid,
            f", at most {QUICK_CANDIDATES} candidates on {QUICK_POINT_SAMPLES} samples, "
            f"{QUICK_REFINE} refined, {QUICK_SHOCK_DIRECTIONS} fatal-shock directions")


def fatal_shocks(scene, ds, workers=None) -> dict:
    """The minimal fatal shock of the target at the pick and at the reference point
    (``fatal_shock_<role>*`` attributes; an upper bound, see ``analysis.fatal_shock``),
    over the design's sampled box: shocks up to half its diagonal."""
    a, box = scene.analysis, scene.initial_conditions.box
    max_shock = 0.5 * math.sqrt(sum((hi - lo) ** 2 for lo, hi in box.values()))
    settings = FatalShockAnalysis("fatal_shock", a.target, SHOCK_PHASES, a.shock_directions,
                                  max_shock, SHOCK_SCAN, SHOCK_TOL, a.seed)
    summary = design_summary(ds)
    out = {"fatal_shock_settings": f"{SHOCK_PHASES} phases x {a.shock_directions} "
                                   f"directions, {SHOCK_SCAN} magnitudes up to "
                                   f"{max_shock:g}, bisection to {SHOCK_TOL:g}"}
    for role in ("best", "reference"):
        point = summary[role]
        if point is None:
            continue
        if not point["target_exists"]:
            out[f"fatal_shock_{role}"] = float("nan")
            continue
        values = {**scene.values, **{k: point[k] for k in a.bounds}}
        shock = fatal_shock_run(replace(scene, values=values, analysis=settings),
                                workers=workers)
        out[f"fatal_shock_{role}"] = float(shock.attrs["mfs"])
        if math.isfinite(shock.attrs["mfs"]):
            out[f"fatal_shock_{role}_time"] = float(shock.attrs["mfs_time"])
            out[f"fatal_shock_{role}_destination"] = str(shock.attrs["mfs_destination"])
    return out


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    free = len(a.bounds)  # each design axis is moved by +-perturbation_steps
    if scene.system.model == CHAIN:
        body = [x for x in a.bounds if not x.startswith("stop.") and a.bounds[x][0] <
                a.bounds[x][1]]
        region = (f"the chain's catalogue at {a.grid_points ** len(body)} body grid points"
                  + (f" ({', '.join(body)})" if body else ""))
    else:
        region = f"d_crit over {a.phi_points} phases"
    return (f"design: target {a.target or '(give --target)'}; {a.candidates} candidates "
            f"screened on {a.screen_n} samples, the best {a.refine} rerun on "
            f"{scene.initial_conditions.count}; {2 * a.perturbation_steps * free} perturbed "
            f"points on {a.robust_n or scene.initial_conditions.count} samples; {region}")


def info_lines(ds) -> list[str]:
    return [format_design(ds)]



# what each [analysis] key means (the scene-key reference)
KEYS = {
    "target": 'the solution that should survive alone (or --target); a non-impacting combination '
              '(a chain: a product of its catalogue)',
    "bounds": '{d = [lo, hi], phi = [lo, hi], k_c = [lo, hi], c_c = [lo, hi]}; k_c, c_c left out: '
              'fixed at [coupling]; lo = hi fixes. A chain: any of its parameters by name, '
              '{"stop.1.d" = [lo, hi], "phi.2" = [lo, hi], ...}',
    "candidates": "points screened inside the region",
    "screen_n": "samples per screened point (the first of [initial_conditions] n)",
    "refine": "best screened points verified on all n samples",
    "robust_n": "samples per perturbed point (default: n)",
    "perturbation": "robustness steps: +- this relative change of d, k_c, c_c; +- this times pi "
                    "of phi",
    "perturbation_steps": "perturbation steps on each side",
    "min_margin": "every candidate tolerates at least this relative change",
    "phi_points": "critical-distance grid over [0, 2 pi) (a pair)",
    "grid_points": "a chain: values per body-parameter axis of the region grid (one catalogue "
                   "per grid point)",
    "reference": 'a point verified beside the pick, e.g. {d = 5.0, phi = "pi", k_c = 8.0, c_c = '
                 '10.0}',
    "seed": "rotates the candidate set",
    "label_tol": "a trajectory whose section points lie this close to a catalogue orbit takes its "
                 "label",
    "shock_directions": "directions of the minimal fatal shock at the pick and the reference (0: "
                        "off)",
}

KINDS = (AnalysisKind("design", "(d, phi, k_c, c_c) where only the target survives (a chain: "
                      "any of its parameters)", read, plan, sections=sections, shrink=shrink,
                      run=run,
                      summary=design_summary,
                      report=format_design, info_lines=info_lines, info_catalogue=False,
                      outcome_counts=design_counts, progress_unit="trajectories",
                      variables=("score", "share"),
                      options=("workers", "scheduler", "echo"),
                      keys=KEYS,
                      plot=PlotSpec("The (d, phi) plane with the target-only region, the "
                                    "pick and runners-up, beside the basin stability at "
                                    "the pick and under perturbations.")),)
