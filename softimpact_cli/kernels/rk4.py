"""Classical fixed-step Runge-Kutta 4, the study's baseline, with or without switch location.

Steps sit on the grid ``t_start + k (t_end - t_start) / n`` with ``n`` the smallest count
whose step does not exceed ``opts[H_FIXED]`` (T / steps_per_period), so they land exactly
on the stroboscopic times. With ``opts[LOCATE] = 1`` the mode is frozen over a step, a
crossing is found on the cubic Hermite extension, the step is redone up to it and the
integration restarts there before continuing to the next grid point. With
``opts[LOCATE] = 0`` each stage takes its mode from its own state: the study's plain scheme.
"""

from math import ceil

import numpy as np
from numba import njit

from .codes import DIVERGED, OK, TOO_MANY_SWITCHES
from .common import apply_switch, out_of_bounds, plain_mode_update, track_contact, track_contact_at
from .dense import hermite_coefficients, write_samples
from .layout import BOUND, H_FIXED, K0, LOCATE, MAX_SWITCHES, MODE, N_RHS, N_STEPS, YNEW, YTMP
from .switching import earliest_exit, mode_of

ORDER = 4
STAGES = 4
C = np.array([0.0, 0.5, 0.5, 1.0])
A = np.array([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 1.0]])
B = np.array([1 / 6, 1 / 3, 1 / 3, 1 / 6])


@njit(cache=True)
def step(rhs, p, t, y, h, mode, locate, A_s, b_s, work):
    """One RK4 step from (t, y) with row K0 = f(t, y); result in YNEW, f(t+h, y_new) in K0+4."""
    dim = y.shape[0]
    for s in range(1, STAGES):
        for i in range(dim):
            work[YTMP, i] = y[i] + h * A[s, s - 1] * work[K0 + s - 1, i]
        m = mode if locate else mode_of(work[YTMP], A_s, b_s)
        rhs(t + C[s] * h, work[YTMP], p, m, work[K0 + s])
    for i in range(dim):
        acc = 0.0
        for s in range(STAGES):
            acc += B[s] * work[K0 + s, i]
        work[YNEW, i] = y[i] + h * acc
    m = mode if locate else mode_of(work[YNEW], A_s, b_s)
    rhs(t + h, work[YNEW], p, m, work[K0 + 4])


@njit(cache=True)
def advance(rhs, p, y, t, t_end, A_s, b_s, relevance, contact, opts, istate, fstate, work,
            sample_t, sample_y):
    """Integrate ``y`` (in place) from ``t`` to exactly ``t_end``; return a status code."""
    locate = opts[LOCATE] != 0.0
    n_surf = A_s.shape[0]
    coef = np.empty(5)
    t_start = t
    n = max(1, int(ceil((t_end - t_start) / opts[H_FIXED] - 1e-9)))
    dt = (t_end - t_start) / n
    k = 1
    need_first = True
    switches = 0
    while k <= n:
        target = t_end if k == n else t_start + k * dt
        h = target - t
        if h <= 1e-14 * max(1.0, abs(target)):
            k += 1
            continue
        mode = istate[MODE]
        if need_first:
            rhs(t, y, p, mode, work[K0])
            istate[N_RHS] += 1
            need_first = False
        step(rhs, p, t, y, h, mode, locate, A_s, b_s, work)
        istate[N_RHS] += STAGES
        hermite_coefficients(work, y, work[YNEW], work[K0], work[K0 + 4], h)
        mask = 0
        if locate and n_surf > 0:
            u, mask = earliest_exit(work, A_s, b_s, relevance, mode, coef)
            if mask != 0:
                h = u * h
                if h <= 0.0:
                    apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
                    need_first = True
                    switches += 1
                    if switches > opts[MAX_SWITCHES]:
                        return TOO_MANY_SWITCHES
                    continue
                step(rhs, p, t, y, h, mode, locate, A_s, b_s, work)
                istate[N_RHS] += STAGES
                hermite_coefficients(work, y, work[YNEW], work[K0], work[K0 + 4], h)
        if locate:
            track_contact(work, A_s, b_s, contact, fstate, coef)
        write_samples(work, t, h, opts, istate, sample_t, sample_y)
        for i in range(y.shape[0]):
            y[i] = work[YNEW, i]
            work[K0, i] = work[K0 + 4, i]
        istate[N_STEPS] += 1
        if out_of_bounds(y, opts[BOUND]):
            return DIVERGED
        if mask != 0:
            t = t + h
            apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
            need_first = True
            switches += 1
            if switches > opts[MAX_SWITCHES]:
                return TOO_MANY_SWITCHES
        else:
            t = target
            k += 1
            if not locate and n_surf > 0:
                plain_mode_update(y, A_s, b_s, contact, istate)
                track_contact_at(y, A_s, b_s, contact, fstate)
    return OK
