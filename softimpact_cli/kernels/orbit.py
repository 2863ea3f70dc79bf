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

from math import ceil

import numpy as np
from numba import njit

from .cells import NO_CELL, cell_key, new_cells
from .codes import CONVERGED, MIXED_CELL, NO_ORBIT, OK, UNRESOLVED
from .layout import MAX_G, MODE, N_CONTACTS, N_FSTATE, N_ISTATE, N_SAMPLES, WORK_ROWS
from .switching import mode_of


@njit(cache=True)
def first_section(t0, period):
    """Index of the first section time n T >= t0 (t0 on a section maps to itself)."""
    return int(ceil(t0 / period - 1e-9))


@njit(cache=True)
def new_state(y0, A_s, b_s):
    dim = y0.shape[0]
    istate = np.zeros(N_ISTATE, dtype=np.int64)
    fstate = np.zeros(N_FSTATE)
    fstate[MAX_G] = -np.inf
    work = np.zeros((WORK_ROWS, dim))
    istate[MODE] = mode_of(y0, A_s, b_s)
    return istate, fstate, work


DISTINCT = 100.0  # sub-period differences below DISTINCT * tol mean "still converging"


@njit(cache=True)
def _repeat_distance(hist, n, depth, q, span):
    """max over j < span of |y_{n-j} - y_{n-j-q}|_inf."""
    dim = hist.shape[1]
    worst = 0.0
    for j in range(span):
        a = hist[(n - j) % depth]
        b = hist[(n - j - q) % depth]
        for i in range(dim):
            worst = max(worst, abs(a[i] - b[i]))
    return worst


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
        if _repeat_distance(hist, n, depth, q, q) > lim:
            continue
        for r in range(1, q):
            if q % r == 0 and _repeat_distance(hist, n, depth, r, q) <= DISTINCT * lim:
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
def classify(advance, rhs, p, y0, t0, period, A_s, b_s, relevance, contact, opts,
             max_periods, max_orbit_period, tol):
    """``classify_near`` with no known orbits: stop when the section points repeat."""
    dim = y0.shape[0]
    status, q, n, orbit, total, worst, istate, _, _ = classify_near(
        advance, rhs, p, y0, t0, period, A_s, b_s, relevance, contact, opts, max_periods,
        max_orbit_period, tol, np.zeros((0, 1, dim)), np.zeros(0, dtype=np.int64),
        np.zeros(0), 0.0, 1, new_cells(), 0.0, 1, np.empty(0, dtype=np.int64))
    return status, q, n, orbit, total, worst, istate


@njit(cache=True)
def classify_near(advance, rhs, p, y0, t0, period, A_s, b_s, relevance, contact, opts,
                  max_periods, max_orbit_period, tol, known, known_q, known_max_g,
                  capture_tol, capture_hits, cells, cell_size, cell_hits, visited):
    """Integrate from (t0, y0) until the section points repeat, or follow a known orbit,
    or the budget ends, or it fails.

    known : (K, Q, dim) section points of K known stable orbits in time order (rows
    0..known_q[k]-1 used); known_q : (K,) their periods; known_max_g : (K,) their max of
    the contact function; capture_tol, capture_hits : capture after this many consecutive
    periods, each within capture_tol * max(1, |y|) of the known orbit's next point and
    without contact (capture_tol = 0 disables capture).
    cells : {cell key: label code} of earlier trajectories (``kernels.cells``); cell_size
    (0 disables), cell_hits : take a cell label after this many consecutive periods in
    cells of that label; visited : (max_periods + 1,) int64, receives the cell keys of
    the section points in order (its length bounds what is recorded).

    Returns
    -------
    status : int (status table code)
    q : int, period of the orbit in forcing periods (0 unless converged)
    n_used : int, forcing periods integrated
    orbit : (max(max_orbit_period, Q), dim) array, rows 0..q-1 the orbit's section points in
            time order (a captured trajectory returns the known orbit)
    contacts : int, contact onsets during the last q periods
    max_g : float, max of the contact function x1 - x2 - d over the last q periods
            (>= 0 means the orbit is in contact; -inf for systems without contact)
    counters : (N_ISTATE,) int64 array of the integrator's counters
    captured : int, index of the known orbit that captured the trajectory, else -1
    cell_code : int, the label code taken from the cells (status CONVERGED, q = 0, orbit
                unknown), else MIXED_CELL; ``visited`` then holds n_used + 1 keys
    """
    dim = y0.shape[0]
    y = y0.copy()
    istate, fstate, work = new_state(y, A_s, b_s)
    empty_t = np.empty(0)
    empty_y = np.empty((0, dim))
    depth = 2 * max_orbit_period + 1
    hist = np.empty((depth, dim))
    contacts = np.zeros(depth, dtype=np.int64)
    max_g = np.full(depth, -np.inf)
    orbit = np.zeros((max(max_orbit_period, known.shape[1]), dim))
    n0 = first_section(t0, period)
    t = t0
    if n0 * period > t:
        status = advance(rhs, p, y, t, n0 * period, A_s, b_s, relevance, contact, opts,
                         istate, fstate, work, empty_t, empty_y)
        if status != OK:
            return status, 0, 0, orbit, 0, -np.inf, istate, NO_ORBIT, MIXED_CELL
    hist[0] = y
    use_cells = cell_size > 0.0 and visited.shape[0] > 0
    run, run_code = 0, MIXED_CELL
    if use_cells:
        visited[0] = cell_key(y, cell_size)
    use_known = capture_tol > 0.0 and known.shape[0] > 0
    streak, last_k, last_j = 0, -1, -1
    for n in range(1, max_periods + 1):
        fstate[MAX_G] = -np.inf
        if contact >= 0 and (istate[MODE] >> contact) & 1:
            fstate[MAX_G] = 0.0  # a period that starts in contact is in contact
        c_before = istate[N_CONTACTS]
        t_start = (n0 + n - 1) * period
        status = advance(rhs, p, y, t_start, t_start + period, A_s, b_s, relevance, contact,
                         opts, istate, fstate, work, empty_t, empty_y)
        if status != OK:
            return status, 0, n, orbit, 0, -np.inf, istate, NO_ORBIT, MIXED_CELL
        k = n % depth
        hist[k] = y
        contacts[k] = istate[N_CONTACTS] - c_before
        max_g[k] = fstate[MAX_G]
        if use_cells and n < visited.shape[0]:  # every visited key is written, whatever
            key = cell_key(y, cell_size)        # classifies the trajectory below
            visited[n] = key
            code = cells.get(key, MIXED_CELL) if key != NO_CELL else MIXED_CELL
            if code == MIXED_CELL:
                run = 0
            elif code == run_code:
                run += 1
            else:
                run, run_code = 1, code
        if use_known:
            scale = 1.0
            for i in range(dim):
                scale = max(scale, abs(y[i]))
            hit_k, hit_j = -1, -1
            if contacts[k] == 0 and not (contact >= 0 and (istate[MODE] >> contact) & 1):
                hit_k, hit_j = _nearest_known(y, known, known_q, capture_tol * scale)
            if hit_k >= 0 and hit_k == last_k and hit_j == (last_j + 1) % known_q[hit_k]:
                streak += 1
            elif hit_k >= 0:
                streak = 1
            else:
                streak = 0
            last_k, last_j = hit_k, hit_j
            if streak >= capture_hits:
                q = known_q[hit_k]
                for i in range(q):  # the known orbit, time order, ending at point hit_j
                    orbit[i] = known[hit_k, (hit_j - q + 1 + i) % q]
                return CONVERGED, q, n, orbit, 0, known_max_g[hit_k], istate, hit_k, MIXED_CELL
        if run >= cell_hits:
            return CONVERGED, 0, n, orbit, 0, -np.inf, istate, -1, run_code
        q = _repeat_period(hist, n, depth, max_orbit_period, tol)
        if q > 0:
            total = 0
            worst = -np.inf
            for i in range(q):
                kk = (n - q + 1 + i) % depth
                orbit[i] = hist[kk]
                total += contacts[kk]
                worst = max(worst, max_g[kk])
            return CONVERGED, q, n, orbit, total, worst, istate, NO_ORBIT, MIXED_CELL
    return UNRESOLVED, 0, max_periods, orbit, 0, -np.inf, istate, NO_ORBIT, MIXED_CELL


