"""Pseudo-arclength continuation of fixed points of the p-th stroboscopic map.

A branch is a curve u(s) = (y(s), lam(s)) in R^(n+1) of solutions of
``G(y, lam) = P^p_lam(y) - y = 0`` (``analysis/shooting.py``), parametrised by arclength s
in the plain Euclidean norm of (y, lam). From a point u_k with unit tangent t_k
(``J t = 0``, ``J = [M - I | dG/dlam]``, oriented by the previous tangent):

- predictor ``u_pred = u_k + h t_k``;
- corrector: Newton on ``G(u) = 0, t_k . (u - u_pred) = 0``, whose matrix ``[J; t_k^T]``
  is regular at regular points and at folds alike (that is why folds are passed, and the
  unstable orbit between two folds is found);
- corners: where the orbit's section point (its state at t = 0) crosses a stop's contact
  surface the map has a corner and so has the branch (:func:`section_corner`); with
  ``cross_corners`` (chains) the step across it is accepted, else the branch ends there;
- step control: ``h`` grows by GROW after an easy correction (at most EASY Newton steps),
  shrinks by SHRINK after a hard one, and is halved and retried when Newton fails, when
  the tangent turns by more than MAX_TURN radians, the corrector moves the point by more
  than MAX_CORRECTION times the step or the state jumps by more than ``max_step`` (what
  keeps the corrector from hopping onto a neighbouring branch), or when the branch turned
  back in the parameter with no multiplier through +1 (two folds in one step); below
  ``min_step`` the branch ends ("step too small").

A branch ends at the parameter bounds (the last point placed on the bound exactly, by
Newton at fixed lam), after ``max_points`` points, when it comes back to its first point
(a closed loop, such as a bubble of period doublings), or when the integration fails. The
Floquet multipliers (eigenvalues of M) are kept at every point; the test functions and
the location of bifurcations are ``analysis/continuation_events.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .shooting import MapValue, OrbitMap

GROW, SHRINK, EASY, HARD = 1.5, 0.6, 3, 6
MAX_TURN = 0.35  # radians between successive tangents
MAX_NEWTON = 12
RESOLVE = 100  # a silent turn is resolved down to RESOLVE * min_step
MAX_CORRECTION = 0.5  # |corrected - predicted| per unit step: more is a hop to another branch
MAX_CORNER_CORRECTION = 4.0  # the same across a corner (section_corner): tan 76 degrees


@dataclass(frozen=True)
class Settings:
    """How a branch is followed (see the ``[analysis]`` keys of ``kinds/continuation.py``).

    bounds : (low, high) of the parameter; step, min_step, max_step : arclength steps in
    the Euclidean norm of (state, parameter); max_points : points per direction;
    tol : Newton tolerance on |G|_inf (and on the last update); resolve_turns : see
    :func:`silent_turn`
    """

    bounds: tuple[float, float]
    step: float = 0.02
    min_step: float = 1e-6
    max_step: float = 0.2
    max_points: int = 400
    tol: float = 1e-10
    # cut the step where the branch turns back in lam with no multiplier through +1 (two
    # folds in one step); off for the atlas's curves, which turn in either parameter freely
    resolve_turns: bool = True
    # accept a corner of the branch where its section point crosses a contact surface (see
    # :func:`section_corner`); on for chains, off for the presets (their results stay)
    cross_corners: bool = False


@dataclass(frozen=True, kw_only=True)
class StepControl:
    """The step control of a continuation's ``[analysis]`` keys, shared by the kinds that
    follow branches (``kinds/continuation.py``, the atlas's ``AtlasSettings``, which gives
    its own defaults): step, min_step, max_step (arclength, Euclidean norm of (state,
    parameters)), max_points per direction, tolerance (Newton, |G|_inf)."""

    step: float = 0.02
    min_step: float = 1e-6
    max_step: float = 0.2
    max_points: int = 400
    tolerance: float = 1e-10

    def settings(self, bounds: tuple[float, float], tol: float | None = None,
                 resolve_turns: bool = True, cross_corners: bool = False) -> Settings:
        """The ``Settings`` of a branch within ``bounds`` (Newton tolerance ``tol``, else
        ``tolerance``)."""
        return Settings(bounds, self.step, self.min_step, self.max_step, self.max_points,
                        self.tolerance if tol is None else tol, resolve_turns=resolve_turns,
                        cross_corners=cross_corners)


@dataclass
class Point:
    """One solution on a branch: u = (y, lam) (n + 1,), the map there, the unit tangent
    (n + 1,), the arclength step that reached it and the Newton steps it took (and, on a
    chain, its stops' gaps once computed)."""

    u: np.ndarray
    value: MapValue
    tangent: np.ndarray
    step: float = 0.0
    newton: int = 0
    # a chain's (n_stops,) maxima of each stop's compression along the orbit, once asked
    # for (continuation_grazing.kernel_gaps)
    stop_gaps: np.ndarray | None = field(default=None, repr=False)

    @property
    def state(self) -> np.ndarray:
        return self.u[:-1]

    @property
    def parameter(self) -> float:
        return float(self.u[-1])

    @property
    def multipliers(self) -> np.ndarray:
        """(n,) complex Floquet multipliers, largest modulus first."""
        mu = np.linalg.eigvals(self.value.monodromy).astype(complex)
        return mu[np.argsort(-np.abs(mu), kind="stable")]

    @property
    def stable(self) -> bool:
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    @property
    def impacting(self) -> bool:
        return self.value.max_g >= 0.0


@dataclass
class Leg:
    """The points of one direction of a branch, in order of arclength, and why it ended."""

    points: list[Point] = field(default_factory=list)
    end: str = ""


def tangent(value: MapValue, previous: np.ndarray | None, sign: float = 1.0) -> np.ndarray:
    """Unit null vector of J (n, n+1): oriented along ``previous`` when given, else with
    sign(lam component) = ``sign`` (the null vector of the SVD)."""
    J = value.jacobian
    if previous is None:
        t = np.linalg.svd(J)[2][-1]
        if t[-1] * sign < 0 or (t[-1] == 0 and sign < 0):
            t = -t
        return t / np.linalg.norm(t)
    A = np.vstack([J, previous])
    rhs = np.zeros(J.shape[1])
    rhs[-1] = 1.0
    t = np.linalg.solve(A, rhs)
    return t / np.linalg.norm(t)


def correct(orbit_map: OrbitMap, u_pred: np.ndarray, normal: np.ndarray | None, tol: float,
            ) -> tuple[np.ndarray, MapValue, int] | None:
    """Newton on G(u) = 0 with ``normal . (u - u_pred) = 0`` (``normal`` None: lam fixed at
    ``u_pred[-1]``). Returns (u, map value at u, Newton steps) or None when it fails."""
    u = np.array(u_pred, dtype=float)
    n = u.size - 1
    fixed = np.zeros(n + 1)
    fixed[-1] = 1.0
    row = fixed if normal is None else normal
    last = np.inf
    for k in range(MAX_NEWTON):
        value = orbit_map.evaluate(u[:n], u[-1])
        if not value.ok or not np.all(np.isfinite(value.jacobian)):
            return None
        residual = float(np.max(np.abs(value.residual)))
        if residual <= tol and last <= max(tol, 1e-8) * max(1.0, np.max(np.abs(u))):
            return u, value, k
        A = np.vstack([value.jacobian, row])
        b = np.concatenate([value.residual, [row @ (u - u_pred)]])
        try:
            du = np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(du)):
            return None
        u = u - du
        last = float(np.max(np.abs(du)))
    return None


