"""auto: Dormand-Prince while its step is accuracy bound, Rodas4 while it is stability bound.

A stop is stiff only while it is engaged, so stiffness belongs to a contact *mode*; free
flight stays non-stiff. ``advance`` therefore decides step by step and remembers per mode:

* **explicit** (``dopri5``'s steps, arithmetic identical to ``dopri5.advance``): after
  every ``TEST_EVERY``-th accepted step (every step once one looked stiff), Hairer's
  estimate ``h |lambda| ~ h ||k7 - k6|| / ||y7 - y6||`` from the two stages at ``t + h``
  (the test of ``dopri5.f``; Hairer & Wanner, *Solving ODEs II*, section IV.2). Above
  ``STIFF_EDGE`` = 3.25 (the stability region ends near -3.3 on the real axis) the
  controller is holding the step at the stability limit. With Hairer's counting
  (``STIFF_HITS`` such steps, forgotten after ``CALM_STEPS`` calm ones in a row) the
  method switches to Rodas4 and flags the mode.
* **stiff** (``rosenbrock``'s steps, Jacobian by differences, as ``rosenbrock.advance``):
  after every accepted step, an upper bound of the spectral radius of the step's
  Jacobian, ``rho <= ||J^16||_inf^(1/16)`` (Gelfand's formula, four rescaled squarings).
  When ``h_next rho < BACK`` for ``BACK_STEPS`` steps in a row, the explicit step would be
  stable with margin and cheaper (6 right-hand sides against ~12 and a factorisation):
  back to dopri5, the mode's flag cleared, and the next ``COOLDOWN`` tests are skipped
  (hysteresis: no ping-pong within a phase).
* **a mode switch** starts the new phase with the method its mode's flag names, so after
  the first stiff contact every later one begins with Rodas4 at once.

Counters (``layout``): ``N_STIFF_STEPS`` accepted Rodas4 steps (the explicit ones are
``N_STEPS`` minus these), ``N_METHOD_SWITCHES``. The running state (``AUTO_*``) lives in
``istate`` so that it carries across calls, one forcing period each.
"""

from math import exp, isfinite, log, sqrt

import numpy as np
from numba import njit

from . import dopri5 as dp
from . import rosenbrock as ro
from .codes import DIVERGED, OK, STEP_BUDGET, STEP_UNDERFLOW, TOO_MANY_SWITCHES
from .common import (
    apply_switch,
    out_of_bounds,
    plain_mode_update,
    track_contact,
    track_contact_at,
)
from .dense import write_samples
from .layout import (
    AUTO_CALM,
    AUTO_COOLDOWN,
    AUTO_HITS,
    AUTO_STIFF,
    AUTO_STIFF_MODES,
    BOUND,
    H_MAX,
    K0,
    LOCATE,
    MAX_STEPS,
    MAX_SWITCHES,
    MODE,
    N_METHOD_SWITCHES,
    N_REJECTED,
    N_RHS,
    N_STEPS,
    N_STIFF_STEPS,
    YNEW,
    H,
)
from .switching import earliest_exit

ORDER = 4  # the lower of the two methods' orders (dopri5 5, rodas4 4)
STIFF_EDGE = 3.25  # h |lambda| above which dopri5's step is stability bound (dopri5.f)
STIFF_HITS = 15  # dopri5.f's count of stability-bound steps before declaring stiffness
CALM_STEPS = 6  # ... forgotten after this many calm steps in a row
TEST_EVERY = 16  # test every 16th explicit step (cost ~1 %), every step once one hit
BACK = 1.0  # rodas4 -> dopri5 when h_next * rho_bound < BACK ...
BACK_STEPS = 4  # ... for this many accepted steps in a row (not on a transient's first steps)
COOLDOWN = 4  # tests skipped after a return to dopri5 (~ 64 explicit steps)
SQUARINGS = 4  # rho <= ||J^(2^SQUARINGS)||^(1/2^SQUARINGS)
H_FLOOR = 1e-13  # relative to the interval being advanced

# rows of the stiff method's scratch array (allocated on first use, shape (ROWS + 3 dim, dim))
F0, DFDT, YT, FT, U0 = 0, 1, 2, 3, 4  # f(t, y), f_t, stage state, stage rhs, U rows 4..9
JAC = U0 + ro.STAGES  # then the Jacobian, its LU factors and a squaring scratch (dim rows each)
ROWS = JAC


# ---------------------------------------------------------------------------------------
# stiffness estimates


