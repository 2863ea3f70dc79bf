"""Classical fixed-step Runge-Kutta 4, the study's baseline, with or without switch location.

Steps sit on the grid ``t_start + k (t_end - t_start) / n`` with ``n`` the smallest count
whose step does not exceed ``opts[H_FIXED]`` (T / steps_per_period), so they land exactly
on the stroboscopic times. With ``opts[LOCATE] = 1`` the mode is frozen over a step, a
crossing is found on the cubic Hermite extension, the step is redone up to it and the
integration restarts there before continuing to the next grid point. With
``opts[LOCATE] = 0`` each stage takes its mode from its own state: the study's plain scheme.
"""

import numpy as np
from numba import njit

from .dense import hermite_coefficients
from .driver import fixed_loop
from .layout import K0, YNEW, YTMP
from .switching import mode_of

# traits of the method (kernels.method_traits): rtol/atol steer its steps; steps_per_period
# fixed steps per forcing period; the closed-form flow of piecewise-linear systems
HAS_TOLERANCE = False
FIXED_STEP = True
CLOSED_FORM = False

ORDER = 4
STAGES = 4
C = np.array([0.0, 0.5, 0.5, 1.0])
A = np.array([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 1.0]])
B = np.array([1 / 6, 1 / 3, 1 / 3, 1 / 6])


@njit(cache=True, inline="always")
def rk4_step(rhs, p, t, y, h, mode, locate, A_s, b_s, work):
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


# ---------------------------------------------------------------------------------------
# the method's hooks for the driver (see ``driver``)


@njit(cache=True, inline="always")
def begin(rhs, p, t, y, mode, work, variant):
    rhs(t, y, p, mode, work[K0])
    return 1


@njit(cache=True, inline="always")
def step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant):
    rk4_step(rhs, p, t, y, h, mode, stage_A.shape[0] == 0, stage_A, stage_b, work)
    return True, STAGES


@njit(cache=True, inline="always")
def dense(y, h, work, variant):
    hermite_coefficients(work, y, work[YNEW], work[K0], work[K0 + 4], h)


@njit(cache=True, inline="always")
def accept(y, h, h_next, work, istate, variant):
    """The state moves on; f at the new state was the step's last evaluation."""
    for i in range(y.shape[0]):
        y[i] = work[YNEW, i]
        work[K0, i] = work[K0 + 4, i]
    return False, False


advance = fixed_loop("rk4", begin, step, dense, accept)
