"""Curves of codimension-one points followed in two parameters, and the codimension-two
points on them.

A curve starts at a point located by one-parameter continuation (a fold, period doubling,
Neimark-Sacker or grazing event, ``analysis/continuation_events.py``) and is followed in
both directions by the one-parameter machinery of ``analysis/continuation.py`` applied to
the augmented map of ``analysis/atlas_augmented.py`` (pseudo-arclength in (y, a, b), the
last component b playing the continued parameter; turns in b are not resolved, a curve
turns freely). A direction ends at the rectangle's edge (the last point placed on it), when
it closes, after ``max_points`` points, or when the corrector fails ("step too small").
A grazing curve is the touching of the orbit's largest maximum of x1 - x2; where another
local maximum becomes the largest the curve has a kink (the corrector stops there), and
it is continued past it by Newton at a value of a just beyond (:func:`_leg`).

Codimension-two points are the zeros, between consecutive points of a curve, of test
functions evaluated on its points, located by the Illinois locator of the events module
(``continuation_events.locate``, each trial corrected on the augmented system):

- on a fold curve: **cusp**, where the curve's direction in the parameter plane reverses
  (the parameter part of the tangent, against the previous point's); **fold-flip**, a
  multiplier through -1 (``psi_PD``);
- on a period-doubling curve: **fold-flip** (``psi_LP``); a **degenerate flip** where the
  normal-form coefficient changes sign;
- on a Neimark-Sacker curve, with ``tau = mu + mu'`` of the critical pair (product 1):
  **1:1 resonance** at tau = 2 and **1:2 resonance** at tau = -2 (beyond them the pair is
  real, a neutral saddle, no NS); **Chenciner**, where the first Lyapunov coefficient
  changes sign;
- on a grazing curve: **grazing-fold**, a multiplier through +1 (``psi_LP``).

Criticality (``analysis/atlas_normal_form.py``) is evaluated at every point of PD and NS
curves: negative coefficients of the normal form mean supercritical for NS, positive
for PD (stored as signed ``criticality``, and ``supercritical`` for both).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .atlas_augmented import AugmentedMap
from .atlas_normal_form import criticality
from .catalogue import orbit_points, same_cycle
from .continuation import Leg, Point, Settings, correct, follow, tangent
from .continuation_events import locate, multiplier_tests

CODIM2_KINDS = ("cusp", "fold-flip", "degenerate flip", "1:1 resonance", "1:2 resonance",
                "Chenciner", "grazing-fold")
MATCH_TOL = 1e-6  # a seed this near (relative, inf-norm) a traced curve lies on it
KINK_STEP = 1e-4  # relative step in a across a kink of a grazing curve
MAX_KINKS = 20  # kinks crossed per direction


@dataclass
class Codim2:
    """A codimension-two point: its kind (CODIM2_KINDS) and the curve point there."""

    kind: str
    point: Point


@dataclass
class Curve:
    """One curve: ``kind`` (atlas_augmented.CURVE_KINDS) of the orbit named ``orbit``
    (period ``periods``), points u = (y, a, b) in order of arclength, why each end stopped,
    its codimension-two points, and the normal-form coefficient at each point (PD, NS;
    NaN otherwise)."""

    kind: str
    orbit: str
    periods: int
    points: list[Point]
    ends: tuple[str, str]
    codim2: list[Codim2] = field(default_factory=list)
    coefficients: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def pairs(self) -> np.ndarray:
        """(m, 2) the (a, b) of each point."""
        return np.array([p.u[-2:] for p in self.points])

    @property
    def multipliers(self) -> np.ndarray:
        """(m, n) complex Floquet multipliers of the orbit at each point."""
        return np.array([p.multipliers for p in self.points])


def stable_beside(kind: str, multipliers: np.ndarray) -> bool:
    """Whether the orbit at a point of a curve of ``kind`` is stable apart from its
    critical multipliers (one nearest +1 or -1, the pair nearest the unit circle for NS;
    none for grazing): it bounds a region where the orbit is stable."""
    mu = np.asarray(multipliers, dtype=complex)
    if kind == "fold":
        mu = np.delete(mu, np.argmin(np.abs(mu - 1.0)))
    elif kind == "period doubling":
        mu = np.delete(mu, np.argmin(np.abs(mu + 1.0)))
    elif kind == "Neimark-Sacker":
        i, j = critical_pair(mu)
        mu = np.delete(mu, [i, j])
    return bool(np.all(np.abs(mu) < 1.0))


def critical_pair(mu: np.ndarray) -> tuple[int, int]:
    """Indices (i < j) of the two multipliers whose product is nearest 1."""
    n = mu.size
    pairs = [(abs(mu[i] * mu[j] - 1.0), i, j) for i in range(n) for j in range(i + 1, n)]
    _, i, j = min(pairs)
    return i, j


def pair_trace(point: Point) -> float:
    """tau = Re(mu_i + mu_j) of the critical pair: 2 cos(theta) on an NS curve."""
    mu = point.multipliers
    i, j = critical_pair(mu)
    return float((mu[i] + mu[j]).real)


def seed(aug: AugmentedMap, u: np.ndarray, tol: float, fixed: int | None = None
         ) -> Point | None:
    """The curve's point near u = (y, a, b) (Newton with component ``fixed`` of u fixed,
    default b: the one-parameter run's fixed parameter), tangent not yet set."""
    aug.border_b = aug.border_c = None
    u = np.asarray(u, dtype=float)
    normal = None
    if fixed is not None:
        normal = np.zeros(u.size)
        normal[fixed] = 1.0
    found = correct(aug, u, normal, tol)
    if found is None:
        return None
    u, value, k = found
    return Point(u, value, np.full(u.size, np.nan), 0.0, k)


