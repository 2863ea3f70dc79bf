"""[analysis] kind = "bifurcation": each solution followed along d (or any parameter),
destruction located."""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ..analysis.bifurcation import bifurcation_dataset, d_values
from ..analysis.catalogue import sample_states
from ..analysis.chain_bifurcation import chain_bifurcation_dataset
from ..analysis.chain_dcrit import chain_products
from ..analysis.labels import parse_label
from ..config.axes import allowed_axes
from ..config.chain_scene import CHAIN
from ..config.reader import ConfigError, positive
from ..config.scene import forcing_period
from ..report.compare import bifurcation_comparison_text, compare_bifurcations
from ..store.catalogues import scene_catalogue, with_catalogue
from ..sweep.check import tightened
from .base import AnalysisKind, PlotSpec, Sections

QUICK_STEPS = 50  # --quick: largest number of d steps of a bifurcation diagram
MAX_STEPS = 100_000


@dataclass(frozen=True)
class BifurcationAnalysis:
    """[analysis] kind = "bifurcation": follow solutions as ``parameter`` (d by default;
    any grid axis but t0, ``config.axes``) moves from ``start`` to ``stop`` by ``step``
    (each step from the previous end state); ``branches`` names the solutions to follow
    (default: every solution of the catalogue)."""

    kind: str
    start: float
    stop: float
    step: float
    branches: tuple[str, ...] = ()
    parameter: str = "d"


def _read_range(sec, check, what: str) -> tuple[float, float, float]:
    """``start``, ``stop``, ``step``: each end checked by ``check`` (a problem's text or
    None; ``what`` says what the value is), the ends apart, at most MAX_STEPS steps."""
    start = sec.number("start", None)
    stop = sec.number("stop", None)
    step = sec.number("step", None, positive)
    for key, v in (("start", start), ("stop", stop)):
        problem = check(v)
        if problem:
            raise sec.fail(key, f"{problem} ({what}), got {v!r}")
    if start == stop:
        raise sec.fail("stop", "must differ from start")
    if abs(stop - start) / step > MAX_STEPS:
        raise sec.fail("step", f"{abs(stop - start) / step:.0f} steps; at most {MAX_STEPS}")
    return start, stop, step


def _read_chain(sec, ctx) -> BifurcationAnalysis:
    """A chain: any parameter by its name (default the first stop's gap or wall)."""
    parameters = {p.name: p for p in ctx.system.parameters}
    stop_keys = [n for n in parameters if n.startswith("stop.1.")]
    parameter = sec.choice("parameter", stop_keys[0] if stop_keys else "w", tuple(parameters))
    start, stop, step = _read_range(sec, parameters[parameter].check,
                                    f"a value of {parameter}")
    raw = sec.raw("branches", [])
    if not isinstance(raw, list) or not all(isinstance(b, str) for b in raw):
        raise sec.fail("branches", "must be a list of product names like "
                                   f"'B1:P1^1 B2:P1-0^2 B3:P1-0^1', got {raw!r}")
    return BifurcationAnalysis("bifurcation", start, stop, step, tuple(raw), parameter)


def read(sec, ctx) -> BifurcationAnalysis:
    if ctx.system.model == CHAIN:
        return _read_chain(sec, ctx)
    allowed = tuple(a for a in allowed_axes(ctx.system) if a != "t0" and a in ctx.values)
    if ctx.system.bodies != 2 and not sec.has("parameter"):
        raise sec.fail("kind", "bifurcation along d needs a pair ([system] bodies = 2); one "
                               f"body follows its solutions along parameter = one of "
                               f"{', '.join(allowed)}")
    parameter = sec.choice("parameter", "d", allowed)
    start, stop, step = _read_range(
        sec, lambda v: ctx.check_axis(parameter, v),
        "a distance d" if parameter == "d" else f"a value of {parameter}")
    raw = sec.raw("branches", [])
    if not isinstance(raw, list) or not all(isinstance(b, str) for b in raw):
        raise sec.fail("branches", f"must be a list of names like 'L1^1 R1-0^2', got {raw!r}")
    kind = "pair" if ctx.system.bodies == 2 else "body"
    for b in raw:
        try:
            if parse_label(b).kind != kind:
                raise ValueError(f"{b!r} is not a non-impacting {kind} solution")
        except ValueError as exc:
            raise sec.fail("branches", str(exc)) from None
    return BifurcationAnalysis("bifurcation", start, stop, step, tuple(raw), parameter)


def sections(analysis, ctx) -> Sections:
    ctx.refuse("grid", "initial_conditions")
    return Sections(analysis, catalogue=ctx.read_catalogue())


def shrink(analysis, grid, axis: int):
    span = abs(analysis.stop - analysis.start)
    return (replace(analysis, step=max(analysis.step, span / QUICK_STEPS)), grid,
            f", at most {QUICK_STEPS} steps in {analysis.parameter}")


