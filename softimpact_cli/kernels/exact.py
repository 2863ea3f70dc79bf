"""exact: the closed-form flow of a piecewise-linear system between its switches.

In every mode m of a piecewise-linear system with harmonic forcing (the bilinear bodies
and pair with a linear stop law),

    y' = M_m y + b_m + u_m sin(w t) + v_m cos(w t),

and with the augmented state ``Y = (y, sin w t, cos w t, 1)`` this is ``Y' = G_m Y``: the
flow over any time tau is ``exp(G_m tau) Y``, with no truncation error. The method steps
with that flow, so what is left is rounding and the location of the switches, which
Newton's method on the flow itself makes exact to rounding too. ``rtol`` and ``atol`` do
not apply.

``systems.piecewise_linear`` packs the modes' data behind the system's parameters (the
rhs reads only its own leading entries): ``p[-1]`` is where the block starts, holding
``n_modes, aug, w, n_surfaces`` and per mode its step ``h_m``, ``G_m``, the quarter
propagator ``exp(G_m h_m / 4)`` and the surfaces' rate matrix ``R_m = A G_m`` (row-major).
``h_m`` turns the fastest mode of ``G_m`` (the forcing's among them) by at most STEP_PHASE
rad, so a quarter step turns it by at most 0.5 rad and a step is at most T / 4.

A step is four quarter steps; at the five nodes the switching functions ``g = A y + b``
and their rates ``g' = R_m Y`` are exact. A watched surface is crossed in a quarter when
``g`` changes side between its nodes, or when ``g'`` changes sign inside it (an
extremum) and ``g`` there is beyond the surface (a grazing excursion): within a quarter
of 0.5 rad ``g'`` changes sign at most once for any solution that is not contrived. The
crossing (and the extremum) is found by safeguarded Newton iterations on the flow's
Taylor series on the quarter (in powers of the fraction of the quarter, built once per
quarter; g along it is then a polynomial whose coefficients are built once per surface,
so an iteration costs a few dozen flops). The contact function's running maximum and
dense samples are exact in the same way. A step shorter than ``h_m`` (landing on
``t_end`` after a switch moved the grid) takes its whole quarters with the propagator and
the rest by the Taylor series, so it has up to four segments of unequal length.

Counters: ``N_STEPS`` counts steps; no right-hand side is evaluated (``N_RHS`` stays).
"""

from math import cos, sin

import numpy as np
from numba import njit

from .borrow import borrow
from .codes import DIVERGED, OK, STEP_BUDGET
from .common import apply_switch, out_of_bounds
from .driver import borrowed, stopped_at_switch
from .layout import (
    BOUND,
    MAX_G,
    MAX_STEPS,
    MAX_SWITCHES,
    MODE,
    N_SAMPLES,
    N_STEPS,
    SAMPLE_DT,
    SAMPLE_T0,
    H,
)
from .linalg import inf_norm, matmul_into

# traits of the method (kernels.method_traits): rtol/atol steer its steps; steps_per_period
# fixed steps per forcing period; the closed-form flow of piecewise-linear systems
HAS_TOLERANCE = False
FIXED_STEP = False
CLOSED_FORM = True

HEADER = 4  # n_modes, aug, w, n_surfaces
STEP_PHASE = 2.0  # rad the fastest mode turns in one step (systems.piecewise_linear)
TAYLOR_TERMS = 60
NEWTON_ITERATIONS = 60
EXTREMUM_TOL = 1e-9  # of a quarter: the value at an extremum is then exact to ~1e-18
NO_ROOT = -1.0
# rows of the scratch buffer: five nodes, the flow's state, a term and its successor;
# then which quarter's series (and which surface's coefficients) the rows below hold, and
# the series' terms. Its last column holds one surface's g along the series (COEF).
NODES, FLOW, TERM, TMP, KEY, SERIES = 0, 5, 6, 7, 8, 9
SCRATCH_ROWS = SERIES + TAYLOR_TERMS
KEY_START, KEY_SPAN, KEY_TERMS, KEY_SURFACE = 0, 1, 2, 3  # columns of row KEY (aug >= 5)


