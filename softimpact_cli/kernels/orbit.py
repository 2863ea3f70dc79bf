"""Trajectories on the stroboscopic section t_n = n T: classification and recording.

``classify`` advances one forcing period at a time and stops as soon as the section
points repeat with some period q <= max_orbit_period: the last 2q points satisfy
``max_j |y_{n-j} - y_{n-j-q}|_inf <= tol * max(1, |y_n|_inf)`` for j < q, the smallest
such q being the period, provided no proper divisor of q nearly repeats as well (see
``_repeat_period``). No fixed transient is integrated.

``classify_near`` stops earlier still when the orbit is known in advance (the catalogue's
stable non-impacting solutions): it captures a trajectory whose section points follow one
known orbit, point after point, within ``capture_tol`` (scaled like the convergence test)
for ``capture_hits`` consecutive periods without contact. Inside such a neighbourhood of a
stable orbit the trajectory contracts onto it, so the label is the one full convergence
would give, reached after about half the periods (the last ~1e-2 -> 1e-6 of the approach
is skipped). With recurrence cells (``kernels.cells``) it also stops when the section
points land, period after period, in cells that earlier trajectories marked with one label.
"""

from collections import namedtuple
from math import ceil

import numpy as np
from numba import njit

from .cells import NO_CELL, cell_key, new_cells
from .codes import CONVERGED, MIXED_CELL, NO_ORBIT, OK, UNRESOLVED
from .layout import (
    MATRICES,
    MAX_G,
    MODE,
    N_CONTACTS,
    N_FSTATE,
    N_ISTATE,
    N_SAMPLES,
    T_STUCK,
    WORK_ROWS,
)
from .switching import mode_of

# What ``classify_near`` returns, as ``classified`` names it. The kernel returns plain
# tuples, ((status, q, periods used, contacts, captured, cell_code), max_g, orbit,
# counters): numba boxes a named tuple by calling its class, Python code during which a
# pending SIGINT handler raises and numba's boxing crashes; a plain tuple is built in C.
# status (status table code); period q in forcing periods (0 unless converged); periods
# used; orbit (max(max_orbit_period, Q), dim), rows 0..q-1 the orbit's section points in
# time order (a captured trajectory returns the known orbit); contacts, contact onsets
# during the last q periods; max_g, max of the contact function x1 - x2 - d over them
# (>= 0: the orbit is in contact; -inf without contact); counters, the integrator's
# (N_ISTATE,) istate; captured, the index of the known orbit that captured it, else
# NO_ORBIT; cell_code, the label code taken from the cells (status CONVERGED, q = 0, orbit
# unknown), else MIXED_CELL.
Classified = namedtuple("Classified", ["status", "period", "periods_used", "orbit", "contacts",
                                       "max_g", "counters", "captured", "cell_code"])
# The bundles of known stable orbits and of recurrence cells ``classify_near`` takes (see
# there); built in Python by ``analysis.engine`` or in jitted code by ``no_known`` and
# ``no_cells``.
Known = namedtuple("Known", ["points", "periods", "max_g", "capture_tol", "capture_hits"])
Cells = namedtuple("Cells", ["size", "hits", "visited"])
# What ``record`` returns, as ``recorded`` names it (the kernel: ((status, samples
# written), (sample_t, sample_y), (section_t, section_y, contacts, max_g), counters,
# sticking time)):
# sample_t (n_samples,), sample_y (n_samples, dim), samples
# written; section_t (n_periods + 1,), section_y (n_periods + 1, dim), contacts and max_g
# per period (row 0: before the first section); rows after a failure are NaN; sticking
# time, the time spent stuck on rigid stops (``kernels.impacts``).
Recorded = namedtuple("Recorded", ["status", "sample_t", "sample_y", "n_samples", "section_t",
                                   "section_y", "contacts", "max_g", "counters",
                                   "sticking_time"])


def classified(raw) -> Classified:
    """``classify_near``'s plain result, named."""
    (status, q, n_used, contacts, captured, cell_code), max_g, orbit, counters = raw
    return Classified(status, q, n_used, orbit, contacts, max_g, counters, captured, cell_code)