@njit(cache=True)
def explicit_stiffness(y, h, work):
    """Hairer's h |lambda| ~ h ||k7 - k6|| / ||y7 - y6|| of the dopri5 step just taken.

    ``y`` is the step's start; ``work`` holds its stages (rows K0..K0+6) and solution
    (YNEW). Stage 6's state is rebuilt from the stages (``dopri5.stages`` overwrote it).
    """
    num = 0.0
    den = 0.0
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(5):
            acc += dp.A[5, j] * work[K0 + j, i]
        dk = work[K0 + 6, i] - work[K0 + 5, i]
        dy = work[YNEW, i] - (y[i] + h * acc)
        num += dk * dk
        den += dy * dy
    if den > 0.0:
        return h * sqrt(num / den)
    return 0.0


@njit(cache=True)
def inf_norm(a):
    worst = 0.0
    for i in range(a.shape[0]):
        s = 0.0
        for j in range(a.shape[1]):
            s += abs(a[i, j])
        worst = max(worst, s)
    return worst


@njit(cache=True)
def spectral_radius_bound(jac, a, b):
    """Upper bound ``||J^(2^k)||_inf^(1/2^k) >= rho(J)``, k = SQUARINGS (Gelfand).

    Each squaring is rescaled to norm 1 and the scale kept as a logarithm, so nothing
    overflows; ``a``, ``b`` are (dim, dim) scratch. Tight within (dim kappa)^(1/16) for a
    diagonalisable J with eigenvector condition number kappa.
    """
    n = jac.shape[0]
    norm = inf_norm(jac)
    if norm == 0.0 or not isfinite(norm):
        return norm
    log_c = log(norm)
    for i in range(n):
        for j in range(n):
            a[i, j] = jac[i, j] / norm
    for _ in range(SQUARINGS):
        for i in range(n):
            for j in range(n):
                s = 0.0
                for k in range(n):
                    s += a[i, k] * a[k, j]
                b[i, j] = s
        m = inf_norm(b)
        if m == 0.0:
            return 0.0  # nilpotent
        log_c = 2.0 * log_c + log(m)
        for i in range(n):
            for j in range(n):
                a[i, j] = b[i, j] / m
    return exp(log_c / 2.0**SQUARINGS)


# ---------------------------------------------------------------------------------------
# the method's state machine


@njit(cache=True)
def explicit_says_stiff(y, h, work, istate):
    """Hairer's counting on the explicit step just taken; True: switch to the stiff method."""
    h_lambda = explicit_stiffness(y, h, work)
    if istate[AUTO_COOLDOWN] > 0:
        istate[AUTO_COOLDOWN] -= 1
        return False
    if h_lambda > STIFF_EDGE:
        istate[AUTO_CALM] = 0
        istate[AUTO_HITS] += 1
        return istate[AUTO_HITS] >= STIFF_HITS
    istate[AUTO_CALM] += 1
    if istate[AUTO_CALM] >= CALM_STEPS:
        istate[AUTO_HITS] = 0
    return False


@njit(cache=True)
def stiff_says_explicit(h_next, scratch, istate):
    """True when the explicit step h_next would have been stable BACK_STEPS times in a row."""
    dim = scratch.shape[1]
    rho = spectral_radius_bound(scratch[JAC:JAC + dim], scratch[JAC + dim:JAC + 2 * dim],
                                scratch[JAC + 2 * dim:JAC + 3 * dim])
    if h_next * rho < BACK:
        istate[AUTO_CALM] += 1
        return istate[AUTO_CALM] >= BACK_STEPS
    istate[AUTO_CALM] = 0
    return False


@njit(cache=True)
def switch_method(istate, mode):
    """Flip the method within a phase in ``mode``; the mode's flag follows."""
    if istate[AUTO_STIFF] != 0:
        istate[AUTO_STIFF] = 0
        istate[AUTO_STIFF_MODES] &= ~(1 << mode)
        istate[AUTO_COOLDOWN] = COOLDOWN
    else:
        istate[AUTO_STIFF] = 1
        istate[AUTO_STIFF_MODES] |= 1 << mode
    istate[AUTO_HITS] = 0
    istate[AUTO_CALM] = 0
    istate[N_METHOD_SWITCHES] += 1