# ---------------------------------------------------------------------------------------
# the packed modes


@njit(cache=True)
def block_start(p):
    return int(p[p.shape[0] - 1])


@njit(cache=True)
def mode_offset(p, base, mode):
    """Where mode ``mode``'s ``h_m`` sits in ``p``; G follows, then the quarter propagator,
    then the surfaces' rate matrix."""
    aug = int(p[base + 1])
    n_surfaces = int(p[base + 3])
    return base + HEADER + mode * (1 + 2 * aug * aug + n_surfaces * aug)


@njit(cache=True)
def mode_matrices(p, at):
    """(G, Q, R) of the mode packed at ``at``: its generator (aug, aug), quarter propagator
    (aug, aug) and rate matrix R = A G (n_surfaces, aug), so that g_i' = R_i Y."""
    base = block_start(p)
    aug = int(p[base + 1])
    n_surfaces = int(p[base + 3])
    a = at + 1
    G = p[a: a + aug * aug].reshape((aug, aug))
    Q = p[a + aug * aug: a + 2 * aug * aug].reshape((aug, aug))
    R = p[a + 2 * aug * aug: a + 2 * aug * aug + n_surfaces * aug].reshape((n_surfaces, aug))
    return G, Q, R


# ---------------------------------------------------------------------------------------
# matrix exponentials


@njit(cache=True)
def expm(G, tau, out, a, b):
    """``out = exp(G tau)`` ((n, n) arrays; ``a``, ``b`` scratch of the same shape): the
    Taylor series of the scaled matrix to rounding, then repeated squaring."""
    n = G.shape[0]
    norm = inf_norm(G) * abs(tau)
    squarings = 0
    while norm > 0.25 and squarings < 64:
        norm *= 0.5
        squarings += 1
    scale = tau / 2.0**squarings
    for i in range(n):
        for j in range(n):
            a[i, j] = G[i, j] * scale
            out[i, j] = a[i, j] + (1.0 if i == j else 0.0)
    for k in range(2, 30):
        matmul_into(a, G, b)
        biggest = 0.0
        for i in range(n):
            for j in range(n):
                b[i, j] = b[i, j] * scale / k
                biggest = max(biggest, abs(b[i, j]))
        for i in range(n):
            for j in range(n):
                a[i, j] = b[i, j]
                out[i, j] += b[i, j]
        if biggest <= 1e-18:
            break
    for _ in range(squarings):
        matmul_into(out, out, b)
        for i in range(n):
            for j in range(n):
                out[i, j] = b[i, j]


@njit(cache=True, inline="always")
def forcing_columns(n, i):
    """The first column row ``i`` of an augmented generator or propagator (n, n) can have
    nonzero: its last three rows (sin w t, cos w t, 1) act on the last three entries only,
    the rest being exact zeros (so a product that skips them makes the same sums)."""
    return 0 if i < n - 3 else n - 3


@njit(cache=True, inline="always")
def taylor_term(G, buf, src, dst, delta, k):
    """Row ``dst`` = the Taylor term after row ``src``: ``G buf[src] delta / k``; its
    largest magnitude (the series' stopping test)."""
    n = G.shape[0]
    biggest = 0.0
    for i in range(n):
        s = 0.0
        for j in range(forcing_columns(n, i), n):
            s += G[i, j] * buf[src, j]
        buf[dst, i] = s * delta / k
        biggest = max(biggest, abs(buf[dst, i]))
    return biggest