def recorded(raw) -> Recorded:
    """``record``'s plain result, named."""
    (status, n_written), (sample_t, sample_y), sections, (counters, stuck) = raw
    return Recorded(status, sample_t, sample_y, n_written, *sections, counters, stuck)


@njit(cache=True)
def first_section(t0, period):
    """Index of the first section time n T >= t0 (t0 on a section maps to itself)."""
    return int(ceil(t0 / period - 1e-9))


@njit(cache=True)
def new_state(y0, A_s, b_s):
    """(istate, fstate, work) of a trajectory starting at ``y0``: the ``state`` bundle."""
    dim = y0.shape[0]
    istate = np.zeros(N_ISTATE, dtype=np.int64)
    fstate = np.zeros(N_FSTATE)
    fstate[MAX_G] = -np.inf
    work = np.zeros((WORK_ROWS + MATRICES * dim, dim))
    istate[MODE] = mode_of(y0, A_s, b_s)
    return istate, fstate, work


@njit(cache=True)
def no_samples(dim):
    """The ``samples`` bundle of a trajectory that writes none."""
    return np.empty(0), np.empty((0, dim))


@njit(cache=True)
def one_period(advance, rhs, p, y, t_start, period, surfaces, opts, state, samples):
    """Advance one forcing period from t_start; (status, contact onsets, max of the contact
    function during it). A period that starts in contact is in contact."""
    istate, fstate, _ = state
    fstate[MAX_G] = -np.inf
    if istate[MODE] & surfaces[3]:  # (surfaces[3]: the bit mask of contact surfaces)
        fstate[MAX_G] = 0.0
    c_before = istate[N_CONTACTS]
    status = advance(rhs, p, y, t_start, t_start + period, surfaces, opts, state, samples)
    return status, istate[N_CONTACTS] - c_before, fstate[MAX_G]


DISTINCT = 100.0  # sub-period differences below DISTINCT * tol mean "still converging"


@njit(cache=True)
def _repeats_within(hist, n, depth, q, span, lim):
    """Whether |y_{n-j} - y_{n-j-q}|_inf <= lim for every j < span (stops at the first
    point that does not: most candidate periods fail on it)."""
    dim = hist.shape[1]
    for j in range(span):
        a = hist[(n - j) % depth]
        b = hist[(n - j - q) % depth]
        for i in range(dim):
            if abs(a[i] - b[i]) > lim:
                return False
    return True


@njit(cache=True)
def _repeat_period(hist, n, depth, max_q, tol):
    """Smallest q <= max_q with the last q points repeating after q; 0 if none yet.

    A candidate q is refused while a proper divisor r of q nearly repeats too (distance
    below DISTINCT * tol): the trajectory is then still spiralling into the period-r orbit
    (complex multipliers near a q-th root of unity make y_n - y_{n-q} small first).
    """
    dim = hist.shape[1]
    last = hist[n % depth]
    scale = 1.0
    for i in range(dim):
        scale = max(scale, abs(last[i]))
    lim = tol * scale
    for q in range(1, max_q + 1):
        if n < 2 * q:
            break
        if not _repeats_within(hist, n, depth, q, q, lim):
            continue
        for r in range(1, q):
            if q % r == 0 and _repeats_within(hist, n, depth, r, q, DISTINCT * lim):
                return 0
        return q
    return 0


@njit(cache=True)
def _nearest_known(y, known, known_q, lim):
    """(k, j) of the known orbit point nearest y within lim (inf-norm), else (-1, -1)."""
    best_k, best_j, best = -1, -1, lim
    for k in range(known.shape[0]):
        for j in range(known_q[k]):
            dist = 0.0
            for i in range(y.shape[0]):
                dist = max(dist, abs(y[i] - known[k, j, i]))
            if dist <= best:
                best_k, best_j, best = k, j, dist
    return best_k, best_j


@njit(cache=True)
def follow_known(y, known, free, streak, last_k, last_j):
    """The capture streak after section point ``y``: (streak, k, j) with (k, j) the known
    orbit point within ``capture_tol`` (scaled) of y, if the period was contact ``free``,
    and the streak counting consecutive periods following one orbit point after point."""
    scale = 1.0
    for i in range(y.shape[0]):
        scale = max(scale, abs(y[i]))
    hit_k, hit_j = -1, -1
    if free:
        hit_k, hit_j = _nearest_known(y, known.points, known.periods, known.capture_tol * scale)
    if hit_k >= 0 and hit_k == last_k and hit_j == (last_j + 1) % known.periods[hit_k]:
        return streak + 1, hit_k, hit_j
    if hit_k >= 0:
        return 1, hit_k, hit_j
    return 0, hit_k, hit_j


