"""Bifurcations and grazing along a branch: test functions, their zeros, branch switching.

With the Floquet multipliers mu_i of a point (eigenvalues of the monodromy M, n of them):

- fold / branch point: ``psi_LP = Re prod (mu_i - 1)`` (= ±det(M - I)); a real multiplier
  through +1. A fold when the parameter component of the tangent turns (the branch turns
  back), else a branch point (another branch crosses: the symmetry-breaking pitchfork of
  a symmetric orbit, or a transcritical crossing; switched onto, see below);
- period doubling: ``psi_PD = Re prod (mu_i + 1)``; a real multiplier through -1;
- Neimark-Sacker: ``psi_NS = Re prod_{i<j} (mu_i mu_j - 1)`` (the bialternate product's
  determinant); zero when a complex pair crosses the unit circle, but also at a "neutral
  saddle" (two real multipliers with product 1), which is not reported;
- a turn of the branch in the parameter, ``t_lam`` (the tangent's parameter component),
  where the fold test kept its sign: on a branch of period p, the point where it meets
  the orbit of period p/2 it doubled from ("doubling origin": seen on P^p, the doubling
  is a pitchfork and det(P^p' - I) touches zero without changing sign), else two folds
  within one step;
- grazing (a pair): ``psi_G = max over the orbit of (x1 - x2) - d``, the orbit touching
  the stop. Signs are compared on the kernels' located maximum; the zero is located on
  the maximum refined by ``critical_distance.locate_maximum`` (root of v1 - v2 on the
  flow, to 1e-12 in time), so the grazing parameter is exact to the integration
  tolerance, as the critical distances are. A chain has one such test per stop, its
  compression's maximum (``continuation_grazing``), and each grazing event names its stop.

Between two consecutive points whose test function differs in sign, the zero is located
by bisection safeguarded with the Illinois secant step on the arclength step sigma from
the left point (each trial point corrected on the hyperplane normal to the left
tangent), until the bracket is below LOCATE_TOL in arclength or |psi| below its floor.
A branch point is located on the chord instead (:func:`locate_branch_point`): there the
corrector's matrix ``[J; t^T]`` is itself singular (J has a two-dimensional null space),
so each trial point is predicted on the chord of the shrinking bracket and corrected on
the hyperplane normal to it, and the point returned is the chord's point at the secant
root of the last bracket that Newton could still resolve (its residual is the chord's
curvature error, ~1e-13 on the shipped cases, and a multiplier is +1 to ~1e-12).

Branch switching at a period doubling of a period-p orbit: the doubled orbit is a fixed
point of P^(2p), which the old orbit also is; at the bifurcation the new branch leaves
along the eigenvector v of M for mu = -1. :func:`doubled_direction` gives the predictor
direction (v, 0) made orthogonal to the old branch's tangent, so the corrector's
hyperplane does not cut the old branch near the bifurcation.

Branch switching at a branch point: the null space of J = [M - I | dG/dlam] is spanned
there by the old branch's tangent t and (v, 0), v the eigenvector of M for mu = +1 (the
null vector of M - I); the crossing branch leaves along (v, 0) made orthogonal to t (for
the pitchfork of a symmetric orbit exactly: v breaks the symmetry, t keeps it).
:func:`switch_at_branch_point` steps along it to either side and corrects on the
hyperplane normal to it, which meets the crossing branch near the predictor and the old
one only a distance ~sqrt(step / curvature) away.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .continuation import MAX_CORRECTION, Point, correct, start_point, tangent
from .continuation_grazing import StopGrazing, kernel_gaps, precise_gap, stop_tests
from .critical_distance import critical_distance
from .shooting import OrbitMap

EVENT_KINDS = ("fold", "branch point", "period doubling", "Neimark-Sacker", "grazing",
               "doubling origin")
HALF_PERIOD_TOL = 1e-3  # a half-period orbit this near (relative) a turn: its origin
LOCATE_TOL = 1e-12  # bracket in arclength
MAX_BISECTIONS = 80
SWITCH_STEPS = (1.0, 0.5, 0.25, 2.0)  # predictor steps tried onto a switched branch
POLISH_STEPS = 3  # Newton steps on a located branch point, singular direction left out
SINGULAR = 1e-6  # relative singular value below which a direction is left out
COMPLEX_TOL = 1e-7  # |Im mu| above this: a complex pair (Neimark-Sacker, not neutral saddle)


@dataclass
class Event:
    """A located bifurcation: its kind (EVENT_KINDS), the point, the index of the
    branch point before it in the leg it was found on, and on a chain the stop (1-based)
    a grazing touches (0: not a chain's grazing)."""

    kind: str
    point: Point
    after: int
    stop: int = 0


def multiplier_tests(multipliers: np.ndarray) -> np.ndarray:
    """(3,) [psi_LP, psi_PD, psi_NS] of (n,) complex multipliers."""
    mu = np.asarray(multipliers, dtype=complex)
    n = mu.size
    pairs = [mu[i] * mu[j] - 1.0 for i in range(n) for j in range(i + 1, n)]
    return np.array([np.prod(mu - 1.0).real, np.prod(mu + 1.0).real,
                     np.prod(pairs).real if pairs else 1.0])


def gap(orbit_map: OrbitMap, point: Point, precise: bool = False) -> float:
    """max over the orbit of x1 - x2, minus d: < 0 apart, >= 0 touching (pairs only)."""
    if not precise:
        return float(point.value.max_g)
    problem = orbit_map.problem(point.parameter)
    top, _ = critical_distance(problem, point.state, orbit_map.periods)
    return top - float(problem.values["d"])


def test_values(orbit_map: OrbitMap, point: Point, chain: bool = False) -> np.ndarray:
    """[psi_LP, psi_PD, psi_NS, psi_G] at a point: (4,) with the pair's psi_G (NaN for one
    body), or for a ``chain`` (3 + n_stops,) with psi_G of each stop."""
    tests = multiplier_tests(point.multipliers)
    if chain:
        return np.concatenate([tests, kernel_gaps(orbit_map, point)])
    g = gap(orbit_map, point) if orbit_map.system.bodies == 2 else np.nan
    return np.append(tests, g)


def _grazing(which) -> bool:
    """Whether test ``which`` is a grazing test (3: the pair's stop; a chain's stop)."""
    return isinstance(which, StopGrazing) or (not callable(which) and which == 3)


def _test(orbit_map: OrbitMap, point: Point, which) -> float:
    if isinstance(which, StopGrazing):
        return precise_gap(orbit_map, point, which)
    if callable(which):  # a test function of the caller's (the atlas's codimension two)
        return float(which(point))
    if which == 3:
        return gap(orbit_map, point, precise=True)
    if which == 4:
        return float(point.tangent[-1])
    return float(multiplier_tests(point.multipliers)[which])



def illinois(fm: float, fa: float, fb: float, side: int) -> tuple[bool, float, float, int]:
    """One Illinois update of a bracket [a, b] with test values (fa, fb) after a trial
    point of value ``fm``: (the trial replaces a (True) or b (False), new fa, new fb,
    new side). The end kept twice in a row has its value halved, so regula falsi does
    not stall on one side."""
    if np.sign(fm) == np.sign(fa):
        return True, fm, fb * 0.5 if side == 1 else fb, 1
    return False, fa * 0.5 if side == -1 else fa, fm, -1

def locate(orbit_map: OrbitMap, left: Point, right: Point, which, tol: float
           ) -> Point | None:
    """The zero of test function ``which`` (0 LP, 1 PD, 2 NS, 3 grazing, 4 turn, a chain's
    ``StopGrazing``, or a callable of a point, floor 1e-12) between two consecutive points
    of a leg (``right`` = the step ``right.step`` from ``left``)."""
    a, b = 0.0, right.step
    fa, fb = _test(orbit_map, left, which), _test(orbit_map, right, which)
    # grazing: the kernel's max and the precise max disagree on the sign change
    if _grazing(which) and np.sign(fa) == np.sign(fb):
        return right if abs(fb) < abs(fa) else left
    best = right if abs(fb) < abs(fa) else left
    side = 0
    floor = 1e-12 if _grazing(which) or callable(which) or which >= 3 else 1e-14
    for _ in range(MAX_BISECTIONS):
        if b - a <= LOCATE_TOL * max(1.0, right.step):
            break
        m = (a * fb - b * fa) / (fb - fa) if fb != fa else 0.5 * (a + b)
        if not a + 0.01 * (b - a) < m < b - 0.01 * (b - a):
            m = 0.5 * (a + b)
        found = correct(orbit_map, left.u + m * left.tangent, left.tangent, tol)
        if found is None:
            return None
        u, value, k = found
        best = Point(u, value, tangent(value, left.tangent), m, k)
        fm = _test(orbit_map, best, which)
        if abs(fm) <= floor:
            break
        left_side, fa, fb, side = illinois(fm, fa, fb, side)
        if left_side:
            a = m
        else:
            b = m
    return best


def half_period(orbit_map: OrbitMap, point: Point, tol: float) -> Point | None:
    """The orbit of half the branch's period p at the point's parameter, when Newton at
    fixed parameter from the point finds one within HALF_PERIOD_TOL (relative): where a
    period-p branch meets the orbit it doubled from. None otherwise (or p odd). Near that
    meeting the tangent is ill-conditioned (two branches cross), so the turn is located
    only roughly and the half-period orbit is solved for instead."""
    p = orbit_map.periods
    if p % 2:
        return None
    found = start_point(orbit_map.with_periods(p // 2), point.state, point.parameter, tol)
    if found is None:
        return None
    scale = max(1.0, float(np.max(np.abs(point.state))))
    if float(np.max(np.abs(found.state - point.state))) > HALF_PERIOD_TOL * scale:
        return None
    value = orbit_map.evaluate(found.state, found.parameter)  # as a fixed point of P^p
    return Point(found.u, value, point.tangent, point.step, found.newton)


def classify(which, located: Point) -> str | None:
    """The name of a sign change of test function ``which`` (1 PD, 2 NS, 3 or a
    ``StopGrazing``: grazing), or
    None when it is no bifurcation of that kind (an NS test zero at a neutral saddle)."""
    if which == 1:
        return "period doubling"
    if which == 2:
        mu = located.multipliers
        n = mu.size
        pairs = [(abs(mu[i] * mu[j] - 1.0), i, j) for i in range(n) for j in range(i + 1, n)]
        _, i, j = min(pairs)
        complex_pair = abs(mu[i].imag) > COMPLEX_TOL and abs(mu[i] - np.conj(mu[j])) < 1e-6
        return "Neimark-Sacker" if complex_pair else None
    return "grazing"


def turn_events(orbit_map: OrbitMap, left: Point, right: Point, fold_sign_changed: bool,
                tol: float) -> list[Event]:
    """The events of a +1 multiplier between two points. The branch turned back in the
    parameter: at the turn (t_lam = 0) the orbit may have half the branch's period (a
    doubling origin), else it is a fold, located on psi_LP when that changed sign (a
    multiplier through +1) and on the turn otherwise (two folds within the step). No
    turn but psi_LP changed sign: a branch point."""
    turned = left.tangent[-1] * right.tangent[-1] < 0
    if turned:
        turn = locate(orbit_map, left, right, 4, tol)
        origin = None if turn is None else half_period(orbit_map, turn, tol)
        if origin is not None:
            return [Event("doubling origin", origin, -1)]
        at = locate(orbit_map, left, right, 0, tol) if fold_sign_changed else turn
        return [] if at is None else [Event("fold", at, -1)]
    if fold_sign_changed:
        return [Event("branch point", locate_branch_point(orbit_map, left, right, tol), -1)]
    return []


def locate_branch_point(orbit_map: OrbitMap, left: Point, right: Point, tol: float) -> Point:
    """The zero of psi_LP between two consecutive points of a leg where the branch does not
    turn (see the module docstring): Illinois-safeguarded bisection on the chord of the
    bracket, each trial corrected on the hyperplane normal to the chord and refused when
    the corrector moves it by more than MAX_CORRECTION times the bracket (it has slid onto
    the crossing branch); the point returned is the chord's point at the secant root of
    the last bracket, evaluated without Newton (singular there), its tangent the chord's."""
    A, B = left, right
    fa, fb = _test(orbit_map, A, 0), _test(orbit_map, B, 0)
    side = 0
    for _ in range(MAX_BISECTIONS):
        chord = B.u - A.u
        length = float(np.linalg.norm(chord))
        if length <= LOCATE_TOL * max(1.0, right.step):
            break
        w = fa / (fa - fb) if fb != fa else 0.5
        if not 0.01 < w < 0.99:
            w = 0.5
        guess = A.u + w * chord
        found = correct(orbit_map, guess, chord / length, tol)
        if found is None or np.linalg.norm(found[0] - guess) > MAX_CORRECTION * length:
            break  # the singular corrector cannot resolve a narrower bracket
        u, value, k = found
        trial = Point(u, value, chord / length, left.step, k)
        fm = _test(orbit_map, trial, 0)
        if abs(fm) <= 1e-14:
            return _on_leg(trial, left, right)
        left_side, fa, fb, side = illinois(fm, fa, fb, side)
        if left_side:
            A = trial
        else:
            B = trial
    chord = B.u - A.u
    w = fa / (fa - fb) if fb != fa else 0.5
    u = A.u + w * chord
    value = orbit_map.evaluate(u[:-1], u[-1])
    if not value.ok:
        return A if abs(fa) <= abs(fb) else B
    normal = chord / np.linalg.norm(chord)
    return _on_leg(_polish(orbit_map, Point(u, value, normal, left.step, 0), tol), left, right)


def _polish(orbit_map: OrbitMap, point: Point, tol: float) -> Point:
    """Newton steps from ``point`` on G = 0 and the hyperplane through it normal to its
    tangent, in the well-conditioned directions only: those of singular values below
    SINGULAR times the largest (at a branch point, the crossing branch's direction) are
    left as they are, so the residual the chord's curvature left is removed without
    sliding along the crossing branch. Stops at ``tol`` or when a step does not help."""
    u, value = point.u, point.value
    for _ in range(POLISH_STEPS):
        residual = float(np.max(np.abs(value.residual)))
        if residual <= tol:
            break
        A = np.vstack([value.jacobian, point.tangent])
        b = np.append(value.residual, point.tangent @ (u - point.u))
        left_vectors, singular, right_vectors = np.linalg.svd(A)
        keep = singular > SINGULAR * singular[0]
        du = right_vectors[keep].T @ ((left_vectors[:, keep].T @ b) / singular[keep])
        trial = orbit_map.evaluate(u[:-1] - du[:-1], u[-1] - du[-1])
        if not trial.ok or float(np.max(np.abs(trial.residual))) >= residual:
            break
        u, value = u - du, trial
    return Point(u, value, point.tangent, point.step, point.newton)


def _on_leg(point: Point, left: Point, right: Point) -> Point:
    """``point`` with the tangent of the leg there (the two ends' tangents interpolated:
    J's null vector is not unique at a branch point) and its arclength from ``left``."""
    s = float(np.clip((point.u - left.u) @ left.tangent / max(right.step, 1e-300), 0.0, 1.0))
    t = (1.0 - s) * left.tangent + s * right.tangent
    return Point(point.u, point.value, t / np.linalg.norm(t),
                 float(np.linalg.norm(point.u - left.u)), point.newton)


def detect(orbit_map: OrbitMap, left: Point, right: Point, tol: float) -> list[Event]:
    """Every event between two consecutive points, located, in the order of arclength
    (on a chain a grazing of each stop, its stop named)."""
    stops = stop_tests(orbit_map, left.parameter)
    chain = bool(stops)
    before = test_values(orbit_map, left, chain)
    after = test_values(orbit_map, right, chain)
    events = turn_events(orbit_map, left, right, np.sign(before[0]) * np.sign(after[0]) < 0,
                         tol)
    # (column of the test values, test): the pair's grazing is column 3, a chain's stop s
    # (its StopGrazing) column 3 + s - 1
    tests = [(1, 1), (2, 2)] + ([(3 + t.surface, t) for t in stops] if chain else [(3, 3)])
    for column, which in tests:
        if not (np.isfinite(before[column]) and np.isfinite(after[column])):
            continue
        if _grazing(which):
            changed = (before[column] >= 0.0) != (after[column] >= 0.0)
        else:
            changed = np.sign(before[column]) * np.sign(after[column]) < 0
        if not changed:
            continue
        located = locate(orbit_map, left, right, which, tol)
        if located is None:
            continue
        kind = classify(which, located)
        if kind is not None:
            stop = which.stop if isinstance(which, StopGrazing) else 0
            events.append(Event(kind, located, -1, stop))
    events.sort(key=lambda e: e.point.step)
    return events


def doubled_direction(point: Point) -> np.ndarray:
    """(n + 1,) unit predictor direction onto the period-doubled branch at a located period
    doubling: the eigenvector of the multiplier nearest -1, lam fixed, made orthogonal to
    the branch's tangent."""
    return crossing_direction(point, -1.0)


def crossing_direction(point: Point, multiplier: float) -> np.ndarray:
    """(n + 1,) unit direction (v, 0) made orthogonal to the branch's tangent, v the
    eigenvector of the multiplier nearest ``multiplier`` (-1 at a period doubling, +1 at a
    branch point); its sign is the eigenvector's as numpy returns it."""
    mu, vectors = np.linalg.eig(point.value.monodromy)
    v = np.real(vectors[:, int(np.argmin(np.abs(mu - multiplier)))])
    d = np.append(v / np.linalg.norm(v), 0.0)
    t = point.tangent
    d = d - (d @ t) * t
    return d / np.linalg.norm(d)


def switch_to_doubled(orbit_map: OrbitMap, point: Point, step: float, tol: float
                      ) -> Point | None:
    """The first point of the doubled branch (a fixed point of P^(2p)) at arclength about
    ``step`` from a located period doubling, its tangent set; None when Newton fails or
    falls back onto the old branch for the steps ``step * SWITCH_STEPS``."""
    doubled = orbit_map.with_periods(2 * orbit_map.periods)
    direction = doubled_direction(point)
    for h in step * np.array(SWITCH_STEPS):
        found = correct(doubled, point.u + h * direction, direction, tol)
        if found is None:
            continue
        u, value, k = found
        status, image, _ = orbit_map.image(u[:-1], u[-1])
        if status == 0 and np.max(np.abs(image - u[:-1])) >= 0.1 * h:  # not the old orbit
            return Point(u, value, tangent(value, direction), h, k)
    return None


def switch_at_branch_point(orbit_map: OrbitMap, point: Point, step: float, tol: float,
                           side: float) -> Point | None:
    """The first point of the branch crossing at a located branch point, on its ``side``
    (+1 or -1 along :func:`crossing_direction`), at arclength about ``step``, its tangent
    set (pointing away from the branch point); None when Newton fails or the corrected
    point is not near its predictor (fallen onto the old branch) for the steps
    ``step * SWITCH_STEPS``."""
    direction = side * crossing_direction(point, 1.0)
    for h in step * np.array(SWITCH_STEPS):
        guess = point.u + h * direction
        found = correct(orbit_map, guess, direction, tol)
        if found is None:
            continue
        u, value, k = found
        if np.linalg.norm(u - guess) <= MAX_CORRECTION * h:
            return Point(u, value, tangent(value, direction), h, k)
    return None
