"""Rodas4: an L-stable, stiffly accurate Rosenbrock method of order 4(3), frozen mode.

For stiff stops (large ``k_c`` or ``c_c``) the explicit pairs become stability bound in
contact. Rodas4 (Hairer & Wanner, *Solving ODEs II*, section IV.7; the coefficients of
``rodas.f``, ``METH = 1``) is linearly implicit: each step factors ``E = I/(gamma h) - J``
once and solves six linear systems, in Hairer's transformed form without matrix products

    E U_i = f(t + c_i h, y + sum_{j<i} a_ij U_j) + sum_{j<i} (c_ij / h) U_j + h d_i f_t

with the exact Jacobian ``J = df/dy`` and ``f_t = df/dt`` of the frozen mode. The method
is stiffly accurate: stage 6 is evaluated at the embedded 3rd-order solution ``y + sum_j
a_6j U_j`` and ``y_1 = that + U_6``, so ``U_6`` is the error estimate; the stability
function vanishes at infinity (L-stable). The dense output is Hairer's 3rd-order
continuous extension ``y(s) = (1-s) y0 + s (y1 + (1-s) (k1 + s k2))``, ``k1 = sum D2_j
U_j``, ``k2 = sum D3_j U_j``, stored as monomial rows like every method's.

Switches are handled as in ``dopri5``: the mode is frozen over a step, the accepted
step's dense output is searched for a crossing (``earliest_exit``), the step is redone up
to it in the same mode, the mode switches there and the method restarts with a fresh
Jacobian. One addition: the dense output is only 3rd order, so the redone step's length
is corrected by a few Newton iterations on ``g(y_1(h)) = 0`` (``refine_crossing``);
without it the crossing's time error shows up as erratic ~3rd-order global errors at
every contact of the paper law (whose force jumps at onset). Steps land exactly on
``t_end``.

Two entry points, built by the adaptive loop of ``driver``:

* ``advance(rhs, p, y, ...)``: the standard signature of every method, so the trajectory
  kernels take it unchanged; the Jacobian and ``f_t`` are differences of ``rhs`` in the
  frozen mode (``linalg.fd_jacobian``);
* ``with_jacobian(jac)(rhs, p, y, ...)``: the system's analytic ``jac(t, y, p, mode,
  jac, dfdt)``.

Every array lives in rows of the driver's ``work`` array (``layout``: F0, DFDT, YT, FT,
U0.., PIV, JAC..).
"""

from functools import cache
from math import sqrt

import numpy as np
from numba import njit

from .control import Controller
from .driver import adaptive_loop, no_change, same_method
from .layout import ATOL, DFDT, F0, FT, JAC, M0, N_STIFF_STEPS, PIV, RTOL, U0, YNEW, YT
from .linalg import fd_jacobian, lu_factor, lu_solve
from .switching import mode_of, poly_rate

# traits of the method (kernels.method_traits): rtol/atol steer its steps; steps_per_period
# fixed steps per forcing period; the closed-form flow of piecewise-linear systems
HAS_TOLERANCE = True
FIXED_STEP = False
CLOSED_FORM = False

ORDER = 4  # of the solution; the embedded one is 3 (error estimate ~ h^4)
STAGES = 6
GAMMA = 0.25
# Stage times c_i and the f_t weights d_i (= row sums of the method's Gamma matrix).
C = np.array([0.0, 0.386, 0.21, 0.63, 1.0, 1.0])
D = np.array([0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0])
# Transformed stage coefficients a_ij (state of stage i = y + sum_j a_ij U_j).
A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.544, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.9466785280815826, 0.2557011698983284, 0.0, 0.0, 0.0, 0.0],
        [3.314825187068521, 2.896124015972201, 0.9986419139977817, 0.0, 0.0, 0.0],
        [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950, 0.0,
         0.0],
        [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950, 1.0,
         0.0],
    ]
)
# Transformed coupling coefficients c_ij (right-hand side gets sum_j c_ij / h U_j).
CC = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [-5.6688, 0.0, 0.0, 0.0, 0.0, 0.0],
        [-2.430093356833875, -0.2063599157091915, 0.0, 0.0, 0.0, 0.0],
        [-0.1073529058151375, -9.594562251023355, -20.47028614809616, 0.0, 0.0, 0.0],
        [7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160, 0.0,
         0.0],
        [8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136,
         -6.058818238834054, 0.0],
    ]
)
# y1 = y + sum_j M_j U_j (stiffly accurate: M is row 6 of A plus U_6); embedded: M_HAT.
M = np.array([1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950,
              1.0, 1.0])