@njit(cache=True)
def taylor_flow(G, buf, start, delta):
    """The augmented state ``delta`` after row ``start`` of ``buf``, into row FLOW (a short
    time: the series converges fast)."""
    n = G.shape[0]
    size = 0.0
    for i in range(n):
        buf[FLOW, i] = buf[start, i]
        size = max(size, abs(buf[start, i]))
    src, dst = start, TERM
    for k in range(1, TAYLOR_TERMS):
        biggest = taylor_term(G, buf, src, dst, delta, k)
        for i in range(n):
            buf[FLOW, i] += buf[dst, i]
        if biggest <= 1e-17 * size:
            break
        src, dst = dst, TERM + TMP - dst  # the two term rows in turn


@njit(cache=True, inline="always")
def surface_at(A, b, i, buf, row):
    g = b[i]
    for j in range(A.shape[1]):
        g += A[i, j] * buf[row, j]
    return g


@njit(cache=True, inline="always")
def surface_rate(R, i, buf, row):
    """g_i' at the augmented state in ``row``, from the mode's rate matrix R = A G."""
    r = 0.0
    for j in range(R.shape[1]):
        r += R[i, j] * buf[row, j]
    return r


# ---------------------------------------------------------------------------------------
# roots and extrema on a quarter, by safeguarded Newton on the flow


@njit(cache=True, inline="always")
def tangents_meet(f_a, r_a, f_b, r_b, span):
    """Where the tangents at a quarter's ends meet: a lower bound of f on the quarter when
    f is convex there (r_a < 0 < r_b), an upper bound when concave (r_a > 0 > r_b); the
    extremum is only located when this bound does not already settle the question."""
    return (f_a * r_b - f_b * r_a + r_a * r_b * span) / (r_b - r_a)


@njit(cache=True, inline="always")
def hermite_guess(f_lo, r_lo, f_hi, r_hi, span):
    """A root in (0, span) of the cubic Hermite interpolant of (f, f') at both ends (a
    start for Newton on the flow: one or two iterations there then reach rounding)."""
    x = f_lo * span / (f_lo - f_hi)  # the secant's root
    for _ in range(8):
        u = x / span
        h00 = (1.0 + 2.0 * u) * (1.0 - u) ** 2
        h10 = u * (1.0 - u) ** 2
        h01 = u * u * (3.0 - 2.0 * u)
        h11 = u * u * (u - 1.0)
        p = h00 * f_lo + h10 * span * r_lo + h01 * f_hi + h11 * span * r_hi
        dp = ((6.0 * u * u - 6.0 * u) * f_lo + (3.0 * u * u - 4.0 * u + 1.0) * span * r_lo
              + (6.0 * u - 6.0 * u * u) * f_hi + (3.0 * u * u - 2.0 * u) * span * r_hi) / span
        if dp == 0.0:
            break
        nxt = x - p / dp
        if not (0.0 < nxt < span):
            break
        x = nxt
    return x


@njit(cache=True)
def scratch(aug):
    """The scratch buffer of ``advance`` (rows as above, ``aug + 1`` columns), holding no
    series yet."""
    buf = np.empty((SCRATCH_ROWS, aug + 1))
    forget_series(buf)
    return buf


@njit(cache=True, inline="always")
def forget_series(buf):
    """The series rows no longer match any quarter (the nodes moved on)."""
    buf[KEY, KEY_START] = -1.0


@njit(cache=True)
def quarter_series(G, buf, start, span):
    """The flow's Taylor series on the quarter from node row ``start``, in powers of
    ``u = x / span``: rows SERIES + k hold ``(G span)^k Y / k!`` until a term is below
    rounding, so the state at x in [0, span] is ``sum_k T_k u^k``. Returns the number of
    terms; a series already built for (start, span) is reused (a root and an extremum on
    one quarter, or two surfaces, share it)."""
    if buf[KEY, KEY_START] == start and buf[KEY, KEY_SPAN] == span:
        return int(buf[KEY, KEY_TERMS])
    n = G.shape[0]
    size = 0.0
    for i in range(n):
        buf[SERIES, i] = buf[start, i]
        size = max(size, abs(buf[start, i]))
    terms = TAYLOR_TERMS
    for k in range(1, TAYLOR_TERMS):
        if taylor_term(G, buf, SERIES + k - 1, SERIES + k, span, k) <= 1e-17 * size:
            terms = k + 1
            break
    buf[KEY, KEY_START] = start
    buf[KEY, KEY_SPAN] = span
    buf[KEY, KEY_TERMS] = terms
    buf[KEY, KEY_SURFACE] = -1.0
    return terms


