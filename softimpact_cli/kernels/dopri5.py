"""Dormand-Prince 5(4) with Hairer's 4th-order dense output, frozen mode, located switches.

The method is data: the tableau ``A``, ``B``, ``C``, the error weights ``E = B - B_hat``
and the dense-output weights ``D``. ``advance`` integrates from ``t`` to ``t_end`` (landing
exactly on ``t_end``), freezing the contact mode over each step; when the accepted step's
dense output shows that a watched surface was crossed (or grazed), the step is redone up
to the crossing, the mode switches there and the method restarts (no stage is reused
across a switch: the "made_jump" rule).
"""

from math import isfinite, sqrt

import numpy as np
from numba import njit

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
    ATOL,
    BOUND,
    H_MAX,
    K0,
    LOCATE,
    M0,
    MAX_STEPS,
    MAX_SWITCHES,
    MODE,
    N_REJECTED,
    N_RHS,
    N_STEPS,
    RTOL,
    YNEW,
    YTMP,
    H,
)
from .switching import earliest_exit, mode_of

ORDER = 5
STAGES = 7
C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1 / 5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3 / 40, 9 / 40, 0.0, 0.0, 0.0, 0.0],
        [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0, 0.0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0, 0.0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0.0],
        [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
    ]
)
B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0])
B_HAT = np.array(
    [5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40]
)
E = B - B_HAT
# Hairer & Wanner's dense output (dopri5.f, CONTD5): the coefficient of the 5th term.
D = np.array(
    [
        -12715105075 / 11282082432,
        0.0,
        87487479700 / 32700410799,
        -10690763975 / 1880347072,
        701980252875 / 199316789632,
        -1453857185 / 822651844,
        69997945 / 29380423,
    ]
)

SAFETY = 0.9
FAC_MIN = 0.2
FAC_MAX = 10.0
H_FLOOR = 1e-13  # relative to the interval being advanced


@njit(cache=True)
def stages(rhs, p, t, y, h, mode, locate, A_s, b_s, work):
    """Stages K1..K6 (rows 1..6; row 0 holds f(t, y)); solution into row YNEW.

    Row 6 ends as f(t + h, y_new), the first stage of the next step (FSAL). In the plain
    scheme (locate False) each stage takes its mode from its own state.
    """
    dim = y.shape[0]
    for s in range(1, STAGES):
        for i in range(dim):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * work[K0 + j, i]
            work[YTMP, i] = y[i] + h * acc
        m = mode if locate else mode_of(work[YTMP], A_s, b_s)
        rhs(t + C[s] * h, work[YTMP], p, m, work[K0 + s])
    for i in range(dim):
        work[YNEW, i] = work[YTMP, i]  # stage 7's state is the 5th-order solution


@njit(cache=True)
def error_norm(y, h, opts, work):
    dim = y.shape[0]
    acc = 0.0
    for i in range(dim):
        e = 0.0
        for j in range(STAGES):
            e += E[j] * work[K0 + j, i]
        scale = opts[ATOL] + opts[RTOL] * max(abs(y[i]), abs(work[YNEW, i]))
        r = h * e / scale
        acc += r * r
    return sqrt(acc / dim)


@njit(cache=True)
def dense_coefficients(y, h, work):
    """Monomial coefficients of Hairer's continuous extension into rows M0..M0+4."""
    for i in range(y.shape[0]):
        ydiff = work[YNEW, i] - y[i]
        bspl = h * work[K0, i] - ydiff
        r4 = ydiff - h * work[K0 + 6, i] - bspl
        r5 = 0.0
        for j in range(STAGES):
            r5 += D[j] * work[K0 + j, i]
        r5 *= h
        # y(u) = y0 + u(r2 + (1-u)(r3 + u(r4 + (1-u) r5))), expanded in powers of u
        work[M0, i] = y[i]
        work[M0 + 1, i] = ydiff + bspl
        work[M0 + 2, i] = r4 + r5 - bspl
        work[M0 + 3, i] = -(r4 + 2.0 * r5)
        work[M0 + 4, i] = r5


