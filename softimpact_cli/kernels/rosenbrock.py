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

Two entry points share one kernel:

* ``advance_with_jacobian(rhs, jac, p, y, ...)``: the system's analytic
  ``jac(t, y, p, mode, jac, dfdt)``;
* ``advance(rhs, p, y, ...)``: the standard signature of every method, so the trajectory
  kernels take it unchanged; the Jacobian is a forward difference of ``rhs`` in the frozen
  mode (column ``j`` with step ``sqrt(eps) max(1, |y_j|)``) and ``f_t`` a central
  difference with step ``eps^(1/3) max(1, |t|)^(1/3)`` (the forcing's phase carries a
  rounding error ~ eps |w t|, so the step must grow slowly with |t|; a forward
  difference in t would cost ~ 1e-4 of f_t at t ~ 1e4).
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
    LOCATE,
    M0,
    MAX_STEPS,
    MAX_SWITCHES,
    MODE,
    N_REJECTED,
    N_RHS,
    N_STEPS,
    N_STIFF_STEPS,
    RTOL,
    YNEW,
    H,
)
from .switching import earliest_exit, mode_of, poly_rate, surface_polynomial, surface_value

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
H_FLOOR = 1e-13  # relative to the interval being advanced
REFINE_ITERATIONS = 4  # Newton steps putting a located switch on the surface
EPS = 2.220446049250313e-16
SQRT_EPS = 1.4901161193847656e-08
CBRT_EPS = 6.055454452393343e-06


# ---------------------------------------------------------------------------------------
# small dense linear algebra