@njit(cache=True)
def surface_series(A, b, i, buf, terms):
    """g_i along the quarter's series: its coefficients in powers of u into column COEF."""
    if buf[KEY, KEY_SURFACE] == i:
        return
    coef = buf.shape[1] - 1
    for k in range(terms):
        c = 0.0
        for j in range(A.shape[1]):
            c += A[i, j] * buf[SERIES + k, j]
        buf[SERIES + k, coef] = c
    buf[SERIES, coef] += b[i]
    buf[KEY, KEY_SURFACE] = i


@njit(cache=True, inline="always")
def series_derivatives(buf, terms, u):
    """(p, dp/du, d2p/du2) at u of the polynomial in column COEF (Horner)."""
    coef = buf.shape[1] - 1
    p = buf[SERIES + terms - 1, coef]
    dp = 0.0
    ddp = 0.0
    for k in range(terms - 2, -1, -1):
        ddp = ddp * u + 2.0 * dp
        dp = dp * u + p
        p = p * u + buf[SERIES + k, coef]
    return p, dp, ddp


@njit(cache=True)
def series_state(G, buf, terms, u):
    """The state at ``u`` of the quarter's series into row FLOW (Horner)."""
    n = G.shape[0]
    for i in range(n):
        v = buf[SERIES + terms - 1, i]
        for k in range(terms - 2, -1, -1):
            v = v * u + buf[SERIES + k, i]
        buf[FLOW, i] = v


@njit(cache=True)
def newton_on_quarter(G, surface, buf, start, span, bracket, of_rate, x):
    """The root in ``bracket = (lo, hi, f_lo, f_hi)`` (within the quarter [0, span] from
    node row ``start``) of ``sign g_i`` (``of_rate`` False) or of ``sign g_i'`` (True),
    ``surface = (A, b, i, sign)``, along the flow, given its values ``f_lo >= 0 > f_hi``
    (or the reverse) at the ends, from the guess ``x`` (outside the bracket: the
    secant's). g and its derivatives are the polynomial of the quarter's Taylor series
    (``quarter_series``), so an iteration costs a few dozen flops. Leaves the flow at the
    root in row FLOW. A root of g is found to rounding; one of g' (an extremum) to
    EXTREMUM_TOL of the bracket, which puts g there within rounding of its extreme value
    (g is flat at the root of g')."""
    A, b, i, sign = surface
    lo, hi, f_lo, f_hi = bracket
    terms = quarter_series(G, buf, start, span)
    surface_series(A, b, i, buf, terms)
    x_tol = EXTREMUM_TOL * (hi - lo) if of_rate else 0.0
    if not (lo < x < hi):
        x = lo + f_lo * (hi - lo) / (f_lo - f_hi) if f_lo != f_hi else 0.5 * (lo + hi)
    positive_low = f_lo >= 0.0
    for _ in range(NEWTON_ITERATIONS):
        p, dp, ddp = series_derivatives(buf, terms, x / span)
        if of_rate:  # g' = p' / span, g'' = p'' / span^2
            f = sign * dp / span
            df = sign * ddp / (span * span)
        else:
            f = sign * p
            df = sign * dp / span
        if f == 0.0:
            break
        if (f >= 0.0) == positive_low:
            lo = x
        else:
            hi = x
        step = -f / df if df != 0.0 else 0.0
        nxt = x + step
        if not (lo < nxt < hi) or df == 0.0:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - x) <= max(1e-16 * max(abs(x), hi - lo), x_tol) or hi - lo <= 1e-300:
            break
        x = nxt
    series_state(G, buf, terms, x / span)
    return x


