"""Whole branches: both directions from a start, events along them, switching at period
doublings and branch points, and one branch traced once however many starts lie on it.

:func:`trace` follows a start point in both directions (``analysis/continuation.py``),
locating the events between consecutive points (``analysis/continuation_events.py``).
:func:`continue_starts` does that for every start (catalogue orbits or a converged
trajectory), skipping a start that lies on a branch already traced (its orbit equals,
to MATCH_TOL, the point where that branch crosses the start's parameter value), and
switches onto the doubled branch at each period doubling and onto both sides of the
crossing branch at each branch point, ``switch_depth`` switches deep.

A switched branch ends where it meets a branch point already located (a fold or branch
point found within MEET_TOL of it): the two symmetry-broken orbits born at one pitchfork
of a symmetric orbit and dying at the next are each traced once, from the first to the
second, and a side of a branch point where a traced branch already arrives is not
switched onto again.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .catalogue import orbit_points, same_cycle
from .continuation import Leg, Point, Settings, bound_point, follow, start_point
from .continuation_events import (
    Event,
    crossing_direction,
    detect,
    switch_at_branch_point,
    switch_to_doubled,
)
from .shooting import OrbitMap

MATCH_TOL = 1e-6  # two orbits at one parameter value within this (inf-norm): the same
# a turn or +1 crossing on a switched branch this near (relative, inf-norm) a located
# branch point: the branch point itself (a turn is located only roughly, being singular)
MEET_TOL = 1e-3


@dataclass
class Branch:
    """One branch: points in order of arclength, located events, why each end stopped.

    periods : forcing periods of its orbits (the map is P^periods); parent : index of the
    branch it was switched from at a period doubling or branch point (-1: a start); start :
    index of its start point in ``points``
    """

    name: str
    periods: int
    points: list[Point]
    events: list[Event]
    ends: tuple[str, str]
    parent: int = -1
    start: int = 0
    crossings: list[np.ndarray] = field(default_factory=list)  # orbits (p, n) at lam0


def _watch(orbit_map: OrbitMap, events: list[Event], tol: float, offset_sign: int,
           meets: tuple[tuple[str, Event], ...] = ()):
    """The ``on_point`` callback of a leg: locate events between its last two points.
    ``meets``: (branch name, branch point) where the leg ends when it reaches one."""

    def on_point(leg: Leg) -> str:
        left, right = leg.points[-2], leg.points[-1]
        for event in detect(orbit_map, left, right, tol):
            met = _met(event, meets) if event.kind in ("fold", "branch point") else None
            if met is not None:  # back on a branch it crosses: the rest is traced there
                owner, known = met
                leg.points[-1] = Point(known.point.u, known.point.value, right.tangent,
                                       right.step, 0)
                return f"meets {owner} at a branch point"
            if any(same_event(event, e) for e in events):
                continue  # a test function flickering in its last digits at one zero
            event.after = offset_sign * (len(leg.points) - 2)
            events.append(event)
            if event.kind == "doubling origin":  # beyond it: the same orbit, shifted by p/2
                leg.points[-1] = event.point
                return "meets the orbit it doubled from"
        return ""

    return on_point


def _met(event: Event, meets: tuple[tuple[str, Event], ...]) -> tuple[str, Event] | None:
    """The (branch name, branch point) of ``meets`` that ``event`` lies at, if any."""
    for owner, known in meets:
        scale = max(1.0, float(np.max(np.abs(known.point.u))))
        if float(np.max(np.abs(event.point.u - known.point.u))) <= MEET_TOL * scale:
            return owner, known
    return None


def same_event(a: Event, b: Event) -> bool:
    """Two events of one kind (and stop) at one point (to MATCH_TOL in state and
    parameter)."""
    return a.kind == b.kind and a.stop == b.stop and \
        float(np.max(np.abs(a.point.u - b.point.u))) < MATCH_TOL


def trace(orbit_map: OrbitMap, first: Point, settings: Settings, name: str,
          both: bool = True, meets: tuple[tuple[str, Event], ...] = ()) -> Branch:
    """Follow ``first`` towards falling and rising parameter (``both``), or only along its
    tangent (ending where it reaches one of the branch points ``meets``); the legs are
    joined into one branch in order of arclength."""
    back_events: list[Event] = []
    fore_events: list[Event] = []
    fore = follow(orbit_map, Point(first.u, first.value, first.tangent, 0.0, first.newton),
                  settings, +1.0, _watch(orbit_map, fore_events, settings.tol, 1, meets))
    if not both:
        return Branch(name, orbit_map.periods, fore.points, fore_events, ("switched", fore.end))
    reverse = -fore.points[0].tangent
    back = follow(orbit_map, Point(first.u, first.value, reverse, 0.0, first.newton),
                  settings, -1.0, _watch(orbit_map, back_events, settings.tol, -1))
    points = back.points[:0:-1] + fore.points
    start = len(back.points) - 1
    for p in back.points[1:]:  # tangents along the joined branch's arclength
        p.tangent = -p.tangent
    for e in back_events:
        e.point.tangent = -e.point.tangent
        e.after = start + e.after - 1  # after the back leg's point k: joined index start - k - 1
    for e in fore_events:
        e.after = start + e.after
    events = sorted(back_events + fore_events, key=lambda e: (e.after, -e.point.step
                                                                if e.after < start else
                                                                e.point.step))
    return Branch(name, orbit_map.periods, points, events, (back.end, fore.end), start=start)


def crossings(orbit_map: OrbitMap, branch: Branch, lam0: float, tol: float
              ) -> list[np.ndarray]:
    """The branch's orbits (p, n) at lam = lam0, one per crossing of that value."""
    out = []
    pts = branch.points
    for a, b in zip(pts[:-1], pts[1:], strict=True):
        if (a.parameter - lam0) * (b.parameter - lam0) > 0 or a.parameter == b.parameter:
            continue
        at = a if a.parameter == lam0 else bound_point(orbit_map, a, b, lam0, tol)
        if at is not None:
            out.append(orbit_points(orbit_map.problem(lam0), at.state, orbit_map.periods))
    return out