@njit(cache=True)
def lu_factor(a, piv):
    """In-place LU with partial pivoting (Doolittle, L unit lower); False if singular."""
    n = a.shape[0]
    for k in range(n):
        m = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                m = i
        piv[k] = m
        if big == 0.0 or not isfinite(big):
            return False
        if m != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[m, j]
                a[m, j] = tmp
        inv = 1.0 / a[k, k]
        for i in range(k + 1, n):
            a[i, k] *= inv
            f = a[i, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= f * a[k, j]
    return True


@njit(cache=True)
def lu_solve(a, piv, x):
    """Solve with the factors of ``lu_factor``; ``x`` holds the right-hand side on entry."""
    n = a.shape[0]
    for k in range(n):
        m = piv[k]
        if m != k:
            tmp = x[k]
            x[k] = x[m]
            x[m] = tmp
    for i in range(1, n):
        acc = x[i]
        for j in range(i):
            acc -= a[i, j] * x[j]
        x[i] = acc
    for i in range(n - 1, -1, -1):
        acc = x[i]
        for j in range(i + 1, n):
            acc -= a[i, j] * x[j]
        x[i] = acc / a[i, i]


# ---------------------------------------------------------------------------------------
# Jacobians


@njit(cache=True)
def fd_jacobian(rhs, p, t, y, mode, f0, jac, dfdt, ytmp, ftmp):
    """Forward-difference d rhs/dy and central-difference d rhs/dt in ``mode``.

    ``f0`` is rhs(t, y). Returns the number of rhs evaluations (dim + 2).
    """
    dim = y.shape[0]
    for i in range(dim):
        ytmp[i] = y[i]
    for j in range(dim):
        yj = y[j]
        step = SQRT_EPS * max(1.0, abs(yj))
        ytmp[j] = yj + step
        step = ytmp[j] - yj  # the increment actually represented
        rhs(t, ytmp, p, mode, ftmp)
        for i in range(dim):
            jac[i, j] = (ftmp[i] - f0[i]) / step
        ytmp[j] = yj
    dt = CBRT_EPS * max(1.0, abs(t)) ** (1.0 / 3.0)
    tp = t + dt
    tm = t - dt
    rhs(tp, y, p, mode, ftmp)
    for i in range(dim):
        dfdt[i] = ftmp[i]
    rhs(tm, y, p, mode, ftmp)
    for i in range(dim):
        dfdt[i] = (dfdt[i] - ftmp[i]) / (tp - tm)
    return dim + 2


# ---------------------------------------------------------------------------------------
# one step


@njit(cache=True)
def step(rhs, p, t, y, h, mode, locate, A_s, b_s, f0, jac, dfdt, lu, piv, U, ytmp, ftmp,
         ynew):
    """One Rodas4 step of size h from (t, y); f0 = f(t, y), jac, dfdt at (t, y).

    Stage increments into ``U`` (rows 0..5), the solution into ``ynew``; ``U[5]`` is the
    error estimate. Returns False when ``I/(gamma h) - J`` is singular. In the plain scheme
    (locate False) each stage takes its mode from its own state.
    """
    dim = y.shape[0]
    fac = 1.0 / (GAMMA * h)
    for i in range(dim):
        for j in range(dim):
            lu[i, j] = -jac[i, j]
        lu[i, i] += fac
    if not lu_factor(lu, piv):
        return False
    for s in range(STAGES):
        if s == 0:
            for i in range(dim):
                ftmp[i] = f0[i]
        else:
            for i in range(dim):
                acc = y[i]
                for j in range(s):
                    acc += A[s, j] * U[j, i]
                ytmp[i] = acc
            m = mode if locate else mode_of(ytmp, A_s, b_s)
            rhs(t + C[s] * h, ytmp, p, m, ftmp)
        hd = h * D[s]
        for i in range(dim):
            acc = ftmp[i] + hd * dfdt[i]
            for j in range(s):
                acc += (CC[s, j] / h) * U[j, i]
            U[s, i] = acc
        lu_solve(lu, piv, U[s])
    for i in range(dim):
        ynew[i] = ytmp[i] + U[STAGES - 1, i]  # stiffly accurate: stage 6 state + U_6
    return True


@njit(cache=True)
def error_norm(y, ynew, U, opts):
    dim = y.shape[0]
    acc = 0.0
    for i in range(dim):
        scale = opts[ATOL] + opts[RTOL] * max(abs(y[i]), abs(ynew[i]))
        r = U[STAGES - 1, i] / scale
        acc += r * r
    return sqrt(acc / dim)


@njit(cache=True)
def dense_coefficients(y, ynew, U, work):
    """Monomial rows M0..M0+4 of (1-s) y0 + s (y1 + (1-s) (k1 + s k2))."""
    for i in range(y.shape[0]):
        k1 = 0.0
        k2 = 0.0
        for j in range(STAGES - 1):
            k1 += D2[j] * U[j, i]
            k2 += D3[j] * U[j, i]
        work[M0, i] = y[i]
        work[M0 + 1, i] = ynew[i] - y[i] + k1
        work[M0 + 2, i] = k2 - k1
        work[M0 + 3, i] = -k2
        work[M0 + 4, i] = 0.0


@njit(cache=True)
def refine_crossing(rhs, p, t, y, h_step, h_full, mode, locate, A_s, b_s, mask, f0, jac, dfdt,
                    lu, piv, U, ytmp, ftmp, ynew, work, coef, istate):
    """Newton on the step length so that the redone step ends on the crossed surface.

    The crossing comes from the 3rd-order dense output (time error ~ h^4); a switch placed
    that far from the crossing of the numerical solution costs the order at every contact
    onset (the paper law's force jumps there). Solving g(Phi_h(y)) = 0 with the step
    itself puts the switch where the 4th-order solution crosses. A step that is not a
    clean transversal crossing (|correction| > 10 % of the step) is left as located.
    Returns the final step length; U, ynew and the dense rows hold that step.
    """
    i = 0
    while not (mask >> i) & 1:
        i += 1
    for _ in range(REFINE_ITERATIONS):
        g = surface_value(A_s, b_s, i, ynew)
        size = abs(b_s[i])
        for j in range(ynew.shape[0]):
            size += abs(A_s[i, j] * ynew[j])
        if abs(g) <= 8.0 * EPS * size:
            break
        surface_polynomial(work, A_s, b_s, i, coef)
        rate = poly_rate(coef, 1.0)  # dg/du at the end of the step
        if rate == 0.0 or abs(g) > 0.1 * abs(rate):
            break
        h_new = h_step * (1.0 - g / rate)
        if h_new <= 0.0 or h_new > h_full:
            break
        ok = step(rhs, p, t, y, h_new, mode, locate, A_s, b_s, f0, jac, dfdt, lu, piv, U,
                  ytmp, ftmp, ynew)
        istate[N_RHS] += STAGES - 1
        if not ok:  # cannot happen for a step shorter than an accepted one; be safe
            step(rhs, p, t, y, h_step, mode, locate, A_s, b_s, f0, jac, dfdt, lu, piv, U,
                 ytmp, ftmp, ynew)
            dense_coefficients(y, ynew, U, work)
            break
        dense_coefficients(y, ynew, U, work)
        h_step = h_new
    return h_step


# ---------------------------------------------------------------------------------------
# the integrator


@njit(cache=True)
def _advance(rhs, jac, p, y, t, t_end, A_s, b_s, relevance, contact, opts, istate,
             fstate, work, sample_t, sample_y):
    """Integrate ``y`` (in place) from ``t`` to exactly ``t_end``; return a status code.

    ``jac`` is the system's Jacobian function, or None for differences of ``rhs`` (numba
    compiles one specialisation for each, the other branch pruned).
    """
    locate = opts[LOCATE] != 0.0
    n_surf = A_s.shape[0]
    dim = y.shape[0]
    coef = np.empty(5)
    f0 = np.empty(dim)
    jmat = np.empty((dim, dim))
    dfdt = np.empty(dim)
    lu = np.empty((dim, dim))
    piv = np.empty(dim, dtype=np.int64)
    U = np.empty((STAGES, dim))
    ytmp = np.empty(dim)
    ftmp = np.empty(dim)
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
        if need_first:
            rhs(t, y, p, mode, f0)
            istate[N_RHS] += 1
            if jac is None:  # pruned at compile time (numba specialises on None)
                istate[N_RHS] += fd_jacobian(rhs, p, t, y, mode, f0, jmat, dfdt, ytmp, ftmp)
            else:
                jac(t, y, p, mode, jmat, dfdt)
            need_first = False
        h = min(h, opts[H_MAX])
        truncated = False
        h_step = h
        if t + 1.0001 * h >= t_end:
            h_step = t_end - t
            truncated = True
        ok = step(rhs, p, t, y, h_step, mode, locate, A_s, b_s, f0, jmat, dfdt, lu, piv, U,
                  ytmp, ftmp, ynew)
        istate[N_RHS] += STAGES - 1
        err = error_norm(y, ynew, U, opts) if ok else np.inf
        if not isfinite(err) or err > 1.0:
            istate[N_REJECTED] += 1
            rejected = True
            if not ok:
                fac = 0.5
            elif not isfinite(err):
                fac = FAC_MIN
            else:
                fac = max(FAC_MIN, SAFETY * err ** (-1.0 / ORDER))
            h = h_step * fac
            if h < h_floor:
                fstate[H] = h
                return STEP_UNDERFLOW
            continue
        fac = FAC_MAX if err == 0.0 else min(FAC_MAX, max(FAC_MIN, SAFETY * err ** (-1.0 / ORDER)))
        h_next = h_step * fac
        if rejected:
            h_next = min(h_next, h_step)  # no growth right after a rejection
        if truncated:
            h_next = max(h_next, h)  # landing on t_end says nothing against the old step
        rejected = False

        dense_coefficients(y, ynew, U, work)
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
                    need_first = True
                    switches += 1
                    if switches > opts[MAX_SWITCHES]:
                        return TOO_MANY_SWITCHES
                    continue
                ok = step(rhs, p, t, y, h_step, mode, locate, A_s, b_s, f0, jmat, dfdt, lu,
                          piv, U, ytmp, ftmp, ynew)
                istate[N_RHS] += STAGES - 1
                if not ok:  # a shorter step than an accepted one: only on breakdown
                    fstate[H] = h_step
                    return STEP_UNDERFLOW
                dense_coefficients(y, ynew, U, work)
                h_step = refine_crossing(rhs, p, t, y, h_step, h_full, mode, locate, A_s, b_s,
                                         mask, f0, jmat, dfdt, lu, piv, U, ytmp, ftmp, ynew,
                                         work, coef, istate)

        # Accept [t, t + h_step].
        if locate:
            track_contact(work, A_s, b_s, contact, fstate, coef)
        write_samples(work, t, h_step, opts, istate, sample_t, sample_y)
        t = t_end if truncated else t + h_step
        for i in range(dim):
            y[i] = ynew[i]
        need_first = True  # Rodas4 is not FSAL: f, J and f_t at the new point
        steps += 1
        istate[N_STEPS] += 1
        istate[N_STIFF_STEPS] += 1
        if out_of_bounds(y, opts[BOUND]):
            fstate[H] = h_next
            return DIVERGED
        if mask != 0:
            apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
            switches += 1
            if switches > opts[MAX_SWITCHES]:
                return TOO_MANY_SWITCHES
        elif not locate and n_surf > 0:
            plain_mode_update(y, A_s, b_s, contact, istate)
            track_contact_at(y, A_s, b_s, contact, fstate)
        h = h_next
        if steps > opts[MAX_STEPS]:
            fstate[H] = h
            return STEP_BUDGET
    fstate[H] = h
    return OK


@njit(cache=True)
def advance_with_jacobian(rhs, jac, p, y, t, t_end, A_s, b_s, relevance, contact, opts,
                          istate, fstate, work, sample_t, sample_y):
    """Rodas4 with the system's analytic ``jac(t, y, p, mode, jac, dfdt)``."""
    return _advance(rhs, jac, p, y, t, t_end, A_s, b_s, relevance, contact, opts,
                    istate, fstate, work, sample_t, sample_y)


@njit(cache=True)
def advance(rhs, p, y, t, t_end, A_s, b_s, relevance, contact, opts, istate, fstate, work,
            sample_t, sample_y):
    """Rodas4 with the common signature; Jacobian and f_t by differences of ``rhs``."""
    return _advance(rhs, None, p, y, t, t_end, A_s, b_s, relevance, contact,
                    opts, istate, fstate, work, sample_t, sample_y)


def _stabilise():
    # Stable dispatcher identities for numba's disk cache (see numba_cache.py); the
    # package's kernels/__init__.py does the same for the modules it imports.
    import sys

    from .numba_cache import stabilise

    stabilise(sys.modules[__name__])


_stabilise()
