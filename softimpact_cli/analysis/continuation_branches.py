"""Whole branches: both directions from a start, events along them, switching at period
doublings, and one branch traced once however many starts lie on it.

:func:`trace` follows a start point in both directions (``analysis/continuation.py``),
locating the events between consecutive points (``analysis/continuation_events.py``).
:func:`continue_starts` does that for every start (catalogue orbits or a converged
trajectory), skipping a start that lies on a branch already traced (its orbit equals,
to MATCH_TOL, the point where that branch crosses the start's parameter value), and
switches onto the doubled branch at each period doubling, ``switch_depth`` doublings
deep.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .catalogue import orbit_points, same_cycle
from .continuation import Leg, Point, Settings, bound_point, follow, start_point
from .continuation_events import Event, detect, switch_to_doubled
from .shooting import OrbitMap

MATCH_TOL = 1e-6  # two orbits at one parameter value within this (inf-norm): the same


@dataclass
class Branch:
    """One branch: points in order of arclength, located events, why each end stopped.

    periods : forcing periods of its orbits (the map is P^periods); parent : index of the
    branch it was switched from at a period doubling (-1: a start); start : index of its
    start point in ``points``
    """

    name: str
    periods: int
    points: list[Point]
    events: list[Event]
    ends: tuple[str, str]
    parent: int = -1
    start: int = 0
    crossings: list[np.ndarray] = field(default_factory=list)  # orbits (p, n) at lam0


def _watch(orbit_map: OrbitMap, events: list[Event], tol: float, offset_sign: int):
    """The ``on_point`` callback of a leg: locate events between its last two points."""

    def on_point(leg: Leg) -> str:
        left, right = leg.points[-2], leg.points[-1]
        for event in detect(orbit_map, left, right, tol):
            if any(same_event(event, e) for e in events):
                continue  # a test function flickering in its last digits at one zero
            event.after = offset_sign * (len(leg.points) - 2)
            events.append(event)
            if event.kind == "doubling origin":  # beyond it: the same orbit, shifted by p/2
                leg.points[-1] = event.point
                return "meets the orbit it doubled from"
        return ""

    return on_point


def same_event(a: Event, b: Event) -> bool:
    """Two events of one kind at one point (to MATCH_TOL in state and parameter)."""
    return a.kind == b.kind and float(np.max(np.abs(a.point.u - b.point.u))) < MATCH_TOL


def trace(orbit_map: OrbitMap, first: Point, settings: Settings, name: str,
          both: bool = True) -> Branch:
    """Follow ``first`` towards falling and rising parameter (``both``), or only along its
    tangent; the legs are joined into one branch in order of arclength."""
    back_events: list[Event] = []
    fore_events: list[Event] = []
    fore = follow(orbit_map, Point(first.u, first.value, first.tangent, 0.0, first.newton),
                  settings, +1.0, _watch(orbit_map, fore_events, settings.tol, 1))
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
    """Trace the doubled branch at every period doubling of ``branches[index]``."""
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
        branch.points.insert(0, Point(event.point.u, doubled.evaluate(event.point.state,
                                                                      event.point.parameter),
                                      first.tangent, 0.0, 0))
        branch.events = [Event(e.kind, e.point, e.after + 1) for e in branch.events]
        branch.parent = index
        branches.append(branch)
        _switch(base, branches, len(branches) - 1, settings, depth - 1)