@njit(cache=True)
def enter_mode(istate):
    """A new phase: the method the mode's flag names. True when the method changed."""
    want = (istate[AUTO_STIFF_MODES] >> istate[MODE]) & 1
    istate[AUTO_HITS] = 0
    istate[AUTO_CALM] = 0
    istate[AUTO_COOLDOWN] = 0
    if want == istate[AUTO_STIFF]:
        return False
    istate[AUTO_STIFF] = want
    istate[N_METHOD_SWITCHES] += 1
    return True


# ---------------------------------------------------------------------------------------
# Rodas4 on the scratch rows


@njit(cache=True)
def stiff_first(rhs, p, t, y, mode, s):
    """f, J and f_t at (t, y) into the scratch rows; returns the rhs evaluations used."""
    dim = y.shape[0]
    rhs(t, y, p, mode, s[F0])
    return 1 + ro.fd_jacobian(rhs, p, t, y, mode, s[F0], s[JAC:JAC + dim], s[DFDT], s[YT],
                              s[FT])


@njit(cache=True)
def stiff_step(rhs, p, t, y, h, mode, locate, A_s, b_s, s, piv, ynew):
    dim = y.shape[0]
    return ro.step(rhs, p, t, y, h, mode, locate, A_s, b_s, s[F0], s[JAC:JAC + dim], s[DFDT],
                   s[JAC + dim:JAC + 2 * dim], piv, s[U0:U0 + ro.STAGES], s[YT], s[FT], ynew)


@njit(cache=True)
def stiff_refine(rhs, p, t, y, h_step, h_full, mode, locate, A_s, b_s, mask, s, piv, ynew,
                 work, coef, istate):
    dim = y.shape[0]
    return ro.refine_crossing(rhs, p, t, y, h_step, h_full, mode, locate, A_s, b_s, mask,
                              s[F0], s[JAC:JAC + dim], s[DFDT], s[JAC + dim:JAC + 2 * dim], piv,
                              s[U0:U0 + ro.STAGES], s[YT], s[FT], ynew, work, coef, istate)


# ---------------------------------------------------------------------------------------
# the integrator