@njit(cache=True)
def advance(rhs, p, y, t, t_end, A_s, b_s, relevance, contact, opts, istate, fstate, work,
            sample_t, sample_y):
    """Integrate ``y`` (in place) from ``t`` to exactly ``t_end``; return a status code."""
    locate = opts[LOCATE] != 0.0
    n_surf = A_s.shape[0]
    coef = np.empty(5)
    span = t_end - t
    h_floor = H_FLOOR * max(span, 1e-300)
    h = fstate[H]
    if h <= 0.0:
        h = min(opts[H_MAX], 0.01 * span)
    need_first = True
    steps = 0
    switches = 0
    while t_end - t > 1e-14 * max(1.0, abs(t_end)):
        mode = istate[MODE]
        if need_first:
            rhs(t, y, p, mode, work[K0])
            istate[N_RHS] += 1
            need_first = False
        h = min(h, opts[H_MAX])
        truncated = False
        h_step = h
        if t + 1.0001 * h >= t_end:
            h_step = t_end - t
            truncated = True
        stages(rhs, p, t, y, h_step, mode, locate, A_s, b_s, work)
        istate[N_RHS] += STAGES - 1
        err = error_norm(y, h_step, opts, work)
        if not isfinite(err) or err > 1.0:
            istate[N_REJECTED] += 1
            fac = FAC_MIN if not isfinite(err) else max(FAC_MIN, SAFETY * err ** (-1.0 / ORDER))
            h = h_step * fac
            if h < h_floor:
                fstate[H] = h
                return STEP_UNDERFLOW
            continue
        fac = FAC_MAX if err == 0.0 else min(FAC_MAX, max(FAC_MIN, SAFETY * err ** (-1.0 / ORDER)))
        h_next = h_step * fac
        if truncated:
            h_next = max(h_next, h)  # landing on t_end says nothing against the old step

        dense_coefficients(y, h_step, work)
        mask = 0
        if locate and n_surf > 0:
            u, mask = earliest_exit(work, A_s, b_s, relevance, mode, coef)
            if mask != 0:
                # Redo the step up to the crossing, in the same frozen mode.
                h_step = u * h_step
                h_next = h  # the controller's proposal stands
                truncated = False
                if h_step <= 0.0:  # leaves right at the start (grazing restart)
                    apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
                    need_first = True
                    switches += 1
                    if switches > opts[MAX_SWITCHES]:
                        return TOO_MANY_SWITCHES
                    continue
                stages(rhs, p, t, y, h_step, mode, locate, A_s, b_s, work)
                istate[N_RHS] += STAGES - 1
                dense_coefficients(y, h_step, work)

        # Accept [t, t + h_step].
        if locate:
            track_contact(work, A_s, b_s, contact, fstate, coef)
        write_samples(work, t, h_step, opts, istate, sample_t, sample_y)
        t = t_end if truncated else t + h_step
        for i in range(y.shape[0]):
            y[i] = work[YNEW, i]
            work[K0, i] = work[K0 + 6, i]
        steps += 1
        istate[N_STEPS] += 1
        if out_of_bounds(y, opts[BOUND]):
            fstate[H] = h_next
            return DIVERGED
        if mask != 0:
            apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
            need_first = True
            switches += 1
            if switches > opts[MAX_SWITCHES]:
                return TOO_MANY_SWITCHES
        elif not locate and n_surf > 0:
            # K6 was evaluated in the mode of its own state, so FSAL still holds.
            plain_mode_update(y, A_s, b_s, contact, istate)
            track_contact_at(y, A_s, b_s, contact, fstate)
        h = h_next
        if steps > opts[MAX_STEPS]:
            fstate[H] = h
            return STEP_BUDGET
    fstate[H] = h
    return OK
