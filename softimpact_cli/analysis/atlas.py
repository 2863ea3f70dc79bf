"""The two-parameter atlas: every curve of codimension-one points of every orbit followed
from the catalogue, in a rectangle of two parameters (a, b), as one Dataset.

**Seeds.** Each start (a catalogue orbit at the scene's point (a0, b0)) is continued in one
parameter by ``continuation_branches.continue_starts`` (stable and unstable parts, with
the period-doubled branches switched onto, ``switch_depth`` deep): in b at a = a0, in a at
b = b0, and in b again at ``slices`` values of a evenly inside the range, starting there
from every orbit the a-branches cross. Every fold, period doubling, Neimark-Sacker point
and grazing they locate, of a branch of at most ``max_period`` forcing periods, seeds a
curve.

**Curves.** A seed that lies on a curve already traced (same kind and period; checked by
Newton where that curve crosses the seed's fixed parameter, ``atlas_curves.on_curve``) is
skipped; so is a seed beyond the end of such a curve (of the same orbit) that stopped
at ``max_points``: that curve is extended through the seed (``atlas_curves.extend_to``)
and its codimension-two points found again. Otherwise its curve is followed through the
rectangle in both directions (``atlas_curves.follow_curve``), its codimension-two points
and criticality computed (``atlas_curves.codimension_two``).

Dataset dims: ``curve_point`` (every point of every curve, curve after curve, each in
order of arclength), ``curve``, ``codim2``, ``parameter`` (a, b), ``variable`` (the
state), ``multiplier`` (n).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import KW_ONLY, dataclass
from typing import Any

import numpy as np
import xarray as xr

from ..systems import System
from .atlas_augmented import CURVE_KINDS, AugmentedMap
from .atlas_curves import (
    Curve,
    codimension_two,
    extend_to,
    follow_curve,
    on_curve,
    seed,
    stable_beside,
)
from .atlas_normal_form import supercritical
from .continuation import Settings, StepControl
from .continuation_branches import Branch, continue_starts, crossings
from .shooting import OrbitMap


@dataclass(frozen=True)
class AtlasSettings(StepControl):
    """How the atlas is drawn (the ``[analysis]`` keys of ``kinds/atlas.py``).

    parameters : (a, b); ranges : ((a_low, a_high), (b_low, b_high)); step, min_step,
    max_step : arclength steps, in the Euclidean norm of (state, parameters), of the
    one-parameter branches and of the curves; max_points : points per direction of each;
    tolerance : Newton tolerance (|F|_inf); max_period : longest orbit (forcing periods)
    whose curves are followed; slices : extra one-parameter runs in b (see the module
    docstring); switch_depth : period doublings switched onto along the branches
    """

    parameters: tuple[str, str]
    ranges: tuple[tuple[float, float], tuple[float, float]]
    _: KW_ONLY  # StepControl's keys, with the atlas's defaults (min_step as there)
    step: float = 0.05
    max_step: float = 0.3
    max_points: int = 300
    tolerance: float = 1e-9
    max_period: int = 2
    slices: int = 2
    switch_depth: int = 1

    def branch_settings(self, which: int) -> Settings:
        return self.settings(self.ranges[which], min(self.tolerance, 1e-10))

    def curve_settings(self) -> Settings:
        return self.settings(self.ranges[1], resolve_turns=False)


@dataclass
class Seed:
    """A located codimension-one point: kind, orbit name, period, u = (y, a, b) and the
    index in u of the parameter that was fixed where it was found."""

    kind: str
    orbit: str
    periods: int
    u: np.ndarray
    fixed: int


def seeds_of(branches: list[Branch], at: float, free: int, n: int, max_period: int
             ) -> list[Seed]:
    """The curve seeds among the events of branches continued in parameter ``free`` (0 a,
    1 b) with the other fixed at ``at``."""
    out = []
    for branch in branches:
        if branch.periods > max_period:
            continue
        for event in branch.events:
            if event.kind not in CURVE_KINDS:
                continue
            y, lam = event.point.state, event.point.parameter
            pair = (lam, at) if free == 0 else (at, lam)
            out.append(Seed(event.kind, branch.name, branch.periods,
                            np.concatenate([y, pair]), n + 1 - free))
    return out


def find_seeds(system: System, values: Mapping[str, Any], settings: AtlasSettings,
               starts: list[tuple[str, np.ndarray, int]], progress=None) -> list[Seed]:
    """Every seed of the module docstring, in the order found."""
    a, b = settings.parameters
    a0, b0 = float(values[a]), float(values[b])
    n = system.dim
    chosen = [s for s in starts if s[2] <= settings.max_period]
    along_b, _ = continue_starts(OrbitMap(system, values, b, 1), chosen, b0,
                                 settings.branch_settings(1), settings.switch_depth)
    out = seeds_of(along_b, a0, 1, n, settings.max_period)
    if progress is not None:
        progress(1)
    along_a, _ = continue_starts(OrbitMap(system, values, a, 1), chosen, a0,
                                 settings.branch_settings(0), settings.switch_depth)
    out += seeds_of(along_a, b0, 0, n, settings.max_period)
    if progress is not None:
        progress(1)
    low, high = settings.ranges[0]
    for a_k in np.linspace(low, high, settings.slices + 2)[1:-1]:
        sliced = {**values, a: float(a_k)}
        slice_starts = []
        for branch in along_a:
            if branch.periods > settings.max_period:
                continue
            base = OrbitMap(system, {**values, b: b0}, a, branch.periods)
            for j, orbit in enumerate(crossings(base, branch, float(a_k), settings.tolerance)):
                slice_starts.append((f"{branch.name}" + (f" #{j + 1}" if j else ""),
                                     orbit[0], branch.periods))
        branches, _ = continue_starts(OrbitMap(system, sliced, b, 1), slice_starts, b0,
                                      settings.branch_settings(1), settings.switch_depth)
        out += seeds_of(branches, float(a_k), 1, n, settings.max_period)
        if progress is not None:
            progress(1)
    return out


def trace_curves(system: System, values: Mapping[str, Any], settings: AtlasSettings,
                 seeds: list[Seed], progress=None) -> list[Curve]:
    """One curve per distinct seed (see the module docstring), with its codimension-two
    points and criticality."""
    curves: list[Curve] = []
    tol = settings.tolerance
    for s in seeds:
        aug = AugmentedMap(system, values, settings.parameters, s.periods, s.kind)
        known = [c for c in curves if c.kind == s.kind and c.periods == s.periods]
        on_known = any(on_curve(aug, c, s.u, s.fixed, tol) for c in known)
        extended = None if on_known else next(
            (c for c in known if c.orbit == s.orbit and extend_to(
                aug, c, s.u, s.fixed, settings.curve_settings(), settings.ranges[0])), None)
        if extended is not None:
            extended.codim2 = []  # the longer curve's, found again
            codimension_two(aug, extended, tol)
        if not on_known and extended is None:
            first = seed(aug, s.u, tol, s.fixed)
            if first is not None:
                curve = follow_curve(aug, first, settings.curve_settings(),
                                     settings.ranges[0], s.orbit)
                codimension_two(aug, curve, tol)
                curves.append(curve)
        if progress is not None:
            progress(1)
    return curves


def _strings(values) -> np.ndarray:
    return np.array(list(values), dtype=object)


def atlas_dataset(system: System, settings: AtlasSettings, curves: list[Curve],
                  seeds: int) -> xr.Dataset:
    """The atlas as a Dataset (layout: the module docstring)."""
    n = system.dim
    points = [(i, p) for i, c in enumerate(curves) for p in c.points]
    N = len(points)
    first = np.cumsum([0] + [len(c.points) for c in curves])[:-1].astype(np.int64)
    mult = np.array([p.multipliers for _, p in points]).reshape(N, n)
    coefficient = np.concatenate([c.coefficients for c in curves]) if curves else np.zeros(0)
    codim = [(i, c2) for i, c in enumerate(curves) for c2 in c.codim2]
    K = len(codim)
    a, b = settings.parameters
    sup = [supercritical(curves[i].kind, float(x))
           for (i, _), x in zip(points, coefficient, strict=True)]
    data = {
        "pair": (("curve_point", "parameter"), np.array([p.u[-2:] for _, p in points])
                 .reshape(N, 2), {"long_name": f"({a}, {b}) of each curve point"}),
        "state": (("curve_point", "variable"), np.array([p.u[:n] for _, p in points])
                  .reshape(N, n), {"long_name": "fixed point of P^p at t = 0 (mod T)",
                                   "units": "1"}),
        "point_curve": (("curve_point",), np.array([i for i, _ in points], dtype=np.int64)),
        "multiplier_re": (("curve_point", "multiplier"), mult.real,
                          {"long_name": "Floquet multiplier, real part (largest |mu| first)"}),
        "multiplier_im": (("curve_point", "multiplier"), mult.imag,
                          {"long_name": "Floquet multiplier, imaginary part"}),
        "stable_beside": (("curve_point",), np.array(
            [stable_beside(curves[i].kind, p.multipliers) for i, p in points], dtype=np.int8),
            {"long_name": "1: every multiplier but the critical one(s) inside the unit "
                          "circle (grazing: every one)"}),
        "impacting": (("curve_point",), np.array([p.value.max_g >= 0 for _, p in points],
                                                 dtype=np.int8)),
        "coefficient": (("curve_point",), coefficient,
                        {"long_name": "normal-form coefficient: PD c (> 0 supercritical), NS "
                                      "first Lyapunov coefficient d (< 0 supercritical); NaN "
                                      "for folds and grazing"}),
        "supercritical": (("curve_point",), np.array([-1 if s is None else int(s) for s in sup],
                                                     dtype=np.int8),
                          {"long_name": "1 supercritical, 0 subcritical, -1 not applicable"}),
        "curve_kind": (("curve",), _strings(c.kind for c in curves)),
        "curve_orbit": (("curve",), _strings(c.orbit for c in curves)),
        "curve_periods": (("curve",), np.array([c.periods for c in curves], dtype=np.int64),
                          {"units": "forcing periods"}),
        "curve_first": (("curve",), first),
        "curve_size": (("curve",), np.array([len(c.points) for c in curves], dtype=np.int64)),
        "curve_end_first": (("curve",), _strings(c.ends[0] for c in curves)),
        "curve_end_last": (("curve",), _strings(c.ends[1] for c in curves)),
        "codim2_kind": (("codim2",), _strings(c2.kind for _, c2 in codim)),
        "codim2_curve": (("codim2",), np.array([i for i, _ in codim], dtype=np.int64)),
        "codim2_pair": (("codim2", "parameter"), np.array([c2.point.u[-2:] for _, c2 in codim])
                        .reshape(K, 2)),
        "codim2_state": (("codim2", "variable"), np.array([c2.point.u[:n] for _, c2 in codim])
                         .reshape(K, n)),
    }
    coords = {"curve_point": np.arange(N), "curve": np.arange(len(curves)),
              "codim2": np.arange(K), "parameter": [a, b],
              "variable": list(system.state_names), "multiplier": np.arange(n)}
    attrs = {"analysis": "atlas", "atlas_parameters": json.dumps([a, b]),
             "atlas_ranges": json.dumps([list(r) for r in settings.ranges]),
             "model": system.model, "bodies": system.bodies, "seeds": int(seeds),
             "max_period": settings.max_period}
    return xr.Dataset(data, coords=coords, attrs=attrs)
