"""[analysis] kind = "continuation": branches of periodic orbits, stable and unstable,
followed in one parameter by pseudo-arclength continuation, with folds, branch points,
period doublings, Neimark-Sacker points and grazing located (``analysis/continuation*.py``).

On a chain (``model = "chain"``) the parameter is any of the chain's by its name (``w``,
``F.2``, ``stop.1.d``, ``phi.3``...), start = "catalogue" follows the chain catalogue's
products that no stop touches (``branches`` names any product) and start = "state" the
orbit a trajectory reaches, impacting or not; grazing is located for each stop."""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..analysis.catalogue import sample_states
from ..analysis.continuation import StepControl
from ..analysis.continuation_branches import continue_starts
from ..analysis.continuation_dataset import continuation_dataset
from ..analysis.continuation_sweep import sweeps
from ..analysis.engine import Problem, classify_state
from ..analysis.shooting import OrbitMap
from ..config.axes import allowed_axes
from ..config.chain_scene import CHAIN
from ..config.reader import ConfigError, positive
from ..kernels.codes import CONVERGED
from ..report.continuation import continuation_info, format_continuation
from ..store.catalogues import build_catalogue, scene_catalogue
from .base import AnalysisKind, PlotSpec, Sections, read_start

STARTS = ("catalogue", "state")
QUICK_POINTS = 60  # --quick: points per direction of a branch
MAX_POINTS = 100_000


@dataclass(frozen=True)
class ContinuationAnalysis(StepControl):
    """[analysis] kind = "continuation".

    parameter : the continued parameter (d, phi, k_c, c_c for a pair; F, w always; any of
        a chain's by name); it starts at the scene's value, which must lie in [low, high]
    start : "catalogue" (every attractor or combination of the [catalogue] search, or
        those named in ``branches``) or "state" (the periodic orbit a trajectory from
        ``state`` at t = 0 converges to)
    step, min_step, max_step : arclength steps in the Euclidean norm of (state, parameter)
    max_points : points per direction of each branch
    tolerance : Newton tolerance on |P^p(y) - y|_inf
    switch_depth : period doublings and branch points switched onto, nested (0: none)
    brute_force_step : the brute-force sweep's parameter step, up and down from each
        start (0: no sweep)
    """

    kind: str
    parameter: str
    low: float
    high: float
    start: str = "catalogue"
    state: tuple[float, ...] | None = None
    branches: tuple[str, ...] = ()
    switch_depth: int = 1
    brute_force_step: float = 0.0


def read(sec, ctx) -> ContinuationAnalysis:
    chain = ctx.system.model == CHAIN
    if chain:  # any of the chain's parameters by its name
        allowed = tuple(p.name for p in ctx.system.parameters)
    else:  # any model parameter the scene has (config.axes: the [grid] axes but t0)
        allowed = tuple(a for a in allowed_axes(ctx.system) if a != "t0" and a in ctx.values)
    parameter = sec.choice("parameter", None, allowed)
    low, high = sec.number("low", None), sec.number("high", None)
    if not low < high:
        raise sec.fail("high", f"must be > low ({low!r}), got {high!r}")
    if chain:
        checked = {p.name: p for p in ctx.system.parameters}[parameter]
        for key, v in (("low", low), ("high", high)):
            problem = checked.check(v)
            if problem:
                raise sec.fail(key, f"{problem} (a value of {parameter}), got {v!r}")
    value = float(ctx.values[parameter])
    if not low <= value <= high:
        raise sec.fail("low", f"the branch starts at the scene's {parameter} = {value!r}, "
                              f"which must lie in [low, high] = [{low!r}, {high!r}]")
    start, state = read_start(sec, ctx.system, STARTS, at=" at t = 0")
    raw = sec.raw("branches", [])
    if not isinstance(raw, list) or not all(isinstance(b, str) for b in raw):
        example = "product names like 'B1:P1^1 B2:P1-0^2 B3:P1-0^1'" if chain else \
            "catalogue names like 'L1^1' or 'L1^1 R1-0^2'"
        raise sec.fail("branches", f"must be a list of {example}, got {raw!r}")
    if raw and start != "catalogue":
        raise sec.fail("branches", "only with start = 'catalogue'")
    step = sec.number("step", 0.02, positive)
    a = ContinuationAnalysis(
        "continuation", parameter, low, high, start, state, tuple(raw), step=step,
        min_step=sec.number("min_step", min(1e-6, step), positive),
        max_step=sec.number("max_step", max(0.2, step), positive),
        max_points=sec.integer("max_points", 400, 2, MAX_POINTS),
        tolerance=sec.number("tolerance", 1e-10, positive),
        switch_depth=sec.integer("switch_depth", 1, 0, 6),
        brute_force_step=sec.number("brute_force_step", 0.0,
                                    lambda v: None if v >= 0 else "must be >= 0"))
    if not a.min_step <= a.step <= a.max_step:
        raise sec.fail("step", f"must lie in [min_step, max_step] = [{a.min_step!r}, "
                               f"{a.max_step!r}], got {a.step!r}")
    if a.brute_force_step and (high - low) / a.brute_force_step > MAX_POINTS:
        raise sec.fail("brute_force_step", f"{(high - low) / a.brute_force_step:.0f} steps; "
                                           f"at most {MAX_POINTS}")
    return a