def _edge_watch(aug: AugmentedMap, bounds_a: tuple[float, float], tol: float):
    """on_point of a leg: new borders at each point; end at the edge in a (placed on it)."""
    n = aug.dim

    def on_point(leg: Leg) -> str:
        here = leg.points[-1]
        aug.refresh(here.value.monodromy)
        a = here.u[n]
        if bounds_a[0] <= a <= bounds_a[1]:
            return ""
        before = leg.points[-2]
        edge = bounds_a[1] if a > bounds_a[1] else bounds_a[0]
        w = (edge - before.u[n]) / (a - before.u[n])
        guess = (1 - w) * before.u + w * here.u
        guess[n] = edge
        normal = np.zeros(n + 2)
        normal[n] = 1.0
        found = correct(aug, guess, normal, tol)
        if found is not None:
            leg.points[-1] = Point(found[0], found[1], here.tangent, here.step, found[2])
        else:
            leg.points.pop()
        return f"parameter bound {edge:g}"

    return on_point


def _watch(aug: AugmentedMap, bounds_a: tuple[float, float], tol: float, stop=None):
    """The edge watch, then ``stop(leg) -> str`` if given (a non-empty answer ends the leg)."""
    edge = _edge_watch(aug, bounds_a, tol)
    if stop is None:
        return edge

    def on_point(leg: Leg) -> str:
        return edge(leg) or stop(leg)

    return on_point


def _leg(aug: AugmentedMap, first: Point, settings: Settings, bounds_a: tuple[float, float],
         sign: float, stop=None) -> Leg:
    """One direction from ``first`` (its tangent set); a grazing curve is carried across
    the kinks where the orbit's largest maximum of x1 - x2 passes from one local maximum
    to another (there the corrector fails, "step too small"): Newton at a value of a
    KINK_STEP further on, where g is continuous, and on from there. ``stop``: an extra
    on_point test (see ``continuation.follow``)."""
    aug.refresh(first.value.monodromy)
    leg = follow(aug, first, settings, sign, _watch(aug, bounds_a, settings.tol, stop))
    n = aug.dim
    for _ in range(MAX_KINKS):
        if aug.kind != "grazing" or leg.end != "step too small":
            break
        last = leg.points[-1]
        direction = np.sign(last.tangent[n])  # on in a as the curve went
        if direction == 0:
            break
        target = last.u[n] + direction * KINK_STEP * max(1.0, abs(last.u[n]))
        if not bounds_a[0] <= target <= bounds_a[1]:
            break
        guess = last.u.copy()
        guess[n] = target
        normal = np.zeros(n + 2)
        normal[n] = 1.0
        found = correct(aug, guess, normal, settings.tol)
        if found is None:
            break
        u, value, k = found
        t = tangent(value, None)
        if t[n] * direction < 0:
            t = -t
        aug.refresh(value.monodromy)
        more = follow(aug, Point(u, value, t, float(np.linalg.norm(u - last.u)), k), settings,
                      sign, _watch(aug, bounds_a, settings.tol, stop))
        leg = Leg(leg.points + more.points, more.end)
    return leg


