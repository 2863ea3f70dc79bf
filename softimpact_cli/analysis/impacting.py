"""The identity of impacting periodic orbits: two different ones are two labels.

A trajectory that converges to a periodic orbit touching the stop is named ``impacting
P{p}``. Two different impacting orbits of one period can coexist at one parameter point
(the study's pair at small d, the bilinear pair); they get numbers, in the order their
first trajectory comes in the sweep's flat order: the first keeps the name ``impacting
P{p}`` (and its code, ``IMPACTING_BASE + p``, as before orbits were numbered), the next
ones are ``impacting P{p}^2``, ``impacting P{p}^3``, ... (``labels.impacting_code``).

**Matching.** Orbits are matched by their section points with the shift: two cyclic
sequences of p points are the same orbit when one, rotated, is within ``tol`` of the
other (``catalogue.same_cycle``; ``tol`` relative to max(1, |y|), the catalogue's
matching). An orbit that matches none of the orbits already numbered at its point is
refined, with each of them, by Newton on the p-th stroboscopic map with the saltation
matrix at every switch (the continuation's shooting: ``continuation.start_point``); the
refined orbits are compared again at ``REFINED_TOL``, so a slow transient that stopped
a little off an orbit is not a new orbit, and two orbits apart are confirmed apart. An
orbit Newton cannot refine is not confirmed apart: it takes the number of the nearest
orbit (as every impacting orbit of a period shared one label before).
While a point has one impacting orbit of a period, nothing is refined: its points and
label are those of a sweep that did not number orbits.

**Where.** A chunk numbers the orbits it meets in its own order (:class:`ImpactingOrbits`
in ``sweep.chunks``, so that the recurrence cells remember distinct codes); the parent
renumbers them over the whole result, chunk after chunk in flat order
(:func:`ImpactingOrbits.merge_chunk`): the same numbers for every chunk size, worker
count and resume.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..kernels.codes import BASE_WIDTH, IMPACTING_BASE, NUMBERED_IMPACTING_BASE
from .catalogue import same_cycle
from .continuation import start_point
from .engine import Problem
from .labels import Label, impacting_code, parse_label
from .shooting import OrbitMap

NEWTON_TOL = 1e-10  # residual |P^p(x) - x| of a refined orbit
REFINED_TOL = 1e-6  # two refined orbits closer than this (relative) are one orbit


def cycle_distance(a: np.ndarray, b: np.ndarray) -> float:
    """The least max-norm distance between two cyclic sequences of p points over the
    rotations of one (the shift)."""
    return min(float(np.max(np.abs(np.roll(a, k, axis=0) - b))) for k in range(a.shape[0]))


def impacting_number(code: int) -> tuple[int, int] | None:
    """(period, number) of an impacting orbit's label code (number 1 for the first), or
    None for any other code."""
    code = int(code)
    if IMPACTING_BASE < code < IMPACTING_BASE + BASE_WIDTH:
        return code - IMPACTING_BASE, 1
    number, period = divmod(code - NUMBERED_IMPACTING_BASE, BASE_WIDTH)
    if 2 <= number < BASE_WIDTH and period >= 1:
        return period, number
    return None


def refine(problem: Problem, points: np.ndarray) -> np.ndarray | None:
    """The impacting orbit through ``points`` (p, dim) (time order, from t = 0 mod T)
    refined by Newton on P^p with saltation; its p section points in time order, or None
    when Newton does not converge."""
    period = points.shape[0]
    parameter = problem.system.parameter_names[0]  # held fixed: any parameter serves
    orbit_map = OrbitMap(problem.system, problem.values, parameter, period)
    found = start_point(orbit_map, points[0], float(problem.values[parameter]), NEWTON_TOL)
    if found is None:
        return None
    out = [found.state]
    for _ in range(1, period):
        status, y, _ = orbit_map.with_periods(1).image(out[-1], found.parameter)
        if status != 0:
            return None
        out.append(y)
    return np.array(out)


class _Orbit:
    """One numbered orbit at one point: its section points as met, refined when needed."""

    def __init__(self, points: np.ndarray):
        self.points = points
        self.refined: np.ndarray | None = None
        self.tried = False

    def refine(self, problem: Problem) -> np.ndarray | None:
        if not self.tried:
            self.tried = True
            self.refined = refine(problem, self.points)
        return self.refined


class ImpactingOrbits:
    """The impacting orbits numbered so far, per (grid point, period).

    ``problem_at(point)`` gives the Problem of a grid point (for Newton); ``tol`` the
    relative matching tolerance of orbits as met (the sweep's ``label_tol``)."""

    def __init__(self, problem_at: Callable[[int], Problem], tol: float):
        self.problem_at = problem_at
        self.tol = float(tol)
        self.orbits: dict[tuple[int, int], list[_Orbit]] = {}

    def number(self, point: int, points: np.ndarray) -> int:
        """The number (1, 2, ...) of the impacting orbit through ``points`` (p, dim) at
        grid point ``point``: an orbit numbered before, or the next number."""
        known = self.orbits.setdefault((point, points.shape[0]), [])
        scale = max(1.0, float(np.max(np.abs(points))))
        for i, orbit in enumerate(known):
            if same_cycle(orbit.points, points, self.tol * scale):
                return i + 1
        new = _Orbit(np.asarray(points, dtype=float))
        if known:  # confirm it apart from each numbered orbit, refined
            problem = self.problem_at(point)
            mine = new.refine(problem)
            if mine is None:  # not confirmed apart: the nearest numbered orbit, as before
                return 1 + int(np.argmin([cycle_distance(o.points, points) for o in known]))
            for i, orbit in enumerate(known):
                theirs = orbit.refine(problem)
                if theirs is not None and same_cycle(theirs, mine, REFINED_TOL * scale):
                    return i + 1
        known.append(new)
        return len(known)

    def seed(self, point: int, points: np.ndarray, number: int) -> None:
        """Take a stored orbit as number ``number`` at ``point`` (seed numbers 1, 2, ... of
        one period in order; a number already held is left as it is)."""
        known = self.orbits.setdefault((point, points.shape[0]), [])
        if len(known) == number - 1:
            known.append(_Orbit(np.asarray(points, dtype=float)))

    def points(self, point: int, period: int, number: int) -> np.ndarray:
        """Section points of a numbered orbit: refined when it was (number >= 2 always
        tried), as met otherwise."""
        orbit = self.orbits[(point, period)][number - 1]
        return orbit.refined if orbit.refined is not None else orbit.points

    def label(self, point: int, points: np.ndarray) -> Label:
        """The numbered label of the impacting orbit through ``points`` at ``point``."""
        number = self.number(point, points)
        return Label("impacting", points.shape[0], number if number > 1 else 0)

    def merge_chunk(self, labels: np.ndarray, start: int, n_ic: int, orbits: dict) -> dict:
        """Renumber a chunk's impacting orbits over the result: ``labels`` the chunk's codes
        (flat indices from ``start``; rewritten in place), ``orbits`` its {(grid point,
        code): (flat, points)}; returns them with the result's codes. Call chunk after
        chunk in flat order."""
        remap: dict[tuple[int, int], int] = {}
        out = {}
        for (point, code), (flat, pts) in sorted(orbits.items(), key=lambda kv: kv[1][0]):
            if impacting_number(code) is None:
                out[(point, code)] = (flat, pts)
                continue
            number = self.number(point, pts)
            new = impacting_code(pts.shape[0], number)
            remap[(point, code)] = new
            out[(point, new)] = (flat, self.points(point, pts.shape[0], number)
                                 if number > 1 else pts)
        if any(old != new for (_, old), new in remap.items()):
            points = (start + np.arange(labels.size)) // n_ic
            before = labels.copy()  # all at once: a chunk's 1001 may become 1002001 and
            for (point, old), new in remap.items():  # its 1002001 become 1001
                labels[(points == point) & (before == old)] = new
        return out


def matching_code(points: np.ndarray, candidates: dict[int, np.ndarray], tol: float) -> int:
    """The code among ``candidates`` {impacting code: section points} whose orbit the
    impacting orbit ``points`` is (same period, ``same_cycle`` within tol relative), or
    the first orbit's code of that period when none is (a rerun's own orbit)."""
    scale = max(1.0, float(np.max(np.abs(points))))
    for code, theirs in candidates.items():
        if theirs.shape == points.shape and same_cycle(theirs, points, tol * scale):
            return code
    return impacting_code(points.shape[0])


def is_impacting_name(name: str) -> bool:
    """Whether a label name is an impacting periodic orbit's (numbered or not)."""
    try:
        return parse_label(name).kind == "impacting"
    except ValueError:
        return False