def sections(analysis, ctx) -> Sections:
    ctx.refuse("grid", "initial_conditions")
    if analysis.start == "state":
        ctx.refuse("catalogue")
        return Sections(analysis)
    return Sections(analysis, catalogue=ctx.read_catalogue())


def shrink(analysis, grid, axis: int):
    bf = analysis.brute_force_step
    span = analysis.high - analysis.low
    return (replace(analysis, max_points=min(analysis.max_points, QUICK_POINTS),
                    brute_force_step=max(bf, span / 40) if bf else 0.0), grid,
            f", at most {QUICK_POINTS} points per direction")


def starts(scene) -> list[tuple[str, object, int]]:
    """(name, state at t = 0, period) of every start of the scene."""
    a = scene.analysis
    if a.start == "state":
        cls = classify_state(Problem(scene.system, scene.values, scene.integrator), a.state)
        if cls.status != CONVERGED:
            raise ConfigError(f"{scene.source}: [analysis] state: the trajectory from it does "
                              f"not converge to a periodic orbit ({cls.outcome}); start "
                              f"closer to one or use start = 'catalogue'")
        return [("orbit from state", cls.orbit[-1], cls.period)]

    if scene.system.model == CHAIN:
        return chain_starts(scene)
    cat = scene_catalogue(scene)
    for name in a.branches:
        if name not in cat.names:
            raise ConfigError(f"{scene.source}: [analysis] branches: {name!r} is not in the "
                              f"catalogue ({', '.join(cat.names)})")
    orbits = cat.orbits
    return [(name, orbit[0], orbit.shape[0]) for name, orbit in orbits.items()
            if not a.branches or name in a.branches]


def chain_starts(scene) -> list[tuple[str, object, int]]:
    """A chain's catalogue starts (``analysis/chain_catalogue.py``, each body searched from
    [catalogue]): the products of its bodies' attractors that no stop touches at the
    scene's values, or the products named in ``branches`` (any of them)."""
    a, c = scene.analysis, scene.catalogue
    cat = build_catalogue(scene.system, dict(scene.values), scene.integrator,
                          sample_states(c.box, c.grid, c.random, c.seed), 0.0, c.match_tol)
    for name in a.branches:
        if name not in cat.names:
            raise ConfigError(f"{scene.source}: [analysis] branches: {name!r} is not a "
                              f"product of the chain's catalogue ({', '.join(cat.names)})")
    chosen = [p for p, alive in zip(cat.products, cat.survives, strict=True)
              if (p.name in a.branches if a.branches else alive)]
    if not chosen:
        raise ConfigError(f"{scene.source}: [catalogue]: no product of the bodies' attractors "
                          f"is apart from every stop at the scene's values (products: "
                          f"{', '.join(cat.names) or 'none'}); name one in [analysis] "
                          "branches or start = 'state'")
    return [(p.name, p.orbit[0], p.orbit.shape[0]) for p in chosen]


