"""Attractors that are not periodic: deduplicate the second stage's recurrent trajectories
across a whole result, decide chaotic or quasi-periodic, and name them.

Input: the trajectories :mod:`.section_follow` found recurrent (each with its located
cells, point cloud and end state), **in flat-index order**. Output: a label code per
trajectory and the table of attractors. Deterministic by construction: the order is the
flat index, not the order chunks finished in, so every worker count and executor (local
pool, Dask) gives the same numbers A1, A2, ... to the same attractors.

**Deduplication.** A trajectory belongs to attractor k when it has the same contact
flag (impacting or not) and at least ``MATCH`` of its cells are cells attractor k's
trajectories visited (the union grows with every member, at any grid point); the best
such k wins, ties to the lower number. Otherwise it starts attractor k + 1. Two distinct
attractors share cells only where they pass within one cell of each other; Attractors.jl
meets the same limit (a grid too coarse merges attractors; ``section_cell`` is the knob).

**Kind.** The first trajectory of an attractor (its representative) gives its Lyapunov
spectrum (``spectrum(point, state, t)``, Benettin's method with saltation matrices,
:mod:`.lyapunov`) from where the second stage left it:

- lambda1 > ``section_zero_exponent``: **chaotic** (nearby section points separate);
- |lambda1| <= ``section_zero_exponent``: **quasi-periodic** (a closed invariant curve on
  the section; the neutral exponent is the drift along the curve);
- lambda1 < -``section_zero_exponent``: every direction contracts, so this is a periodic
  orbit not yet converged (longer than ``section_max_period`` or approached slowly):
  its trajectories stay ``unresolved`` (the table says "settling").
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..kernels.codes import BASE_WIDTH, NONPERIODIC_BASES, UNRESOLVED_LABEL
from .engine import Problem
from .labels import Label
from .lyapunov import lyapunov_spectrum

MATCH = 0.5  # share of a trajectory's cells that must be an attractor's to belong to it
SETTLING = "settling"  # the table's kind of a contracting recurrent set (not an attractor)
LYAPUNOV_TRANSIENT = 20  # periods to align the tangent vectors before averaging
LYAPUNOV_SEGMENTS = 10


def section_spectrum(problem: Problem, state, t: float) -> tuple[np.ndarray, np.ndarray]:
    """(exponents, standard errors), (dim,) each in 1/time, largest first, of the
    trajectory through ``state`` at time ``t``: the spectrum every recurrent set is
    judged by (``section_lyapunov_periods`` rounded up to whole segments, after
    LYAPUNOV_TRANSIENT periods), in sweeps and for a single trajectory alike."""
    s = problem.integrator
    periods = -(-s.section_lyapunov_periods // LYAPUNOV_SEGMENTS) * LYAPUNOV_SEGMENTS
    sp = lyapunov_spectrum(problem, state, t, periods=periods, transient=LYAPUNOV_TRANSIENT,
                           segments=LYAPUNOV_SEGMENTS)
    return sp.exponents, sp.stderr


@dataclass(frozen=True)
class Recurrent:
    """One trajectory the second stage found recurrent.

    flat : flat index in the result; point : grid point; cells : (m, dim) int64 located
    cells; cloud : (n, dim) located section points; impacting : contact on them;
    end_state : (dim,) and end_time : where the second stage stopped.
    """

    flat: int
    point: int
    cells: np.ndarray
    cloud: np.ndarray
    impacting: bool
    end_state: np.ndarray
    end_time: float


@dataclass
class Presence:
    """An attractor at one grid point: its first trajectory there, the spectrum from where
    that trajectory's second stage ended (1/time, largest first), the trajectories there
    and the cells they visited."""

    first: Recurrent
    exponents: np.ndarray
    stderr: np.ndarray
    members: int = 0
    cells: set = field(default_factory=set, repr=False)


@dataclass
class Attractor:
    """A deduplicated recurrent set: its kind, number (0 for SETTLING), contact flag,
    cells (the union over every member) and its presence at each grid point."""

    kind: str
    number: int
    impacting: bool
    cells: set = field(repr=False)
    at: dict = field(default_factory=dict)  # grid point -> Presence

    @property
    def code(self) -> int:
        if self.kind == SETTLING:
            return UNRESOLVED_LABEL
        return NONPERIODIC_BASES[self.kind] + self.number

    @property
    def name(self) -> str:
        if self.kind == SETTLING:
            return f"unresolved ({SETTLING})"
        return Label(self.kind, left=self.number).name

    def add(self, rec: Recurrent, cells: set, spectrum=None) -> None:
        """Count ``rec`` (its cells ``cells``) as a member; ``spectrum`` = (exponents,
        stderr) of rec when it is the first member at its grid point."""
        if rec.point not in self.at:
            self.at[rec.point] = Presence(rec, *spectrum)
        here = self.at[rec.point]
        here.members += 1
        here.cells |= cells
        self.cells |= cells


def kind_of(impacting: bool, largest: float, zero: float) -> str:
    """The attractor kind of a recurrent set from its largest exponent (1/time)."""
    if largest > zero:
        kind = "chaotic"
    elif largest >= -zero:
        kind = "quasi-periodic"
    else:
        return SETTLING
    return f"impacting {kind}" if impacting else kind


def _rows(cells: np.ndarray) -> set:
    return set(map(tuple, np.asarray(cells).tolist()))


def identify(found: list[Recurrent], spectrum: Callable, zero: float,
             known: list[Attractor] = ()) -> tuple[np.ndarray, list[Attractor]]:
    """(label code per trajectory (len(found),), attractors in number order) of recurrent
    trajectories ``found`` sorted by flat index; ``spectrum(point, state, t)`` returns
    (exponents, stderr) of the trajectory through ``state`` at time t at grid point
    ``point``; ``zero`` is ``section_zero_exponent``. ``known``: attractors of an earlier
    result (:func:`known_attractors`) matched first and keeping their numbers (a
    verification rerun names what it finds as the result it checks does).

    The kind is decided at every grid point an attractor reaches (by its first trajectory
    there): a trajectory whose cells match an attractor of another kind at its own grid
    point (chaos at c_c = 3 turning into a torus at c_c = 4) is not that attractor.
    """
    if any(a.flat >= b.flat for a, b in zip(found, found[1:], strict=False)):
        raise ValueError("recurrent trajectories must come in increasing flat index")
    attractors: list[Attractor] = list(known)
    codes = np.empty(len(found), dtype=np.int32)
    numbered = max((a.number for a in attractors), default=0)
    for i, rec in enumerate(found):
        mine = _rows(rec.cells)
        candidates = sorted(
            ((len(mine & a.cells) / len(mine), -k) for k, a in enumerate(attractors)
             if a.impacting == rec.impacting and mine),
            reverse=True)
        own = None  # rec's spectrum, computed once if needed
        chosen = None
        for share, minus_k in candidates:
            if share < MATCH:
                break
            a = attractors[-minus_k]
            if rec.point in a.at:
                chosen = a
                break
            own = own or spectrum(rec.point, rec.end_state, rec.end_time)
            if kind_of(rec.impacting, float(own[0][0]), zero) == a.kind:
                chosen = a
                break
        if chosen is None:
            own = own or spectrum(rec.point, rec.end_state, rec.end_time)
            kind = kind_of(rec.impacting, float(own[0][0]), zero)
            numbered += kind != SETTLING
            chosen = Attractor(kind, numbered if kind != SETTLING else 0, rec.impacting,
                               set())
            attractors.append(chosen)
        chosen.add(rec, mine, own if rec.point not in chosen.at else None)
        codes[i] = chosen.code
    return codes, attractors


def known_attractors(table, cell: float) -> list[Attractor]:
    """The attractors of a result's table (``attractor_table``'s variables), with the
    cells of their stored clouds at side ``cell``, to seed :func:`identify`."""
    if table is None or "nonperiodic_code" not in table:
        return []
    by_code: dict[int, Attractor] = {}
    for i, kind in enumerate(table["nonperiodic_kind"].values):
        cloud = table["nonperiodic_cloud"].values[i]
        cloud = cloud[np.isfinite(cloud[:, 0])]
        code = int(table["nonperiodic_code"].values[i])
        kind = str(kind)
        first = Recurrent(int(table["nonperiodic_flat"].values[i]),
                          int(table["nonperiodic_point"].values[i]), np.zeros((0, 0)), cloud,
                          kind.startswith("impacting"), cloud[-1], 0.0)
        a = by_code.setdefault(code, Attractor(kind, 0 if kind == SETTLING else
                                               code % BASE_WIDTH, first.impacting, set()))
        a.add(first, _rows(np.floor(cloud / cell).astype(np.int64)),
              (table["nonperiodic_exponents"].values[i],
               table["nonperiodic_stderr"].values[i]))
    return list(by_code.values())


def attractor_table(attractors: list[Attractor], state_names: tuple[str, ...]
                    ) -> xr.Dataset:
    """One row per attractor and grid point it reaches (dimension ``nonperiodic``; an
    empty Dataset when there are none): code, name, kind, grid point and flat index of
    its first trajectory there, members and cells there, Lyapunov exponents and their
    standard errors there, and that trajectory's point cloud."""
    rows = [(a, point, p) for a in attractors for point, p in sorted(a.at.items())]
    if not rows:
        return xr.Dataset()
    dim = len(state_names)
    n_cloud = max(p.first.cloud.shape[0] for _, _, p in rows)
    cloud = np.full((len(rows), n_cloud, dim), np.nan)
    for i, (_, _, p) in enumerate(rows):
        cloud[i, : p.first.cloud.shape[0]] = p.first.cloud
    one = ("nonperiodic",)
    return xr.Dataset(
        {
            "nonperiodic_code": (one, np.array([a.code for a, _, _ in rows], np.int32),
                                 {"long_name": "label code of each recurrent set"}),
            "nonperiodic_name": (one, np.array([a.name for a, _, _ in rows], dtype=object),
                                 {"long_name": "name of each recurrent set"}),
            "nonperiodic_kind": (one, np.array([a.kind for a, _, _ in rows], dtype=object),
                                 {"long_name": "chaotic, quasi-periodic (impacting or not) "
                                               "or settling"}),
            "nonperiodic_point": (one, np.array([pt for _, pt, _ in rows], np.int64),
                                  {"long_name": "grid point (flat over the grid dims)"}),
            "nonperiodic_flat": (one, np.array([p.first.flat for _, _, p in rows], np.int64),
                                 {"long_name": "flat index of its first trajectory there"}),
            "nonperiodic_members": (one, np.array([p.members for _, _, p in rows], np.int64),
                                    {"long_name": "trajectories labelled with it there"}),
            "nonperiodic_cells": (one, np.array([len(p.cells) for _, _, p in rows], np.int64),
                                  {"long_name": "section cells its trajectories visited "
                                                "there"}),
            "nonperiodic_exponents": (
                one + ("exponent",), np.stack([p.exponents for _, _, p in rows]),
                {"long_name": "Lyapunov exponents of its first trajectory there, largest "
                              "first", "units": "1/time"}),
            "nonperiodic_stderr": (
                one + ("exponent",), np.stack([p.stderr for _, _, p in rows]),
                {"long_name": "standard error of the exponents (segment means)",
                 "units": "1/time"}),
            "nonperiodic_cloud": (
                one + ("cloud_point", "variable"), cloud,
                {"long_name": "section points of its first trajectory there after "
                              "recurrence", "units": "1"}),
        },
        coords={"variable": ("variable", list(state_names))},
    )
