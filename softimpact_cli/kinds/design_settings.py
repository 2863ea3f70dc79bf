"""[analysis] kind = "design": the keys of a control-design scene, and the --target check.

A design scene names the solution to keep (``target``), the search box (``bounds`` over
d, phi, k_c, c_c; a chain: over any of its parameters by name, ``stop.1.d``, ``phi.2``...)
and the search budget; its basin-stability samples come from [initial_conditions]
(kind = "random") and its labels from [catalogue], as for sweeps.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

from ..analysis.labels import parse_label
from ..config.axes import COUPLING_AXES
from ..config.expressions import parse_multiple
from ..config.limits import MAX_INITIAL_CONDITIONS, MAX_SEED
from ..config.reader import ConfigError, Section
from ..config.sweep import flat_grid

DESIGN_AXES = COUPLING_AXES  # a design searches over the coupling


@dataclass(frozen=True)
class DesignAnalysis:
    """[analysis] kind = "design" (see ``analysis.design`` for the method).

    target : ASCII name of the non-impacting combination to keep (None: --target gives it)
    bounds : {axis: (low, high)} over d, phi (rad), k_c, c_c; low == high fixes the axis
    candidates : points screened; screen_n : samples per screened point (a prefix of the
        [initial_conditions] samples); refine : best screened points rerun with all n
    robust_n : samples per perturbed point (default: all n); perturbation : relative step
        of d, k_c, c_c (phi: the step is perturbation * pi); perturbation_steps : steps on
        each side; min_margin : smallest relative margin a candidate may have
    phi_points : phases of the critical-distance grid over [0, 2 pi) (a pair)
    grid_points : values per body-parameter axis of a chain's region grid (a chain)
    reference : a point to verify beside the pick with the same samples (or None)
    seed : rotation of the candidate set (the samples' seed is in [initial_conditions])
    shock_directions : directions of the minimal fatal shock of the target at the pick and
        the reference (``kinds.fatal_shock``; 4 phases, bisection to 1e-2; 0: not computed)
    """

    kind: str
    target: str | None
    bounds: Mapping[str, tuple[float, float]]
    candidates: int = 48
    screen_n: int = 100
    refine: int = 4
    robust_n: int | None = None
    perturbation: float = 0.02
    perturbation_steps: int = 1
    min_margin: float = 0.02
    phi_points: int = 180
    reference: Mapping[str, float] | None = None
    seed: int = 0
    label_tol: float = 1e-3
    shock_directions: int = 16
    grid_points: int = 12


MAX_REGION_POINTS = 400  # a chain's body grid: one catalogue per point
TARGET_KINDS = ("pair",)  # what a pair's target may be; a chain's adds its own forms
CHAIN_TARGET_KINDS = ("pair", "bodies", "body")


def check_target(name: object, where: str, kinds: tuple[str, ...] = TARGET_KINDS) -> str:
    """The target name if it names a non-impacting solution (a pair's combination; on a
    chain, ``kinds`` = CHAIN_TARGET_KINDS, any product); ConfigError naming ``where``."""
    if not isinstance(name, str):
        raise ConfigError(f"{where}: must be a name like 'L1^1 R1-0^1', got {name!r}")
    try:
        kind = parse_label(name).kind
    except ValueError as exc:
        raise ConfigError(f"{where}: {exc}") from None
    if kind in kinds:
        return name
    if kinds == CHAIN_TARGET_KINDS:
        raise ConfigError(f"{where}: {name!r} is not a non-impacting product; the target "
                          "must be a product of the chain's catalogue like 'B1:P1^1 "
                          "B2:P1-0^1 B3:P1-0^1' (two bodies: 'L1^1 R1-0^1')")
    if kind != "pair":
        what = "an impacting solution" if kind == "impacting" else \
            f"{'an' if kind[0] in 'aeiou' else 'a'} {kind} outcome"
        if kind == "body":
            what = "one body's attractor"
        raise ConfigError(f"{where}: {name!r} is {what}; the target must be a non-impacting "
                          "combination of the pair like 'L1^1 R1-0^1'")
    return name


def _is_phase(key: str) -> bool:
    """A phase axis (in multiples of pi): the pair's phi, a chain's phi.i."""
    return key.split(".")[-1] == "phi" or key.startswith(("phi.", "bounds.phi.",
                                                          "reference.phi."))


def _pair(sec: Section, key: str, raw, check) -> tuple[float, float]:
    ok = isinstance(raw, list) and len(raw) == 2
    if ok:
        try:
            lo, hi = (parse_multiple(v, "pi", math.pi) if _is_phase(key) else
                      _number(v) for v in raw)
        except ValueError:
            ok = False
    if not ok or not lo <= hi:
        raise sec.fail(key, f"must be [low, high] with low <= high, got {raw!r}")
    for v in (lo, hi):
        problem = check(v)
        if problem:
            raise sec.fail(key, f"{problem}, got {raw!r}")
    return lo, hi


def _number(v) -> float:
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise ValueError(v)
    return float(v)


def read_design(sec: Section, values: Mapping, check_axis) -> DesignAnalysis:
    """The design keys of [analysis]; ``check_axis(axis, value)`` returns a problem or None."""
    target = sec.raw("target", None)
    if target is not None:
        target = check_target(target, f"{sec.source}: [analysis] target")
    raw = sec.raw("bounds", None)
    if not isinstance(raw, dict) or not {"d", "phi"} <= set(raw):
        raise sec.fail("bounds", "is required: a table {d = [lo, hi], phi = [lo, hi]} (k_c, "
                                 "c_c optional: fixed at [coupling] when missing)")
    for key in raw:
        if key not in DESIGN_AXES:
            raise sec.fail(f"bounds.{key}", f"unknown axis; allowed: {', '.join(DESIGN_AXES)}")
    bounds = {a: _pair(sec, f"bounds.{a}", raw[a], lambda v, a=a: check_axis(a, v))
              if a in raw else (float(values[a]), float(values[a])) for a in DESIGN_AXES}
    if bounds["d"][0] <= 0:
        raise sec.fail("bounds.d", f"must be above 0 (margins are relative to d), got "
                                   f"{raw['d']!r}")
    if bounds["phi"][1] - bounds["phi"][0] > 2 * math.pi + 1e-12:
        raise sec.fail("bounds.phi", "spans more than 2 pi; phi is an angle")
    reference = None
    ref_raw = sec.raw("reference", None)
    if ref_raw is not None:
        if not isinstance(ref_raw, dict):
            raise sec.fail("reference", f"must be a table like {{d = 5.0, phi = \"pi\"}}, got "
                                        f"{ref_raw!r}")
        reference = {}
        for key in ref_raw:
            if key not in DESIGN_AXES:
                raise sec.fail(f"reference.{key}", f"unknown axis; allowed: "
                                                   f"{', '.join(DESIGN_AXES)}")
        for a in DESIGN_AXES:
            v = ref_raw.get(a, values[a])
            try:
                v = parse_multiple(v, "pi", math.pi) if a == "phi" else _number(v)
            except ValueError:
                raise sec.fail(f"reference.{a}", f"must be a number, got {v!r}") from None
            problem = check_axis(a, v)
            if problem:
                raise sec.fail(f"reference.{a}", f"{problem}, got {v!r}")
            reference[a] = v
    return DesignAnalysis(kind="design", target=target, bounds=bounds, reference=reference,
                          phi_points=sec.integer("phi_points", 180, 8, 100_000),
                          **_budget_keys(sec))


def _budget_keys(sec: Section) -> dict:
    """The keys a pair's and a chain's design share: how many points, samples and
    perturbations the search spends, its margin, seed, label tolerance and shocks."""
    candidates = sec.integer("candidates", 48, 1, 100_000)
    return dict(
        candidates=candidates,
        screen_n=sec.integer("screen_n", 100, 1, MAX_INITIAL_CONDITIONS),
        refine=sec.integer("refine", min(4, candidates), 1, candidates),
        robust_n=(sec.integer("robust_n", 1, 1, MAX_INITIAL_CONDITIONS)
                  if sec.has("robust_n") else None),
        perturbation=sec.number("perturbation", 0.02,
                                lambda v: None if 0 < v < 0.5 else "must be in (0, 0.5)"),
        perturbation_steps=sec.integer("perturbation_steps", 1, 1, 10),
        min_margin=sec.number("min_margin", 0.02,
                              lambda v: None if 0 <= v < 0.5 else "must be in [0, 0.5)"),
        seed=sec.integer("seed", 0, 0, MAX_SEED),
        label_tol=sec.number("label_tol", 1e-3, lambda v: None if v > 0 else "must be > 0"),
        shock_directions=sec.integer("shock_directions", 16, 0, 100_000),
    )


def read_chain_design(sec: Section, system, values: Mapping, check_axis) -> DesignAnalysis:
    """The design keys of [analysis] on a chain: ``bounds`` and ``reference`` over the
    chain's parameters by name (``analysis.chain_design``), ``grid_points`` for its body
    axes; the budget keys as a pair's."""
    if sec.has("phi_points"):
        raise sec.fail("phi_points", "is a pair's phase grid; a chain's region grid takes "
                                     "grid_points values per body-parameter axis")
    target = sec.raw("target", None)
    if target is not None:
        target = check_target(target, f"{sec.source}: [analysis] target", CHAIN_TARGET_KINDS)
    raw = sec.raw("bounds", None)
    allowed = tuple(system.parameter_names)
    example = "{\"stop.1.d\" = [1.0, 4.0], \"phi.2\" = [0.0, \"pi\"]}"
    if not isinstance(raw, dict) or not raw:
        raise sec.fail("bounds", f"is required: a table of the chain's parameters like "
                                 f"{example}")
    raw = flat_grid(raw)
    for key in raw:
        if key not in allowed:
            raise sec.fail(f"bounds.{key}", f"unknown parameter; allowed: {', '.join(allowed)}")
    bounds = {a: _pair(sec, f"bounds.{a}", raw[a], lambda v, a=a: check_axis(a, v))
              for a in raw}
    for a, (lo, hi) in bounds.items():
        if a.startswith("stop.") and a.endswith(".d") and lo <= 0:
            raise sec.fail(f"bounds.{a}", f"must be above 0 (margins are relative to the "
                                          f"gap), got {raw[a]!r}")
        if _is_phase(a) and hi - lo > 2 * math.pi + 1e-12:
            raise sec.fail(f"bounds.{a}", "spans more than 2 pi; a phase is an angle")
    reference = None
    ref_raw = sec.raw("reference", None)
    if ref_raw is not None:
        if not isinstance(ref_raw, dict):
            raise sec.fail("reference", f"must be a table over the bounds' parameters, got "
                                        f"{ref_raw!r}")
        ref_raw = flat_grid(ref_raw)
        for key in ref_raw:
            if key not in bounds:
                raise sec.fail(f"reference.{key}", f"not a design axis; the bounds name: "
                                                   f"{', '.join(bounds)}")
        reference = {}
        for a in bounds:
            v = ref_raw.get(a, values[a])
            try:
                v = parse_multiple(v, "pi", math.pi) if _is_phase(a) else _number(v)
            except ValueError:
                raise sec.fail(f"reference.{a}", f"must be a number, got {v!r}") from None
            problem = check_axis(a, v)
            if problem:
                raise sec.fail(f"reference.{a}", f"{problem}, got {v!r}")
            reference[a] = v
    grid_points = sec.integer("grid_points", 12, 2, MAX_REGION_POINTS)
    body = [a for a in bounds if not a.startswith("stop.") and bounds[a][0] < bounds[a][1]]
    if grid_points ** len(body) > MAX_REGION_POINTS:
        raise sec.fail("grid_points", f"{grid_points}^{len(body)} body grid points (one "
                                      f"catalogue each); at most {MAX_REGION_POINTS}")
    return DesignAnalysis(kind="design", target=target, bounds=bounds, reference=reference,
                          grid_points=grid_points, **_budget_keys(sec))


def with_target(scene, target: str):
    """The scene with its design target replaced by ``target`` (from --target); the stored
    scene text records the override, so its hash differs."""
    if scene.analysis.kind != "design":
        raise ConfigError(f"{scene.source}: --target is for design scenes; kind is "
                          f"{scene.analysis.kind!r}")
    chain = "chain" in scene.system.extra
    name = check_target(target, "--target", CHAIN_TARGET_KINDS if chain else TARGET_KINDS)
    note = f"\n# --target {name!r}\n"
    return replace(scene, analysis=replace(scene.analysis, target=name),
                   text=scene.text + note)