@njit(cache=True)
def first_exit(G, R, A, b, i, sign, buf, times, last):
    """Earliest time in (0, times[last]] where ``sign g_i`` turns negative (a crossing or a
    grazing excursion), or NO_ROOT; quarters 1..last. The state there is in row FLOW."""
    h_prev = sign * surface_at(A, b, i, buf, NODES)
    on_surface = h_prev <= 0.0
    h_prev = max(h_prev, 0.0)  # a restart on the surface: its residual is rounding
    r_prev = sign * surface_rate(R, i, buf, NODES)
    for q in range(1, last + 1):
        h_q = sign * surface_at(A, b, i, buf, NODES + q)
        r_q = sign * surface_rate(R, i, buf, NODES + q)
        span = times[q] - times[q - 1]
        if q == 1 and on_surface and h_q < 0.0 and r_prev > 0.0 > r_q:
            # a restart on the surface that rises into its mode's side and comes back
            # within the quarter: the exit is after the maximum, not the start's residual
            x_max = newton_on_quarter(G, (A, b, i, sign), buf, NODES, span,
                                      (0.0, span, r_prev, r_q), True, -1.0)
            h_max = sign * surface_at(A, b, i, buf, FLOW)
            if h_max > 0.0:
                x = newton_on_quarter(G, (A, b, i, sign), buf, NODES, span,
                                      (x_max, span, h_max, h_q), False, -1.0)
                return x
        if h_q < 0.0:
            guess = hermite_guess(h_prev, r_prev, h_q, r_q, span)
            x = newton_on_quarter(G, (A, b, i, sign), buf, NODES + q - 1, span,
                                  (0.0, span, h_prev, h_q), False, guess)
            return times[q - 1] + x
        if r_prev < 0.0 < r_q and tangents_meet(h_prev, r_prev, h_q, r_q, span) <= 0.0:
            # a minimum of sign g inside that may lie beyond the surface
            x_min = newton_on_quarter(G, (A, b, i, sign), buf, NODES + q - 1, span,
                                      (0.0, span, r_prev, r_q), True, -1.0)
            h_min = sign * surface_at(A, b, i, buf, FLOW)
            if h_min < 0.0:
                guess = hermite_guess(h_prev, r_prev, h_min, 0.0, x_min)
                x = newton_on_quarter(G, (A, b, i, sign), buf, NODES + q - 1, span,
                                      (0.0, x_min, h_prev, h_min), False, guess)
                return times[q - 1] + x
        h_prev, r_prev = h_q, r_q
    return NO_ROOT


@njit(cache=True)
def contact_maximum(G, R, A, b, i, buf, times, last, end, known):
    """Largest value of g_i on [0, end] (end <= times[last]): the nodes and the maxima
    inside quarters, those that may exceed ``known`` (the running maximum) located."""
    best = surface_at(A, b, i, buf, NODES)
    g_prev = best
    r_prev = surface_rate(R, i, buf, NODES)
    for q in range(1, last + 1):
        r_q = surface_rate(R, i, buf, NODES + q)
        g_q = surface_at(A, b, i, buf, NODES + q)
        if times[q] <= end:
            best = max(best, g_q)
        floor = max(best, known)
        span = times[q] - times[q - 1]
        if r_prev > 0.0 > r_q and tangents_meet(g_prev, r_prev, g_q, r_q, span) > floor:
            x = newton_on_quarter(G, (A, b, i, 1.0), buf, NODES + q - 1, span,
                                  (0.0, span, r_prev, r_q), True, -1.0)
            if times[q - 1] + x <= end:
                best = max(best, surface_at(A, b, i, buf, FLOW))
        g_prev, r_prev = g_q, r_q
    return best


# ---------------------------------------------------------------------------------------
# the step