def start_point(orbit_map: OrbitMap, state, lam: float, tol: float) -> Point | None:
    """Newton at fixed lam from ``state``: the first point of a branch (no tangent yet)."""
    u0 = np.append(np.asarray(state, dtype=float), float(lam))
    found = correct(orbit_map, u0, None, tol)
    if found is None:
        return None
    u, value, k = found
    return Point(u, value, np.full(u.size, np.nan), 0.0, k)


def step_from(orbit_map: OrbitMap, point: Point, h: float, tol: float
              ) -> tuple[np.ndarray, MapValue, int] | None:
    """The corrected point at arclength step h along ``point.tangent`` (None: Newton fails)."""
    return correct(orbit_map, point.u + h * point.tangent, point.tangent, tol)


def follow(orbit_map: OrbitMap, first: Point, settings: Settings, sign: float = 1.0,
           on_point=None) -> Leg:
    """Follow the branch from ``first`` (a corrected point) in the direction of growing
    lam (sign +1) or falling lam (-1), or along ``first.tangent`` when it is set.

    on_point(leg) -> str : called after each accepted point; a non-empty answer ends the
    leg with that reason (the events module stops a branch that is lost this way).
    """
    low, high = settings.bounds
    if not np.all(np.isfinite(first.tangent)):
        first.tangent = tangent(first.value, None, sign)
    leg = Leg([first])
    h = settings.step
    while len(leg.points) < settings.max_points:
        here = leg.points[-1]
        found = step_from(orbit_map, here, h, settings.tol)
        accepted = None
        if found is not None:
            u, value, k = found
            t_new = tangent(value, here.tangent)
            turn = np.arccos(np.clip(t_new @ here.tangent, -1.0, 1.0))
            jump = float(np.max(np.abs(u - here.u)))
            moved = float(np.linalg.norm(u - here.u - h * here.tangent))
            corner = settings.cross_corners and moved <= MAX_CORNER_CORRECTION * h and \
                section_corner(orbit_map, here.u, u)
            if (corner or turn <= MAX_TURN and moved <= MAX_CORRECTION * h) and \
                    jump <= max(settings.max_step, 2 * h):
                accepted = Point(u, value, t_new, h, k)
                if settings.resolve_turns and not corner and silent_turn(here, accepted) \
                        and h > RESOLVE * settings.min_step:
                    accepted = None  # two folds within one step: resolve them
        if accepted is None:
            h *= 0.5
            if h < settings.min_step:
                leg.end = "step too small"
                return leg
            continue
        lam = accepted.parameter
        if lam < low or lam > high:
            edge = high if lam > high else low
            ends = bound_point(orbit_map, here, accepted, edge, settings.tol)
            if ends is not None:
                leg.points.append(ends)
                if on_point is not None:
                    on_point(leg)
            leg.end = f"parameter bound {edge:g}"
            return leg
        leg.points.append(accepted)
        if len(leg.points) > 4 and np.linalg.norm(accepted.u - first.u) < h:
            leg.end = "closed loop"  # back at the first point: a loop, traced once
            return leg
        if on_point is not None:
            reason = on_point(leg)
            if reason:
                leg.end = reason
                return leg
        h = min(h * GROW, settings.max_step) if accepted.newton <= EASY else \
            h * SHRINK if accepted.newton >= HARD else h
    leg.end = "max points"
    return leg