@njit(cache=True)
def record(advance, rhs, p, y0, t0, period, n_periods, A_s, b_s, relevance, contact, opts,
           n_samples):
    """Integrate n_periods forcing periods from (t0, y0), writing dense samples.

    ``opts[SAMPLE_DT]``/``opts[SAMPLE_T0]`` set the sampling; ``n_samples`` is the capacity.
    Returns (status, sample_t, sample_y, n_written, section_t, section_y, contacts per
    period, max contact function per period, counters); section arrays have n_periods + 1
    rows (row 0 is the first section at or after t0); rows after a failure are NaN.
    """
    dim = y0.shape[0]
    y = y0.copy()
    istate, fstate, work = new_state(y, A_s, b_s)
    sample_t = np.full(n_samples, np.nan)
    sample_y = np.full((n_samples, dim), np.nan)
    section_t = np.full(n_periods + 1, np.nan)
    section_y = np.full((n_periods + 1, dim), np.nan)
    contacts = np.zeros(n_periods + 1, dtype=np.int64)
    max_g = np.full(n_periods + 1, -np.inf)
    n0 = first_section(t0, period)
    t = t0
    status = OK
    if n0 * period > t:
        status = advance(rhs, p, y, t, n0 * period, A_s, b_s, relevance, contact, opts,
                         istate, fstate, work, sample_t, sample_y)
    if status == OK:
        section_t[0] = n0 * period
        section_y[0] = y
        contacts[0] = istate[N_CONTACTS]
        max_g[0] = fstate[MAX_G]
        for n in range(1, n_periods + 1):
            fstate[MAX_G] = -np.inf
            if contact >= 0 and (istate[MODE] >> contact) & 1:
                fstate[MAX_G] = 0.0
            c_before = istate[N_CONTACTS]
            t_start = (n0 + n - 1) * period
            status = advance(rhs, p, y, t_start, t_start + period, A_s, b_s, relevance,
                             contact, opts, istate, fstate, work, sample_t, sample_y)
            if status != OK:
                break
            section_t[n] = t_start + period
            section_y[n] = y
            contacts[n] = istate[N_CONTACTS] - c_before
            max_g[n] = fstate[MAX_G]
    return (status, sample_t, sample_y, istate[N_SAMPLES], section_t, section_y, contacts, max_g,
            istate)


@njit(cache=True)
def flow(advance, rhs, p, y0, t0, t1, A_s, b_s, relevance, contact, opts):
    """State at t1 of the trajectory through (t0, y0). Returns (status, y, max_g, counters)."""
    y = y0.copy()
    istate, fstate, work = new_state(y, A_s, b_s)
    status = OK
    if t1 > t0:
        status = advance(rhs, p, y, t0, t1, A_s, b_s, relevance, contact, opts, istate, fstate,
                         work, np.empty(0), np.empty((0, y.shape[0])))
    return status, y, fstate[MAX_G], istate
