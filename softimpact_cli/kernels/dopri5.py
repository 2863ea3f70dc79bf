"""Dormand-Prince 5(4) with Hairer's 4th-order dense output.

The method is data: the tableau ``A``, ``B``, ``C``, the error weights ``E = B - B_hat``
and the dense-output weights ``D``; its step, error norm and dense output are the hooks
``advance`` hands to the adaptive loop of ``driver`` (frozen mode, located switches, no
stage reused across a switch: the "made_jump" rule).
"""

from math import sqrt

import numpy as np
from numba import njit

from .control import Controller
from .driver import adaptive_loop, no_change, no_refinement, same_method
from .layout import ATOL, K0, M0, RTOL, YNEW, YTMP
from .switching import mode_of

# traits of the method (kernels.method_traits): rtol/atol steer its steps; steps_per_period
# fixed steps per forcing period; the closed-form flow of piecewise-linear systems
HAS_TOLERANCE = True
FIXED_STEP = False
CLOSED_FORM = False

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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


# ---------------------------------------------------------------------------------------
# the method's hooks for the driver (see ``driver``)


@njit(cache=True, inline="always")
def begin(rhs, p, t, y, mode, work, variant):
    rhs(t, y, p, mode, work[K0])
    return 1


@njit(cache=True, inline="always")
def step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant):
    stages(rhs, p, t, y, h, mode, stage_A.shape[0] == 0, stage_A, stage_b, work)
    return True, STAGES - 1


@njit(cache=True, inline="always")
def error(y, h, work, opts, variant):
    return error_norm(y, h, opts, work)


@njit(cache=True, inline="always")
def controller(variant):
    return Controller(ORDER, SAFETY, FAC_MIN, FAC_MAX, FAC_MIN, False)


@njit(cache=True, inline="always")
def dense(y, h, work, variant):
    dense_coefficients(y, h, work)


@njit(cache=True, inline="always")
def accept(y, h, h_next, work, istate, variant):
    """The state moves on; first same as last: stage 7 is f at the new state."""
    for i in range(y.shape[0]):
        y[i] = work[YNEW, i]
        work[K0, i] = work[K0 + 6, i]
    return False, False


advance = adaptive_loop("dopri5", begin, step, error, controller, dense, no_refinement, accept,
                        no_change, same_method)