def run(scene, progress=None, **_):
    a = scene.analysis
    values = dict(scene.values)
    lam0 = float(values[a.parameter])
    chosen = starts(scene)
    base = OrbitMap(scene.system, values, a.parameter, 1)
    # a chain's branches cross the corners where their section point crosses a stop's
    # surface; the presets' stop there as they did (their results do not move)
    settings = a.settings((a.low, a.high), cross_corners=scene.system.model == CHAIN)
    tick = progress(len(chosen) * (2 if a.brute_force_step else 1)) if progress else None
    branches, fates = continue_starts(base, [(n, s, p) for n, s, p in chosen], lam0, settings,
                                      a.switch_depth, tick)
    if not branches:
        raise ConfigError(f"{scene.source}: [analysis] start: Newton shooting converged at no "
                          f"start ({', '.join(fates)}); loosen tolerance (now "
                          f"{a.tolerance:g}) or start from another orbit")
    brute = []
    if a.brute_force_step:
        brute = sweeps(scene.system, values, scene.integrator, a.parameter,
                       [(n, s) for n, s, _ in chosen], lam0, (a.low, a.high),
                       a.brute_force_step)
        if tick:
            tick(len(chosen))
    ds = continuation_dataset(base, branches, fates, brute, lam0, (a.low, a.high))
    if a.start == "catalogue" and scene.system.model != CHAIN:
        # its order gives each solution the colour of the basins
        ds.attrs["catalogue_names"] = list(scene_catalogue(scene).names)
    return ds


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    what = "every catalogue solution" if a.start == "catalogue" and not a.branches else \
        ", ".join(a.branches) if a.branches else \
        f"the orbit reached from ({', '.join(f'{x:g}' for x in a.state)})"
    brute = f"; brute force every {a.brute_force_step:g}" if a.brute_force_step else ""
    return (f"continuation: {what} in {a.parameter} from {scene.values[a.parameter]:g} "
            f"within [{a.low:g}, {a.high:g}], steps {a.min_step:g}..{a.max_step:g}, at most "
            f"{a.max_points} points per direction, {a.switch_depth} switches (period "
            f"doublings, branch points) deep{brute}")


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "parameter": "the continued parameter (its value in the scene is where the branches "
                 "start; on a chain any of its parameters by name: w, F.2, stop.1.d, phi.3)",
    "low": "the lower end of the continued range",
    "high": "the upper end",
    "start": '"catalogue" (every catalogue orbit, or branches; on a chain its non-impacting '
             'products) or "state" (Newton from state)',
    "state": 'start = "state": a point near the orbit at t = 0: [x1, v1, x2, v2] ([x, v] for one '
             "body)",
    "branches": 'catalogue names of the orbits to follow, like "L1^1" or "L1^1 R1-0^2" (default: '
                'all)',
    "step": "the first arclength step",
    "min_step": "the smallest step before a branch ends",
    "max_step": "the largest step",
    "max_points": "points per branch at most",
    "tolerance": "Newton tolerance of the corrector",
    "switch_depth": "how many generations of branches born at bifurcation points are followed",
    "brute_force_step": "step of a brute-force sweep up and down for comparison (0: off)",
}

KINDS = (AnalysisKind("continuation", "branches of periodic orbits (stable and unstable) "
                      "followed in one parameter; folds, branch points, period doublings, "
                      "Neimark-Sacker and grazing located", read, plan, sections=sections,
                      shrink=shrink,
                      run=run, summary=continuation_info, report=format_continuation,
                      variables=("parameter", "state", "branch_name"),
                      info_after=lambda ds: format_continuation(ds).splitlines(),
                      progress_unit="branches",
                      keys=KEYS,
                      plot=PlotSpec("Branches against the parameter (stable solid, unstable "
                                    "dashed, bifurcations marked, brute-force points "
                                    "overlaid) and their Floquet multipliers.")),)