M_HAT = np.array([1.221224509226641, 6.019134481288629, 12.53708332932087,
                  -0.6878860361058950, 1.0, 0.0])
# Dense output weights (rodas.f D21..D25, D31..D35; U_6 does not enter).
D2 = np.array([10.12623508344586, -7.487995877610167, -34.80091861555747, -7.992771707568823,
               1.025137723295662, 0.0])
D3 = np.array([-0.6762803392801253, 6.087714651680015, 16.43084320892478, 24.76722511418386,
               -6.594389125716872, 0.0])

SAFETY = 0.9
FAC_MIN = 0.2
FAC_MAX = 6.0
REFINE_ITERATIONS = 4  # Newton steps putting a located switch on the surface
EPS = 2.220446049250313e-16


# ---------------------------------------------------------------------------------------
# one step


@njit(cache=True, inline="always")
def rodas_step(rhs, p, t, y, h, mode, locate, A_s, b_s, work):
    """One Rodas4 step of size h from (t, y) with f, J and f_t at (t, y) in rows F0, JAC,
    DFDT of ``work``.

    Stage increments into rows U0..U0+5, the solution into YNEW; ``U_6`` is the error
    estimate. Returns False when ``I/(gamma h) - J`` is singular. In the plain scheme
    (locate False) each stage takes its mode from its own state.
    """
    dim = y.shape[0]
    lu = work[JAC + dim:JAC + 2 * dim]
    piv = work[PIV]
    ytmp = work[YT]
    ftmp = work[FT]
    fac = 1.0 / (GAMMA * h)
    for i in range(dim):
        for j in range(dim):
            lu[i, j] = -work[JAC + i, j]
        lu[i, i] += fac
    if not lu_factor(lu, piv):
        return False
    for s in range(STAGES):
        if s == 0:
            for i in range(dim):
                ftmp[i] = work[F0, i]
        else:
            for i in range(dim):
                acc = y[i]
                for j in range(s):
                    acc += A[s, j] * work[U0 + j, i]
                ytmp[i] = acc
            m = mode if locate else mode_of(ytmp, A_s, b_s)
            rhs(t + C[s] * h, ytmp, p, m, ftmp)
        hd = h * D[s]
        for i in range(dim):
            acc = ftmp[i] + hd * work[DFDT, i]
            for j in range(s):
                acc += (CC[s, j] / h) * work[U0 + j, i]
            work[U0 + s, i] = acc
        lu_solve(lu, piv, work[U0 + s])
    for i in range(dim):
        work[YNEW, i] = ytmp[i] + work[U0 + STAGES - 1, i]  # stiffly accurate: stage 6 + U_6
    return True


@njit(cache=True, inline="always")
def error_norm(y, work, opts):
    dim = y.shape[0]
    acc = 0.0
    for i in range(dim):
        scale = opts[ATOL] + opts[RTOL] * max(abs(y[i]), abs(work[YNEW, i]))
        r = work[U0 + STAGES - 1, i] / scale
        acc += r * r
    return sqrt(acc / dim)


@njit(cache=True, inline="always")
def dense_coefficients(y, work):
    """Monomial rows M0..M0+4 of (1-s) y0 + s (y1 + (1-s) (k1 + s k2))."""
    for i in range(y.shape[0]):
        k1 = 0.0
        k2 = 0.0
        for j in range(STAGES - 1):
            k1 += D2[j] * work[U0 + j, i]
            k2 += D3[j] * work[U0 + j, i]
        work[M0, i] = y[i]
        work[M0 + 1, i] = work[YNEW, i] - y[i] + k1
        work[M0 + 2, i] = k2 - k1
        work[M0 + 3, i] = -k2
        work[M0 + 4, i] = 0.0