def run(scene, progress=None, **_):
    """Follow the scene's branches along d (figure 7) or the scene's parameter, with the
    catalogue attached."""
    a = scene.analysis
    values = dict(scene.values)
    if scene.system.model == CHAIN:
        return run_chain(scene, progress)
    cat = scene_catalogue(scene)
    branches = list(a.branches) or list(cat.names)
    for b in branches:
        if b not in cat.names:
            raise ConfigError(f"{scene.source}: [analysis] branches: {b!r} is not in the "
                              f"catalogue ({', '.join(cat.names)})")
    tick = progress(len(branches)) if progress else None
    ds = bifurcation_dataset(scene.system, values, scene.integrator, cat, branches,
                             d_values(a.start, a.stop, a.step), tick, a.parameter)
    return with_catalogue(ds, cat, scene)


def run_chain(scene, progress=None):
    """A chain: its non-impacting products (each body searched from [catalogue]) followed
    along the scene's parameter."""
    a, c = scene.analysis, scene.catalogue
    found = chain_products(scene.system, dict(scene.values),
                           sample_states(c.box, c.grid, c.random, c.seed))
    names = [p.name for p in found]
    for b in a.branches:
        if b not in names:
            raise ConfigError(f"{scene.source}: [analysis] branches: {b!r} is not a "
                              f"non-impacting product of the chain ({', '.join(names)})")
    chosen = [p for p in found if not a.branches or p.name in a.branches]
    tick = progress(len(chosen)) if progress else None
    ds = chain_bifurcation_dataset(scene.system, dict(scene.values), scene.integrator,
                                   chosen, a.parameter, d_values(a.start, a.stop, a.step),
                                   tick)
    ds.attrs["forcing_period"] = forcing_period(scene.values)
    return ds


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    branches = f"{len(a.branches)} branches" if a.branches else \
        "every solution of the catalogue"
    return (f"bifurcation: {branches} x {d_values(a.start, a.stop, a.step).size} steps of "
            f"{a.parameter} from {a.start:g} to {a.stop:g} by {a.step:g}")


def check(scene, sample=None, seed=None, result=None) -> dict:
    """``softimpact check``: the destruction points at the scene's settings and at
    tightened ones with half the step, branch by branch (matched by name)."""
    start = time.perf_counter()
    a = run(scene)
    mid = time.perf_counter()
    b = run(replace(scene, integrator=tightened(scene.integrator),
                                   analysis=replace(scene.analysis,
                                                    step=scene.analysis.step / 2)))
    end = time.perf_counter()
    tight = dict(zip(map(str, b["branch_name"].values), b["destroyed_at"].values,
                     strict=True))
    names = [str(n) for n in a["branch_name"].values]
    da = a["destroyed_at"].values
    db = np.array([tight.get(n, np.nan) for n in names], dtype=float)
    both = np.isfinite(da) & np.isfinite(db)
    changed = np.sum(np.isfinite(da) != np.isfinite(db))
    return {"kind": "destruction points", "sample": int(da.size),
            "max_change": float(np.max(np.abs(da[both] - db[both]))) if both.any() else 0.0,
            "appeared_or_vanished": int(changed), "wall_s": mid - start,
            "tight_wall_s": end - mid, "wall_ratio": (end - mid) / max(mid - start, 1e-12)}


def info_lines(ds) -> list[str]:
    p = str(ds.attrs.get("parameter", "d"))
    if "step" in ds.coords and p not in ds.coords:  # a chain's (dim step)
        d = ds["step"].values
        return [f"{p:28s} {d[0]:.6g} -> {d[-1]:.6g} ({d.size} steps)"]
    if p not in ds.coords:
        return []
    d = ds[p].values
    return [f"{p:28s} {d[0]:.6g} -> {d[-1]:.6g} ({d.size} steps)"]


def compare(a, b, name_a: str, name_b: str) -> dict:
    return compare_bifurcations(a, b)


def compare_text(report: dict, max_points: int) -> list[str]:
    return bifurcation_comparison_text(report)


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "parameter": "the parameter followed (default the gap d; any model or coupling parameter)",
    "start": "the first value of the parameter",
    "stop": "the last value of the parameter",
    "step": "the step in the parameter",
    "branches": 'the solutions followed, by name (default: every non-impacting one)',
}

KINDS = (AnalysisKind("bifurcation", "each solution followed along d (or any parameter), "
                      "destruction points located", read, plan, sections=sections,
                      shrink=shrink, run=run,
                      check=check, info_after=info_lines, compare=compare,
                      keys=KEYS,
                      compare_text=compare_text, progress_unit="branches",
                      variables=("label", "destroyed_at", "branch_name"),
                      plot=PlotSpec("Section displacements of both bodies (one body: "
                                    "displacement and velocity) against the followed "
                                    "parameter, destruction points marked.")),)