@njit(cache=True)
def advance(rhs, p, y, t, t_end, A_s, b_s, relevance, contact, opts, istate, fstate, work,
            sample_t, sample_y):
    """Integrate ``y`` (in place) from ``t`` to exactly ``t_end``; return a status code."""
    locate = opts[LOCATE] != 0.0
    n_surf = A_s.shape[0]
    dim = y.shape[0]
    coef = np.empty(5)
    scratch = np.empty((0, dim))  # Rodas4's arrays: allocated when first needed
    piv = np.empty(0, dtype=np.int64)
    ynew = work[YNEW]
    span = t_end - t
    h_floor = H_FLOOR * max(span, 1e-300)
    h = fstate[H]
    if h <= 0.0:
        h = min(opts[H_MAX], 0.01 * span)
    need_first = True
    rejected = False
    steps = 0
    switches = 0
    while t_end - t > 1e-14 * max(1.0, abs(t_end)):
        mode = istate[MODE]
        stiff = istate[AUTO_STIFF] != 0
        if stiff and scratch.shape[0] == 0:
            scratch = np.empty((ROWS + 3 * dim, dim))
            piv = np.empty(dim, dtype=np.int64)
        if need_first:
            if stiff:
                istate[N_RHS] += stiff_first(rhs, p, t, y, mode, scratch)
            else:
                rhs(t, y, p, mode, work[K0])
                istate[N_RHS] += 1
            need_first = False
        h = min(h, opts[H_MAX])
        truncated = False
        h_step = h
        if t + 1.0001 * h >= t_end:
            h_step = t_end - t
            truncated = True
        ok = True
        if stiff:
            ok = stiff_step(rhs, p, t, y, h_step, mode, locate, A_s, b_s, scratch, piv, ynew)
            istate[N_RHS] += ro.STAGES - 1
            err = ro.error_norm(y, ynew, scratch[U0:U0 + ro.STAGES], opts) if ok else np.inf
        else:
            dp.stages(rhs, p, t, y, h_step, mode, locate, A_s, b_s, work)
            istate[N_RHS] += dp.STAGES - 1
            err = dp.error_norm(y, h_step, opts, work)
        if not isfinite(err) or err > 1.0:
            istate[N_REJECTED] += 1
            if not stiff:
                fac = dp.FAC_MIN if not isfinite(err) else max(
                    dp.FAC_MIN, dp.SAFETY * err ** (-1.0 / dp.ORDER))
            else:
                rejected = True
                if not ok:
                    fac = 0.5
                elif not isfinite(err):
                    fac = ro.FAC_MIN
                else:
                    fac = max(ro.FAC_MIN, ro.SAFETY * err ** (-1.0 / ro.ORDER))
            h = h_step * fac
            if h < h_floor:
                fstate[H] = h
                return STEP_UNDERFLOW
            continue
        if not stiff:
            fac = dp.FAC_MAX if err == 0.0 else min(
                dp.FAC_MAX, max(dp.FAC_MIN, dp.SAFETY * err ** (-1.0 / dp.ORDER)))
            h_next = h_step * fac
        else:
            fac = ro.FAC_MAX if err == 0.0 else min(
                ro.FAC_MAX, max(ro.FAC_MIN, ro.SAFETY * err ** (-1.0 / ro.ORDER)))
            h_next = h_step * fac
            if rejected:
                h_next = min(h_next, h_step)  # no growth right after a rejection
            rejected = False
        if truncated:
            h_next = max(h_next, h)  # landing on t_end says nothing against the old step

        if stiff:
            ro.dense_coefficients(y, ynew, scratch[U0:U0 + ro.STAGES], work)
        else:
            dp.dense_coefficients(y, h_step, work)
        mask = 0
        if locate and n_surf > 0:
            u, mask = earliest_exit(work, A_s, b_s, relevance, mode, coef)
            if mask != 0:
                # Redo the step up to the crossing, in the same frozen mode.
                h_full = h_step
                h_step = u * h_step
                h_next = h  # the controller's proposal stands
                truncated = False
                if h_step <= 0.0:  # leaves right at the start (grazing restart)
                    apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
                    enter_mode(istate)
                    need_first = True
                    switches += 1
                    if switches > opts[MAX_SWITCHES]:
                        return TOO_MANY_SWITCHES
                    continue
                if stiff:
                    ok = stiff_step(rhs, p, t, y, h_step, mode, locate, A_s, b_s, scratch, piv,
                                    ynew)
                    istate[N_RHS] += ro.STAGES - 1
                    if not ok:  # a shorter step than an accepted one: only on breakdown
                        fstate[H] = h_step
                        return STEP_UNDERFLOW
                    ro.dense_coefficients(y, ynew, scratch[U0:U0 + ro.STAGES], work)
                    h_step = stiff_refine(rhs, p, t, y, h_step, h_full, mode, locate, A_s, b_s,
                                          mask, scratch, piv, ynew, work, coef, istate)
                else:
                    dp.stages(rhs, p, t, y, h_step, mode, locate, A_s, b_s, work)
                    istate[N_RHS] += dp.STAGES - 1
                    dp.dense_coefficients(y, h_step, work)

        # Accept [t, t + h_step]; the stiffness test reads the step before y moves on.
        if locate:
            track_contact(work, A_s, b_s, contact, fstate, coef)
        write_samples(work, t, h_step, opts, istate, sample_t, sample_y)
        change = False
        if stiff:
            change = stiff_says_explicit(h_next, scratch, istate)
        elif istate[AUTO_HITS] > 0 or istate[N_STEPS] % TEST_EVERY == 0:
            change = explicit_says_stiff(y, h_step, work, istate)
        t = t_end if truncated else t + h_step
        for i in range(dim):
            y[i] = ynew[i]
        if stiff:
            need_first = True  # Rodas4 is not FSAL
            istate[N_STIFF_STEPS] += 1
        else:
            for i in range(dim):
                work[K0, i] = work[K0 + 6, i]
        steps += 1
        istate[N_STEPS] += 1
        if out_of_bounds(y, opts[BOUND]):
            fstate[H] = h_next
            return DIVERGED
        if change:
            switch_method(istate, mode)
            need_first = True
            rejected = False
        if mask != 0:
            apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
            if enter_mode(istate):
                rejected = False
            need_first = True
            switches += 1
            if switches > opts[MAX_SWITCHES]:
                return TOO_MANY_SWITCHES
        elif not locate and n_surf > 0:
            # K6 was evaluated in the mode of its own state, so FSAL still holds.
            plain_mode_update(y, A_s, b_s, contact, istate)
            track_contact_at(y, A_s, b_s, contact, fstate)
            if istate[MODE] != mode and enter_mode(istate):
                need_first = True
                rejected = False
        h = h_next
        if steps > opts[MAX_STEPS]:
            fstate[H] = h
            return STEP_BUDGET
    fstate[H] = h
    return OK
