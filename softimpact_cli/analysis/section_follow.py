"""The second stage of classification: follow an unresolved trajectory on the section.

A trajectory whose section points did not repeat with a period <= ``max_orbit_period``
within ``max_periods`` (label ``unresolved``) is continued from where the first pass
left it, block after block of ``SECTION_BLOCK`` forcing periods, until one of:

- **periodic**: its last section points repeat with some period q <= ``section_max_period``
  (the first pass's test, ``kernels.orbit._repeat_period``'s rule, on a longer window):
  a long-period orbit (q > max_orbit_period) or a slow transient that converged late;
- **recurrent**: Attractors.jl's recurrence rule (``AttractorsViaRecurrences``, Datseris
  and Wagemakers 2022) on a grid of cells of side ``section_cell`` in the section's
  state space: ``section_recurrences`` consecutive section points in cells the
  trajectory already visited mean it has settled on a bounded set; the next
  ``section_locate`` points are its attractor's cells and point cloud (what
  :mod:`.nonperiodic` deduplicates and calls chaotic or quasi-periodic);
- **transient**: the budget ``section_periods`` ends first (a long transient: the only
  outcome still labelled ``unresolved``);
- **failed**: the integration failed (diverged, step budget): its kernel status.

No new kernel: the first pass's ``kernels.orbit.record`` integrates (period by period,
so a block keeps the per-period step and switch budgets), and the cells are numpy here.
The first pass is not touched, so every label it gives stays bit for bit; the price is
that the first ``max_periods`` periods are integrated again (``classify_near`` does not
return its end state), which the README's measured cost includes.

**Known sets** (``KnownSets``: the recurrent sets earlier trajectories of the same block
of a sweep reached, with their cells). Before integrating the first pass again, a
trajectory is probed for at most ``PROBE_PERIODS`` periods from its start, ``PROBE_BLOCK``
at a time: once ``section_recurrences`` consecutive section points lie in the cells of
one known set (and do not repeat with a period <= ``section_max_period``: a long-period
orbit inside the set's cells is left to the full stage), it is **recurrent on that set**
(``known_set``; Attractors.jl's rule for points landing in a known attractor's cells)
and stops there, its located cells and cloud being those points. A probe that does not
stop is discarded and the stage runs as without known sets, bit for bit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..config import IntegratorSettings
from ..kernels import orbit
from ..kernels.codes import OK
from .engine import Problem
from .nonperiodic import SETTLING, kind_of, section_spectrum

SECTION_BLOCK = 250  # forcing periods integrated between two looks at the section points
PROBE_BLOCK = 50  # periods between two looks while probing for a known set
PROBE_PERIODS = 500  # the probe's budget from the start (then the stage as without sets)
DISTINCT = 100.0  # as kernels.orbit.DISTINCT: a divisor nearly repeating means "spiralling"

PERIODIC, RECURRENT, TRANSIENT, FAILED = "periodic", "recurrent", "transient", "failed"


@dataclass(frozen=True)
class SectionFollow:
    """What following a trajectory on the section found.

    outcome : PERIODIC, RECURRENT, TRANSIENT or FAILED; status : kernel status (OK unless
    FAILED); periods : forcing periods integrated in this stage (after the first pass's);
    orbit : (q, dim) section points of the periodic orbit in time order (PERIODIC);
    cells : (m, dim) int64 sorted distinct cell indices floor(y / section_cell) of the
    located attractor (RECURRENT); cloud : (locate, dim) its section points in time order;
    contacts : contact onsets over the orbit or the located points; max_g : max of
    x1 - x2 - d over them (>= 0: impacting; -inf without a stop); end_state (dim,),
    end_time : where the stage stopped (on a section time); known_set : index of the
    known set it was found recurrent on (``KnownSets``), else -1, whose contact flag it
    takes (the few points located there may miss a rare impact of an impacting set).
    """

    outcome: str
    status: int
    periods: int
    orbit: np.ndarray
    cells: np.ndarray
    cloud: np.ndarray
    contacts: int
    max_g: float
    end_state: np.ndarray
    end_time: float
    known_set: int = -1
    known_impacting: bool = False

    @property
    def impacting(self) -> bool:
        if self.known_set >= 0:
            return self.known_impacting
        return self.max_g >= 0.0


class KnownSets:
    """The recurrent sets earlier trajectories of one block of a sweep reached: their
    section cells (rows of ``cell_indices``) and contact flags, in the order found. A
    sweep starts a new one where it starts new recurrence cells (every grid point and
    block of flat indices), so labels do not depend on how a run is cut into chunks."""

    def __init__(self):
        self.cells: list[set] = []
        self.impacting: list[bool] = []
        self.first: list[tuple[np.ndarray, float]] = []  # its first trajectory's end
        self.attractor: list[bool | None] = []  # not contracting ("settling")? None: unknown

    def __len__(self) -> int:
        return len(self.cells)

    def learn(self, follow: SectionFollow) -> None:
        """Add what a recurrent trajectory's stage found: its cells join the set it was
        found on, or start a new set."""
        rows = set(map(tuple, np.asarray(follow.cells).tolist()))
        if follow.known_set >= 0:
            self.cells[follow.known_set] |= rows
        else:
            self.cells.append(rows)
            self.impacting.append(follow.impacting)
            self.first.append((follow.end_state, follow.end_time))
            self.attractor.append(None)

    def is_attractor(self, k: int, problem: Problem) -> bool:
        """Whether set k is chaotic or quasi-periodic by its first trajectory's spectrum
        (the one the sweep's naming computes for it, ``nonperiodic.section_spectrum``),
        computed once when a trajectory first lands on it. A contracting set is a
        periodic orbit not converged yet: its trajectories go through the full stage."""
        if self.attractor[k] is None:
            exponents, _ = section_spectrum(problem, *self.first[k])
            self.attractor[k] = kind_of(self.impacting[k], float(exponents[0]),
                                        problem.integrator.section_zero_exponent) != SETTLING
        return self.attractor[k]

    def landed(self, cells: np.ndarray, runs: list[int], needed: int) -> tuple[int, int]:
        """Feed cell rows (n, dim) in time order; ``runs`` (one per set, updated in place)
        count the consecutive points in each set's cells. (set, row) at which a run
        first reached ``needed`` (the lowest set on a tie), else (-1, -1)."""
        while len(runs) < len(self.cells):
            runs.append(0)
        for i, row in enumerate(map(tuple, cells.tolist())):
            hit = -1
            for k, known in enumerate(self.cells):
                runs[k] = runs[k] + 1 if row in known else 0
                if hit < 0 and runs[k] >= needed:
                    hit = k
            if hit >= 0:
                return hit, i
        return -1, -1


def cell_indices(points: np.ndarray, size: float) -> np.ndarray:
    """(n, dim) int64 cell indices floor(y / size) of section points (n, dim)."""
    return np.floor(np.asarray(points) / size).astype(np.int64)


def repeat_period(points: np.ndarray, max_q: int, tol: float) -> int:
    """Smallest q <= max_q with the last q points of ``points`` (n, dim) repeating after
    q periods within tol * max(1, |y_n|_inf), refused while a proper divisor nearly
    repeats (``kernels.orbit._repeat_period``'s rule); 0 if none."""
    n = points.shape[0]
    lim = tol * max(1.0, float(np.max(np.abs(points[-1]))))
    for q in range(1, min(max_q, n // 2) + 1):
        if np.max(np.abs(points[n - q:] - points[n - 2 * q: n - q])) > lim:
            continue
        for r in range(1, q):
            if q % r == 0 and np.max(np.abs(points[n - q:] - points[n - q - r: n - r])) \
                    <= DISTINCT * lim:
                return 0
        return q
    return 0


class Recurrences:
    """Attractors.jl's finite-state rule on one trajectory's cells: ``found`` once
    ``needed`` consecutive points fell in cells already visited."""

    def __init__(self, needed: int):
        self.needed = needed
        self.visited: set[tuple[int, ...]] = set()
        self.streak = 0

    def feed(self, cells: np.ndarray) -> int:
        """Take cell rows (n, dim) in time order; the index of the row at which the
        trajectory was found recurrent, or -1."""
        for i, row in enumerate(map(tuple, cells.tolist())):
            if row in self.visited:
                self.streak += 1
                if self.streak >= self.needed:
                    return i
            else:
                self.streak = 0
                self.visited.add(row)
        return -1


def _record(problem: Problem, y: np.ndarray, t: float, periods: int):
    """(status, section points (periods + 1, dim), contacts, max_g) of ``periods`` forcing
    periods from the section time t."""
    out = orbit.recorded(orbit.record(
        problem.advance, problem.system.rhs, problem.params, (y, float(t), problem.period),
        int(periods), problem.kernel_args(), problem.options(), 0))
    return int(out.status), out.section_y, out.contacts, out.max_g


def _probe(problem: Problem, y: np.ndarray, t0: float, budget: int, known: KnownSets
           ) -> SectionFollow | None:
    """The trajectory from ``y`` at ``t0`` for at most ``budget`` periods, PROBE_BLOCK at a
    time: RECURRENT on a known set once ``section_recurrences`` consecutive section points
    lie in its cells (unless they repeat with a period <= section_max_period), else None
    (see the module docstring)."""
    s: IntegratorSettings = problem.integrator
    T = problem.period
    n0 = orbit.first_section(t0, T)
    points, contacts, max_g, runs = [], [], [], []  # point j: the section at (n0 + j) T
    used = 0
    while used < budget:
        block = min(PROBE_BLOCK, budget - used)
        status, pts, c, g = _record(problem, y, (n0 + used) * T if used else t0, block)
        if status != OK:
            return None  # the full stage meets the failure and reports it
        new = slice(1 if used else 0, None)  # row 0 repeats the previous block's last
        points.append(pts[new])
        contacts.append(c[new])
        max_g.append(g[new])
        used += block
        y = pts[-1].copy()
        k, i = known.landed(cell_indices(pts[new], s.section_cell), runs,
                            s.section_recurrences)
        if k < 0:
            continue
        cloud = np.concatenate(points)
        end = len(cloud) - len(points[-1]) + i  # the point that completed the run
        window = cloud[max(0, end + 1 - (2 * s.section_max_period + 1)): end + 1]
        if repeat_period(window, s.section_max_period, s.convergence_tol) or \
                not known.is_attractor(k, problem):
            return None  # an orbit inside the set's cells: the full stage names it
        located = slice(end + 1 - s.section_recurrences, end + 1)
        c_all, g_all = np.concatenate(contacts), np.concatenate(max_g)
        return SectionFollow(
            RECURRENT, OK, used, np.zeros((0, cloud.shape[1])),
            np.unique(cell_indices(cloud[located], s.section_cell), axis=0),
            cloud[located].copy(), int(c_all[located].sum()), float(g_all[located].max()),
            cloud[end].copy(), (n0 + end) * T, k, known.impacting[k])
    return None


def follow_section(problem: Problem, state, t0: float, skip: int,
                   known: KnownSets | None = None) -> SectionFollow:
    """Follow the trajectory imposed as ``state`` at ``t0`` on the section, from the end
    of its first ``skip`` forcing periods (the first pass's budget), with the problem's
    ``section_*`` settings; ``known``: the recurrent sets earlier trajectories of its
    block reached, which it may be found on at once (see the module docstring)."""
    s: IntegratorSettings = problem.integrator
    T = problem.period
    y = np.array(state, dtype=np.float64)
    dim = y.shape[0]
    empty = np.zeros((0, dim))
    no_cells = np.zeros((0, dim), dtype=np.int64)
    n0 = orbit.first_section(float(t0), T)
    if known:
        landed = _probe(problem, y, float(t0), PROBE_PERIODS, known)
        if landed is not None:
            return landed
    status, pts, _, _ = _record(problem, y, t0, skip)  # the first pass again
    if status != OK:
        return SectionFollow(FAILED, status, 0, empty, no_cells, empty, 0, -np.inf, y, t0)
    y, t = pts[-1].copy(), (n0 + skip) * T
    window = max(2 * s.section_max_period, 1) + 1
    history = pts[-window:]
    hist_contacts = np.zeros(len(history), dtype=np.int64)
    hist_g = np.full(len(history), -np.inf)
    rec = Recurrences(s.section_recurrences)
    used = 0
    while used < s.section_periods:
        block = min(SECTION_BLOCK, s.section_periods - used)
        status, pts, contacts, max_g = _record(problem, y, t, block)
        if status != OK:
            return SectionFollow(FAILED, status, used, empty, no_cells, empty, 0, -np.inf,
                                 y, t)
        new, new_c, new_g = pts[1:], contacts[1:], max_g[1:]
        used += block
        y, t = pts[-1].copy(), t + block * T
        history = np.concatenate([history, new])[-window:]
        hist_contacts = np.concatenate([hist_contacts, new_c])[-window:]
        hist_g = np.concatenate([hist_g, new_g])[-window:]
        q = repeat_period(history, s.section_max_period, s.convergence_tol)
        if q:
            return SectionFollow(PERIODIC, OK, used, history[-q:].copy(), no_cells, empty,
                                 int(hist_contacts[-q:].sum()), float(hist_g[-q:].max()),
                                 y, t)
        found = rec.feed(cell_indices(new, s.section_cell))
        if found < 0:
            continue
        cloud, c, g = new[found + 1:], new_c[found + 1:], new_g[found + 1:]
        more = s.section_locate - len(cloud)
        if more > 0:
            status, pts, contacts, max_g = _record(problem, y, t, more)
            if status != OK:
                return SectionFollow(FAILED, status, used, empty, no_cells, empty, 0,
                                     -np.inf, y, t)
            used += more
            y, t = pts[-1].copy(), t + more * T
            cloud = np.concatenate([cloud, pts[1:]])
            c = np.concatenate([c, contacts[1:]])
            g = np.concatenate([g, max_g[1:]])
        cloud, c, g = cloud[: s.section_locate], c[: s.section_locate], g[: s.section_locate]
        cells = np.unique(cell_indices(cloud, s.section_cell), axis=0)
        return SectionFollow(RECURRENT, OK, used, empty, cells, cloud, int(c.sum()),
                             float(g.max()), y, t)
    return SectionFollow(TRANSIENT, OK, used, empty, no_cells, empty, 0, -np.inf, y, t)