def continue_starts(base: OrbitMap, starts: list[tuple[str, np.ndarray, int]], lam0: float,
                    settings: Settings, switch_depth: int = 1, progress=None
                    ) -> tuple[list[Branch], dict[str, str]]:
    """Branches through every start ``(name, state (n,), periods)`` at lam0.

    Returns (branches, {start name: what became of it}): "traced", "on branch <name>" or
    "no convergence" (Newton found no periodic orbit near it). ``progress(1)`` is called
    once per start, whatever became of it.
    """
    branches: list[Branch] = []
    fate: dict[str, str] = {}
    for name, state, periods in starts:
        fate[name] = _continue_start(base, branches, name, state, periods, lam0, settings,
                                     switch_depth)
        if progress is not None:
            progress(1)
    return branches, fate


def _continue_start(base: OrbitMap, branches: list[Branch], name: str, state: np.ndarray,
                    periods: int, lam0: float, settings: Settings, switch_depth: int) -> str:
    """Trace the branch through one start unless it lies on one of ``branches`` (appended
    to in place, with its period-doubled branches); returns what became of the start."""
    orbit_map = base.with_periods(periods)
    first = start_point(orbit_map, state, lam0, settings.tol)
    if first is None:
        return "no convergence"
    orbit = orbit_points(orbit_map.problem(lam0), first.state, periods)
    owner = next((b.name for b in branches for c in b.crossings
                  if same_cycle(c, orbit, MATCH_TOL)), None)
    if owner is not None:
        return f"on branch {owner}"
    branch = trace(orbit_map, first, settings, name)
    branch.crossings = crossings(orbit_map, branch, lam0, settings.tol)
    branches.append(branch)
    _switch(base, branches, len(branches) - 1, settings, switch_depth)
    return "traced"


def _switch(base: OrbitMap, branches: list[Branch], index: int, settings: Settings,
            depth: int) -> None:
    """Trace the doubled branch at every period doubling of ``branches[index]`` and the
    crossing branch, both sides, at every branch point."""
    if depth <= 0:
        return
    parent = branches[index]
    doublings = [e for e in parent.events if e.kind == "period doubling"]
    for k, event in enumerate(doublings, start=1):
        orbit_map = base.with_periods(parent.periods)
        first = switch_to_doubled(orbit_map, event.point, settings.step, settings.tol)
        if first is None:
            continue
        doubled = base.with_periods(2 * parent.periods)
        branch = trace(doubled, first, settings, f"{parent.name} PD{k}", both=False)
        _attach(branch, event, doubled, first, index)
        branches.append(branch)
        _switch(base, branches, len(branches) - 1, settings, depth - 1)
    crossings_ = [e for e in parent.events if e.kind == "branch point"]
    orbit_map = base.with_periods(parent.periods)
    for k, event in enumerate(crossings_, start=1):
        for side, sign in ((+1.0, "+"), (-1.0, "-")):
            if _arrived(branches, event, side):
                continue  # a branch switched at another branch point ends here
            first = switch_at_branch_point(orbit_map, event.point, settings.step,
                                           settings.tol, side)
            if first is None:
                continue
            meets = tuple((b.name, e) for b in branches for e in b.events
                          if e.kind == "branch point")
            branch = trace(orbit_map, first, settings, f"{parent.name} BP{k}{sign}",
                           both=False, meets=meets)
            _attach(branch, event, orbit_map, first, index)
            branches.append(branch)
            _switch(base, branches, len(branches) - 1, settings, depth - 1)


def _attach(branch: Branch, event: Event, orbit_map: OrbitMap, first: Point, parent: int
            ) -> None:
    """Put the located bifurcation as the first point of a branch switched there."""
    branch.points.insert(0, Point(event.point.u, orbit_map.evaluate(event.point.state,
                                                                    event.point.parameter),
                                  first.tangent, 0.0, 0))
    branch.events = [replace(e, after=e.after + 1) for e in branch.events]
    branch.parent = parent


def _arrived(branches: list[Branch], event: Event, side: float) -> bool:
    """Whether a traced branch ends at the branch point ``event`` coming from ``side`` of it
    (the sign of its last step along :func:`crossing_direction`)."""
    direction = crossing_direction(event.point, 1.0)
    for b in branches:
        for end, near in ((b.points[0], b.points[1:2]), (b.points[-1], b.points[-2:-1])):
            if near and float(np.max(np.abs(end.u - event.point.u))) < MATCH_TOL and \
                    np.sign(direction @ (near[0].u - end.u)) == side:
                return True
    return False