@njit(cache=True)
def follow_cells(y, n, cells, table, run, run_code):
    """Record the cell of section point n in ``visited``; the run of consecutive periods in
    cells of one label after it: (run, its label code)."""
    if n >= cells.visited.shape[0]:
        return run, run_code
    key = cell_key(y, cells.size, table)  # every visited key is written, whatever classifies
    cells.visited[n] = key
    code = MIXED_CELL
    if key != NO_CELL:
        code = table.get(key, MIXED_CELL)
    if code == MIXED_CELL:
        return 0, run_code
    if code == run_code:
        return run + 1, run_code
    return 1, code


@njit(cache=True)
def known_orbit(known, k, j, orbit):
    """Write known orbit k into ``orbit`` in time order, ending at its point j; its period."""
    q = known.periods[k]
    for i in range(q):
        orbit[i] = known.points[k, (j - q + 1 + i) % q]
    return q


@njit(cache=True)
def repeated_orbit(hist, contacts, max_g, n, q, orbit):
    """Write the last q section points into ``orbit``; (contact onsets, max of the contact
    function) over those q periods."""
    depth = hist.shape[0]
    total = 0
    worst = -np.inf
    for i in range(q):
        kk = (n - q + 1 + i) % depth
        orbit[i] = hist[kk]
        total += contacts[kk]
        worst = max(worst, max_g[kk])
    return total, worst


@njit(cache=True)
def no_known(dim):
    """The ``known`` bundle without orbits (capture off)."""
    return Known(np.zeros((0, 1, dim)), np.zeros(0, dtype=np.int64), np.zeros(0), 0.0, 1)


@njit(cache=True)
def no_cells():
    """The ``cells`` bundle without recurrence cells."""
    return Cells(0.0, 1, np.empty(0, dtype=np.int64))


@njit(cache=True)
def classify(advance, rhs, p, start, surfaces, opts, limits):
    """``classify_near`` with no known orbits and no cells: stop when the points repeat."""
    return classify_near(advance, rhs, p, start, surfaces, opts, limits,
                         no_known(start[0].shape[0]), no_cells(), new_cells())