def follow_curve(aug: AugmentedMap, first: Point, settings: Settings,
                 bounds_a: tuple[float, float], orbit: str) -> Curve:
    """Both directions from ``first`` (a corrected point), joined in order of arclength."""
    fore = _leg(aug, Point(first.u, first.value, first.tangent, 0.0, first.newton), settings,
                bounds_a, +1.0)
    reverse = -fore.points[0].tangent
    back = _leg(aug, Point(first.u, first.value, reverse, 0.0, first.newton), settings,
                bounds_a, -1.0)
    for p in back.points[1:]:
        p.tangent = -p.tangent
    points = back.points[:0:-1] + fore.points
    curve = Curve(aug.kind, orbit, aug.periods, points, (back.end, fore.end))
    if fore.end == "closed loop":
        curve.points, curve.ends = fore.points, ("closed loop", "closed loop")
    return curve


def on_curve(aug: AugmentedMap, curve: Curve, u: np.ndarray, fixed: int, tol: float) -> bool:
    """Whether u (n + 2,) lies on ``curve``: where the curve crosses u's value of component
    ``fixed`` (a or b), the corrected point's orbit equals u's to MATCH_TOL."""
    n = aug.dim
    scale = max(1.0, float(np.max(np.abs(u))))
    normal = np.zeros(n + 2)
    normal[fixed] = 1.0
    for left, right in zip(curve.points[:-1], curve.points[1:], strict=True):
        x0, x1 = left.u[fixed] - u[fixed], right.u[fixed] - u[fixed]
        if x0 * x1 > 0 or x0 == x1:
            continue
        w = x0 / (x0 - x1)
        guess = (1 - w) * left.u + w * right.u
        guess[fixed] = u[fixed]
        if float(np.max(np.abs(guess - u))) > 0.1 * scale:
            continue
        found = correct(aug, guess, normal, tol)
        if found is None:
            continue
        there = found[0]
        if float(np.max(np.abs(there[n:] - u[n:]))) > MATCH_TOL * scale:
            continue
        if aug.periods == 1:
            if float(np.max(np.abs(there[:n] - u[:n]))) <= MATCH_TOL * scale:
                return True
            continue
        problem = aug.problem(u[n], u[n + 1])
        if same_cycle(orbit_points(problem, there[:n], aug.periods),
                      orbit_points(problem, u[:n], aug.periods), MATCH_TOL * scale):
            return True
    return False


def _passing(u: np.ndarray, fixed: int):
    """A stop test: the leg's last step crossed u's value of component ``fixed`` near u
    (within the same 10% as ``on_curve``'s guess)."""
    scale = max(1.0, float(np.max(np.abs(u))))

    def passed(leg: Leg) -> str:
        if len(leg.points) < 2:
            return ""
        left, right = leg.points[-2].u, leg.points[-1].u
        x0, x1 = left[fixed] - u[fixed], right[fixed] - u[fixed]
        if x0 * x1 > 0 or x0 == x1:
            return ""
        w = x0 / (x0 - x1)
        near = float(np.max(np.abs((1 - w) * left + w * right - u))) <= 0.1 * scale
        return "passed the seed" if near else ""

    return passed