def section_corner(orbit_map: OrbitMap, a: np.ndarray, b: np.ndarray) -> bool:
    """Whether the section point (the state at t = 0) crosses a contact surface between
    the branch points ``a`` and ``b`` ((n + 1,) each, at their own parameter values).

    There the stroboscopic map has a corner: from one side the orbit's contact onset (or
    release) falls just after t = 0 and the monodromy holds its saltation matrix S first,
    from the other just before t = T and S comes last (M S^-1 against S M: the same
    multipliers, another matrix), so the branch of fixed points turns abruptly (a tangent
    turning by up to ~75 degrees, the corrector landing up to MAX_CORNER_CORRECTION steps
    off its predictor) and the smooth step control would end it ("step too small")."""
    sides = []
    for u in (a, b):
        surfaces = orbit_map.problem(float(u[-1])).surfaces
        g = surfaces.A @ u[:-1] + surfaces.b
        sides.append([g[i] >= 0.0 for i in surfaces.contact_indices])
    return sides[0] != sides[1]


def silent_turn(left: Point, right: Point) -> bool:
    """Whether the branch turned back in the parameter between two points while
    det(M - I) kept its sign: an odd number of folds must lie between them, so a single
    turn with no multiplier through +1 means at least two folds (a narrow S near a cusp)
    or a jump: the step is cut until they are resolved."""
    def fold_test(point: Point) -> float:
        return float(np.prod(point.multipliers - 1.0).real)

    turned = left.tangent[-1] * right.tangent[-1] < 0
    return bool(turned and fold_test(left) * fold_test(right) > 0)


def bound_point(orbit_map: OrbitMap, before: Point, after: Point, edge: float, tol: float
                ) -> Point | None:
    """The solution at lam = edge between two points of a branch (Newton at fixed lam from
    the linear interpolation), with the tangent oriented as ``after``'s."""
    a, b = before.parameter, after.parameter
    w = (edge - a) / (b - a)
    guess = (1 - w) * before.u + w * after.u
    guess[-1] = edge
    found = correct(orbit_map, guess, None, tol)
    if found is None:
        return None
    u, value, k = found
    return Point(u, value, tangent(value, after.tangent), float(np.linalg.norm(u - before.u)),
                 k)