@njit(cache=True)
def quarter_nodes(Q, G, buf, extra):
    """Nodes 1..4 from node 0 with the quarter propagator ``Q``; node 4 then moves on by
    ``extra`` (a landing step a rounding longer than the mode's)."""
    n = Q.shape[0]
    for q in range(1, 5):
        for i in range(n):
            s = 0.0
            for j in range(forcing_columns(n, i), n):
                s += Q[i, j] * buf[NODES + q - 1, j]
            buf[NODES + q, i] = s
    finish_nodes(G, buf, extra)


@njit(cache=True)
def partial_nodes(Q, G, buf, quarter, h, times):
    """Nodes of a step of ``h`` shorter than its mode's: its whole quarters by the quarter
    propagator, the rest by the flow's Taylor series; node times into ``times``. Returns
    the number of segments (1 .. 4)."""
    n = Q.shape[0]
    whole = min(int(h / quarter), 3)
    if h - whole * quarter <= 1e-12 * h and whole > 0:  # (a rounding short of whole quarters)
        whole -= 1
    for q in range(1, whole + 1):
        for i in range(n):
            s = 0.0
            for j in range(forcing_columns(n, i), n):
                s += Q[i, j] * buf[NODES + q - 1, j]
            buf[NODES + q, i] = s
        times[q] = q * quarter
    taylor_flow(G, buf, NODES + whole, h - whole * quarter)
    for i in range(n):
        buf[NODES + whole + 1, i] = buf[FLOW, i]
    times[whole + 1] = h
    return whole + 1


@njit(cache=True, inline="always")
def finish_nodes(G, buf, extra):
    if extra != 0.0:
        taylor_flow(G, buf, NODES + 4, extra)
        for i in range(G.shape[0]):
            buf[NODES + 4, i] = buf[FLOW, i]


@njit(cache=True)
def write_exact_samples(G, buf, times, last, t, end, opts, istate, sample_t, sample_y):
    """Samples at every sample time in [t, t + end], each from the flow of its segment
    (``last`` segments)."""
    dt = opts[SAMPLE_DT]
    capacity = sample_t.shape[0]
    k = istate[N_SAMPLES]
    dim = sample_y.shape[1]
    while k < capacity:
        ts = opts[SAMPLE_T0] + k * dt
        if ts > t + end * (1.0 + 1e-12):
            break
        x = min(max(ts - t, 0.0), end)
        q = 0
        while q < last - 1 and times[q + 1] <= x:
            q += 1
        taylor_flow(G, buf, NODES + q, x - times[q])
        sample_t[k] = ts
        for i in range(dim):
            sample_y[k, i] = buf[FLOW, i]
        k += 1
    istate[N_SAMPLES] = k


@njit(cache=True)
def step_nodes(G, Q, w, h_mode, y, t, h, buf, times):
    """The nodes of a step of ``h`` from (t, y) in the mode of generator G and quarter
    propagator Q (its step ``h_mode``) and their times; returns the number of segments."""
    dim = y.shape[0]
    forget_series(buf)
    for i in range(dim):
        buf[NODES, i] = y[i]
    buf[NODES, dim] = sin(w * t)
    buf[NODES, dim + 1] = cos(w * t)
    buf[NODES, dim + 2] = 1.0
    times[0] = 0.0
    if abs(h - h_mode) > 1e-6 * h_mode:
        return partial_nodes(Q, G, buf, 0.25 * h_mode, h, times)
    quarter_nodes(Q, G, buf, h - h_mode)
    for q in range(1, 4):
        times[q] = 0.25 * q * h_mode
    times[4] = h
    return 4