@njit(cache=True)
def end_value(a, b, work, coef):
    """(g at the step's end, a scale of its rounding, dg/du there) for the surface
    g = a . y + b on the step in ``work``; ``coef`` receives g's polynomial in u."""
    g = b
    size = abs(b)
    for j in range(a.shape[0]):
        g += a[j] * work[YNEW, j]
        size += abs(a[j] * work[YNEW, j])
    for k in range(5):
        s = 0.0
        for j in range(a.shape[0]):
            s += a[j] * work[M0 + k, j]
        coef[k] = s
    coef[0] += b
    return g, size, poly_rate(coef, 1.0)


@njit(cache=True)
def refine_crossing(rhs, p, t, y, h_step, h_full, mode, surface, work, variant):
    """Newton on the step length so that the redone step ends on the crossed surface.

    The crossing comes from the 3rd-order dense output (time error ~ h^4); a switch placed
    that far from the crossing of the numerical solution costs the order at every contact
    onset (the paper law's force jumps there). Solving g(Phi_h(y)) = 0 with the step
    itself puts the switch where the 4th-order solution crosses. A step that is not a
    clean transversal crossing (|correction| > 10 % of the step) is left as located.
    ``surface`` = (A row, b) of the crossed surface. Returns (the final step length, the
    rhs evaluations used); the work rows hold that step.
    """
    a, b = surface
    no_rows = work[:0]
    coef = np.empty(5)
    evals = 0
    for _ in range(REFINE_ITERATIONS):
        g, size, rate = end_value(a, b, work, coef)
        if abs(g) <= 8.0 * EPS * size:
            break
        if rate == 0.0 or abs(g) > 0.1 * abs(rate):
            break
        h_new = h_step * (1.0 - g / rate)
        if h_new <= 0.0 or h_new > h_full:
            break
        ok = rodas_step(rhs, p, t, y, h_new, mode, True, no_rows, no_rows[0], work)
        evals += STAGES - 1
        if not ok:  # cannot happen for a step shorter than an accepted one; be safe
            rodas_step(rhs, p, t, y, h_step, mode, True, no_rows, no_rows[0], work)
            dense_coefficients(y, work)
            break
        dense_coefficients(y, work)
        h_step = h_new
    return h_step, evals


# ---------------------------------------------------------------------------------------
# the method's hooks for the driver (see ``driver``)


@njit(cache=True, inline="always")
def begin(rhs, p, t, y, mode, work, variant):
    """f, J and f_t at (t, y), the derivatives by differences of ``rhs``."""
    dim = y.shape[0]
    rhs(t, y, p, mode, work[F0])
    return 1 + fd_jacobian(rhs, p, t, y, mode, work[F0], work[JAC:JAC + dim], work[DFDT],
                           work[YT], work[FT])


@njit(cache=True, inline="always")
def step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant):
    ok = rodas_step(rhs, p, t, y, h, mode, stage_A.shape[0] == 0, stage_A, stage_b, work)
    return ok, STAGES - 1


@njit(cache=True, inline="always")
def error(y, h, work, opts, variant):
    return error_norm(y, work, opts)


@njit(cache=True, inline="always")
def controller(variant):
    return Controller(ORDER, SAFETY, FAC_MIN, FAC_MAX, 0.5, True)


@njit(cache=True, inline="always")
def dense(y, h, work, variant):
    dense_coefficients(y, work)


@njit(cache=True, inline="always")
def accept(y, h, h_next, work, istate, variant):
    """The state moves on; Rodas4 is not FSAL: f, J and f_t are needed at the new point."""
    for i in range(y.shape[0]):
        y[i] = work[YNEW, i]
    istate[N_STIFF_STEPS] += 1
    return False, True


advance = adaptive_loop("rodas4", begin, step, error, controller, dense, refine_crossing, accept,
                        no_change, same_method)


@cache
def with_jacobian(jac):
    """Rodas4's ``advance`` with the system's analytic ``jac(t, y, p, mode, jac, dfdt)``
    (a jitted function) instead of differences of the right-hand side."""

    @njit(cache=True)
    def begin_with_jacobian(rhs, p, t, y, mode, work, variant):
        dim = y.shape[0]
        rhs(t, y, p, mode, work[F0])
        jac(t, y, p, mode, work[JAC:JAC + dim], work[DFDT])
        return 1

    name = f"rodas4_{jac.py_func.__module__}_{jac.__name__}".replace(".", "_")
    return adaptive_loop(name, begin_with_jacobian,
                         step, error, controller, dense, refine_crossing, accept, no_change,
                         same_method)