@njit(cache=True)
def classify_near(advance, rhs, p, start, surfaces, opts, limits, known, cells, table):
    """Integrate from (t0, y0) until the section points repeat, or follow a known orbit,
    or the budget ends, or it fails; returns a ``Classified`` as plain tuples (see there).

    start = (y0, t0, T); surfaces = (A, b, relevance, contact); limits = (max_periods,
    max_orbit_period, tol) of the convergence test.
    known = Known(points (K, Q, dim): K known stable orbits in time order, periods (K,),
    max_g (K,) of the contact function, capture_tol, capture_hits): captured after
    capture_hits consecutive contact-free periods, each within capture_tol * max(1, |y|)
    of the known orbit's next point (capture_tol = 0: off).
    cells = Cells(size (0: off), hits, visited (max_periods + 1,) int64), table {cell key:
    label code} (``kernels.cells``; apart: a typed dict inside a tuple costs ~20 us per
    call from Python): a cell label after ``hits`` consecutive periods in cells of that
    label; ``visited`` receives the section points' cell keys in order.
    """
    y0, t0, period = start
    max_periods, max_orbit_period, tol = limits
    dim = y0.shape[0]
    y = y0.copy()
    state = new_state(y, surfaces[0], surfaces[1])
    istate = state[0]
    samples = no_samples(dim)
    depth = 2 * max_orbit_period + 1
    hist = np.empty((depth, dim))
    contacts = np.zeros(depth, dtype=np.int64)
    max_g = np.full(depth, -np.inf)
    orbit = np.zeros((max(max_orbit_period, known.points.shape[1]), dim))
    n0 = first_section(t0, period)
    if n0 * period > t0:
        status = advance(rhs, p, y, t0, n0 * period, surfaces, opts, state, samples)
        if status != OK:
            return (status, 0, 0, 0, NO_ORBIT, MIXED_CELL), -np.inf, orbit, istate
    hist[0] = y
    use_cells = cells.size > 0.0 and cells.visited.shape[0] > 0
    if use_cells:
        cells.visited[0] = cell_key(y, cells.size, table)
    use_known = known.capture_tol > 0.0 and known.points.shape[0] > 0
    run, run_code, streak, last_k, last_j = 0, MIXED_CELL, 0, -1, -1
    for n in range(1, max_periods + 1):
        k = n % depth
        status, contacts[k], max_g[k] = one_period(advance, rhs, p, y, (n0 + n - 1) * period,
                                                   period, surfaces, opts, state, samples)
        if status != OK:
            return (status, 0, n, 0, NO_ORBIT, MIXED_CELL), -np.inf, orbit, istate
        hist[k] = y
        if use_cells:
            run, run_code = follow_cells(y, n, cells, table, run, run_code)
        if use_known:
            free = contacts[k] == 0 and not istate[MODE] & surfaces[3]
            streak, last_k, last_j = follow_known(y, known, free, streak, last_k, last_j)
            if streak >= known.capture_hits:
                q = known_orbit(known, last_k, last_j, orbit)
                return (CONVERGED, q, n, 0, last_k, MIXED_CELL), known.max_g[last_k], orbit, istate
        if run >= cells.hits:
            return (CONVERGED, 0, n, 0, NO_ORBIT, run_code), -np.inf, orbit, istate
        q = _repeat_period(hist, n, depth, max_orbit_period, tol)
        if q > 0:
            total, worst = repeated_orbit(hist, contacts, max_g, n, q, orbit)
            return (CONVERGED, q, n, total, NO_ORBIT, MIXED_CELL), worst, orbit, istate
    return (UNRESOLVED, 0, max_periods, 0, NO_ORBIT, MIXED_CELL), -np.inf, orbit, istate


@njit(cache=True)
def record(advance, rhs, p, start, n_periods, surfaces, opts, n_samples):
    """Integrate n_periods forcing periods from start = (y0, t0, T), writing dense samples;
    returns a ``Recorded`` as plain tuples (see there).

    ``opts[SAMPLE_DT]``/``opts[SAMPLE_T0]`` set the sampling; ``n_samples`` is the capacity.
    Section arrays have n_periods + 1 rows (row 0 is the first section at or after t0).
    """
    y0, t0, period = start
    dim = y0.shape[0]
    y = y0.copy()
    state = new_state(y, surfaces[0], surfaces[1])
    istate, fstate, _ = state
    samples = (np.full(n_samples, np.nan), np.full((n_samples, dim), np.nan))
    section_t = np.full(n_periods + 1, np.nan)
    section_y = np.full((n_periods + 1, dim), np.nan)
    contacts = np.zeros(n_periods + 1, dtype=np.int64)
    max_g = np.full(n_periods + 1, -np.inf)
    n0 = first_section(t0, period)
    status = OK
    if n0 * period > t0:
        status = advance(rhs, p, y, t0, n0 * period, surfaces, opts, state, samples)
    if status == OK:
        section_t[0] = n0 * period
        section_y[0] = y
        contacts[0] = istate[N_CONTACTS]
        max_g[0] = fstate[MAX_G]
        for n in range(1, n_periods + 1):
            t_start = (n0 + n - 1) * period
            status, c, g = one_period(advance, rhs, p, y, t_start, period, surfaces, opts,
                                      state, samples)
            if status != OK:
                break
            section_t[n] = t_start + period
            section_y[n] = y
            contacts[n] = c
            max_g[n] = g
    return ((status, istate[N_SAMPLES]), samples, (section_t, section_y, contacts, max_g),
            (istate, fstate[T_STUCK]))


@njit(cache=True)
def flow(advance, rhs, p, y0, t0, t1, surfaces, opts):
    """State at t1 of the trajectory through (t0, y0). Returns (status, y, max_g, counters)."""
    y = y0.copy()
    state = new_state(y, surfaces[0], surfaces[1])
    status = OK
    if t1 > t0:
        status = advance(rhs, p, y, t0, t1, surfaces, opts, state, no_samples(y.shape[0]))
    return status, y, state[1][MAX_G], state[0]