@njit(cache=True)
def earliest_crossing(G, R, surfaces, mode, buf, times, last, work):
    """The earliest time a watched surface is crossed in the step, and the mask of every
    surface crossed then ((2 * step, 0): none); the state there into ``work[0]``."""
    A_s, b_s, relevance, _ = surfaces
    dim = A_s.shape[1]
    watched = relevance[mode]
    h = times[last]
    best, mask = 2.0 * h, 0
    for i in range(A_s.shape[0]):
        if not (watched >> i) & 1:
            continue
        sign = 1.0 if (mode >> i) & 1 else -1.0
        x = first_exit(G, R, A_s, b_s, i, sign, buf, times, last)
        if x == NO_ROOT:
            continue
        if x < best - 1e-14 * h:
            best, mask = x, 1 << i
            for j in range(dim):
                work[0, j] = buf[FLOW, j]  # the state on the surface
        elif x <= best + 1e-14 * h:
            mask |= 1 << i
    return best, mask


@njit(cache=True)
def advance(rhs, p, y, t, t_end, surfaces, opts, state, samples):
    """Integrate ``y`` in place from ``t`` to exactly ``t_end`` on the modes' exact flow;
    a status code (see ``driver`` for the conventions; switches are always located)."""
    buf = scratch(int(p[block_start(p) + 1]))
    times = np.empty(5)
    return exact_loop(p, y, t, t_end, surfaces, opts, state, samples, buf, times)


@njit(cache=True)
def exact_loop(p, y, t, t_end, surfaces, opts, state, samples, buf, times):
    """``advance`` with its scratch (``buf``, node ``times``): the caller holds every array,
    so the loop borrows them (``driver.borrowed``: no reference counting per step)."""
    (p, y, opts), (A_s, b_s, relevance, contact), (istate, fstate, work), \
        (sample_t, sample_y) = borrowed(p, y, opts, surfaces, state, samples)
    buf, times = borrow(buf), borrow(times)
    surfaces = (A_s, b_s, relevance, contact)
    dim = y.shape[0]
    base = block_start(p)
    w = p[base + 2]
    sampling = opts[SAMPLE_DT] > 0.0
    steps, switches = 0, 0
    h_mode = 0.0
    while t_end - t > 1e-14 * max(1.0, abs(t_end)):
        mode = istate[MODE]
        at = mode_offset(p, base, mode)
        h_mode = p[at]
        G, Q, R = mode_matrices(p, at)
        remaining = t_end - t
        landing = remaining <= h_mode * (1.0 + 1e-6)
        h = remaining if landing else h_mode
        last = step_nodes(G, Q, w, h_mode, y, t, h, buf, times)
        best, mask = earliest_crossing(G, R, surfaces, mode, buf, times, last, work)
        end = best if mask != 0 else h
        rest, i = contact, 0  # (contact: the bit mask of the contact surfaces)
        while rest != 0:
            if rest & 1:
                g_max = contact_maximum(G, R, A_s, b_s, i, buf, times, last, end,
                                        fstate[MAX_G])
                if mask != 0:  # (the step ends on a surface: g there counts too)
                    g_max = max(g_max, surface_at(A_s, b_s, i, work, 0))
                fstate[MAX_G] = max(fstate[MAX_G], g_max)
            rest >>= 1
            i += 1
        if end > 0.0:  # (a grazing restart, leaving right at the start, takes no step)
            if sampling:
                write_exact_samples(G, buf, times, last, t, end, opts, istate, sample_t,
                                    sample_y)
            if mask != 0:
                for i in range(dim):
                    y[i] = work[0, i]
                t = t + end
            else:
                for i in range(dim):
                    y[i] = buf[NODES + last, i]
                t = t_end if landing else t + h
            istate[N_STEPS] += 1
            steps += 1
            if out_of_bounds(y, opts[BOUND]):
                fstate[H] = h_mode
                return DIVERGED
        if mask != 0:
            apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
            switches += 1
            if switches > opts[MAX_SWITCHES]:
                return stopped_at_switch(fstate, t, h_mode)
        if steps > opts[MAX_STEPS]:
            fstate[H] = h_mode
            return STEP_BUDGET
    fstate[H] = h_mode
    return OK