def extend_to(aug: AugmentedMap, curve: Curve, u: np.ndarray, fixed: int, settings: Settings,
              bounds_a: tuple[float, float]) -> bool:
    """Whether u (n + 2,) lies on the continuation of ``curve`` beyond an end that stopped
    at ``max_points``; if so the curve is extended in place through u and on (another
    ``max_points`` at most, its codimension-two points to be recomputed by the caller), so
    that a seed beyond where a curve stopped does not trace the same curve twice.

    From each such end the curve is followed (at most ``max_points`` points) until it
    passes u's value of component ``fixed`` near u; the piece is kept only if u lies on it
    (``on_curve``)."""
    for end in (1, 0):
        if curve.ends[end] != "max points":
            continue
        last = curve.points[-1] if end == 1 else curve.points[0]
        sign = 1.0 if end == 1 else -1.0  # the stored tangents point along the curve
        start = Point(last.u, last.value, sign * last.tangent, 0.0, last.newton)
        piece = _leg(aug, start, settings, bounds_a, sign, _passing(u, fixed))
        probe = Curve(curve.kind, curve.orbit, curve.periods, piece.points, ("", ""))
        if piece.end != "passed the seed" or not on_curve(aug, probe, u, fixed, settings.tol):
            continue
        on = piece.points[-1]
        more = _leg(aug, Point(on.u, on.value, on.tangent, 0.0, on.newton), settings,
                    bounds_a, sign)
        added = piece.points[1:] + more.points[1:]
        if end == 1:
            curve.points = curve.points + added
            curve.ends = (curve.ends[0], more.end)
        else:
            for p in added:
                p.tangent = -p.tangent
            curve.points = added[::-1] + curve.points
            curve.ends = (more.end, curve.ends[1])
        return True
    return False


def _cusp_test(reference: np.ndarray, n: int):
    def test(point: Point) -> float:
        return float(point.tangent[n:] @ reference)

    return test


def codimension_two(aug: AugmentedMap, curve: Curve, tol: float) -> None:
    """Fill ``curve.coefficients`` and ``curve.codim2`` (see the module docstring)."""
    n = aug.dim
    kind = curve.kind
    if kind in ("period doubling", "Neimark-Sacker"):
        curve.coefficients = np.array([_coefficient(aug, p) for p in curve.points])
    else:
        curve.coefficients = np.full(len(curve.points), np.nan)

    tests = []  # (codim-2 kind, test of a point) whose sign changes are located
    if kind == "fold":
        tests += [("fold-flip", lambda p: multiplier_tests(p.multipliers)[1])]
    if kind == "period doubling":
        tests += [("fold-flip", lambda p: multiplier_tests(p.multipliers)[0]),
                  ("degenerate flip", lambda p: _coefficient(aug, p))]
    if kind == "Neimark-Sacker":
        tests += [("1:1 resonance", lambda p: pair_trace(p) - 2.0),
                  ("1:2 resonance", lambda p: pair_trace(p) + 2.0),
                  ("Chenciner", lambda p: _coefficient(aug, p))]
    if kind == "grazing":
        tests += [("grazing-fold", lambda p: multiplier_tests(p.multipliers)[0])]
    values = {name: [test(p) for p in curve.points] for name, test in tests}
    values["Chenciner"] = values["degenerate flip"] = list(curve.coefficients)
    for k, (left, right) in enumerate(zip(curve.points[:-1], curve.points[1:], strict=True)):
        for name, test in tests:
            fa, fb = values[name][k], values[name][k + 1]
            if np.isfinite(fa) and np.isfinite(fb) and fa * fb < 0:
                _add(aug, curve, name, test, left, right, tol)
        if kind == "fold":
            reference = left.tangent[n:]
            if float(right.tangent[n:] @ reference) < 0:
                _add(aug, curve, "cusp", _cusp_test(reference, n), left, right, tol)


def _coefficient(aug: AugmentedMap, point: Point) -> float:
    n = aug.dim
    return criticality(aug.kind, aug.orbit_map(point.u[n], point.u[n + 1]), point.u[:n],
                       point.value.monodromy)


def _add(aug: AugmentedMap, curve: Curve, name: str, test, left: Point, right: Point,
         tol: float) -> None:
    aug.refresh(left.value.monodromy)
    # the arclength from left along its tangent (a joined back leg keeps its own steps)
    right = Point(right.u, right.value, right.tangent,
                  float((right.u - left.u) @ left.tangent), right.newton)
    where = locate(aug, left, right, test, tol)
    if where is None:  # the corrector failed inside the bracket: the nearer end
        where = left if abs(test(left)) <= abs(test(right)) else right
    curve.codim2.append(Codim2(name, where))
