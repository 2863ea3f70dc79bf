"""Switching surfaces along a step: mode bits, first exit, grazing, penetration.

A surface is affine in the state, ``g_i(y) = A[i] @ y + b[i]``, so along a step's dense
output ``g_i`` is a polynomial of degree <= 4 in the step fraction ``u``. Bit ``i`` of the
mode is set on the engaged side ``g_i >= 0``. A step *exits* its mode when some watched
surface changes side anywhere inside it, including a grazing excursion that comes back
before the step ends (both end values on the same side). The polynomial's critical
points in (0, 1) are computed exactly (roots of its cubic derivative, each isolated in a
piece where the cubic is monotone, between the roots of its quadratic second derivative);
between consecutive critical points g is monotone, so checking g there finds every exit
and every maximum, however close two extrema lie.
"""

from math import sqrt

import numpy as np
from numba import njit

from .layout import M0

ROOT_TOL = 1e-14  # in units of the step fraction u


@njit(cache=True)
def surface_value(A, b, i, y):
    g = b[i]
    for j in range(y.shape[0]):
        g += A[i, j] * y[j]
    return g


@njit(cache=True)
def mode_of(y, A, b):
    """Mode bit mask of state ``y``: bit i set where g_i(y) >= 0."""
    mode = 0
    for i in range(A.shape[0]):
        if surface_value(A, b, i, y) >= 0.0:
            mode |= 1 << i
    return mode


@njit(cache=True, inline="always")
def surface_polynomial(work, A, b, i, coef):
    """Monomial coefficients of g_i along the step (from the dense output in ``work``)."""
    dim = A.shape[1]
    for k in range(5):
        s = 0.0
        for j in range(dim):
            s += A[i, j] * work[M0 + k, j]
        coef[k] = s
    coef[0] += b[i]


@njit(cache=True, inline="always")
def poly(coef, u):
    return coef[0] + u * (coef[1] + u * (coef[2] + u * (coef[3] + u * coef[4])))


@njit(cache=True)
def poly_rate(coef, u):
    return coef[1] + u * (2.0 * coef[2] + u * (3.0 * coef[3] + u * 4.0 * coef[4]))


@njit(cache=True)
def _quadratic_roots(a, b, c, out):
    """Real roots of a u^2 + b u + c in (0, 1), sorted, into out; returns their count."""
    n = 0
    if a == 0.0:
        if b != 0.0:
            r = -c / b
            if 0.0 < r < 1.0:
                out[0] = r
                n = 1
        return n
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return 0
    sq = sqrt(disc)
    q = -0.5 * (b + sq) if b >= 0.0 else -0.5 * (b - sq)  # no cancellation
    r1 = q / a
    r2 = c / q if q != 0.0 else r1
    lo, hi = min(r1, r2), max(r1, r2)
    if 0.0 < lo < 1.0:
        out[n] = lo
        n += 1
    if 0.0 < hi < 1.0 and hi != lo:
        out[n] = hi
        n += 1
    return n


@njit(cache=True)
def _cubic(q0, q1, q2, q3, u):
    return q0 + u * (q1 + u * (q2 + u * q3))


@njit(cache=True)
def critical_points(coef, out):
    """Roots of g'(u) in (0, 1), sorted, into out (size >= 3); returns their count."""
    q0 = coef[1]
    q1 = 2.0 * coef[2]
    q2 = 3.0 * coef[3]
    q3 = 4.0 * coef[4]
    breaks = np.empty(4)
    nb = _quadratic_roots(3.0 * q3, 2.0 * q2, q1, breaks[1:3]) + 1
    breaks[0] = 0.0
    breaks[nb] = 1.0
    n = 0
    for k in range(nb):
        a = breaks[k]
        b = breaks[k + 1]
        fa = _cubic(q0, q1, q2, q3, a)
        fb = _cubic(q0, q1, q2, q3, b)
        if fa == 0.0:
            if a > 0.0 and (n == 0 or out[n - 1] < a):
                out[n] = a
                n += 1
            continue
        if fa * fb >= 0.0:
            continue
        # monotone piece with a sign change: Illinois to ROOT_TOL
        side = 0
        for _ in range(200):
            if b - a < ROOT_TOL:
                break
            m = a - fa * (b - a) / (fb - fa)
            if m <= a or m >= b:
                m = 0.5 * (a + b)
            fm = _cubic(q0, q1, q2, q3, m)
            if fm == 0.0:
                a = b = m
                break
            if (fm < 0.0) == (fa < 0.0):
                a = m
                fa = fm
                if side == 1:
                    fb *= 0.5
                side = 1
            else:
                b = m
                fb = fm
                if side == -1:
                    fa *= 0.5
                side = -1
        out[n] = 0.5 * (a + b)
        n += 1
    return n


@njit(cache=True)
def _root(coef, sign, a, b, ha, hb):
    """Illinois (modified regula falsi) on sign*g, with ha >= 0 > hb."""
    side = 0
    u = b
    for _ in range(200):
        if b - a < ROOT_TOL:
            break
        u = a + ha * (b - a) / (ha - hb)
        if u <= a or u >= b:
            u = 0.5 * (a + b)
        hu = sign * poly(coef, u)
        if hu == 0.0:
            return u
        if hu < 0.0:
            b = u
            hb = hu
            if side == -1:
                ha *= 0.5
            side = -1
        else:
            a = u
            ha = hu
            if side == 1:
                hb *= 0.5
            side = 1
    return 0.5 * (a + b)


@njit(cache=True, inline="always")
def first_exit(coef, engaged):
    """Fraction u in [0, 1] where g first leaves the side given by ``engaged``; -1 if never.

    The step starts on its mode's side by construction (a restart right at a switch may
    leave a residual of rounding size on the wrong side; it is treated as zero).
    Inlined: most steps end at the cheap rejection, which then costs no call (a call
    passing arrays costs reference counting, more than the test itself).
    """
    sign = 1.0 if engaged else -1.0
    h0 = sign * coef[0]
    # Cheap rejection: sign * c_k u^k >= min(sign * c_k, 0) on [0, 1].
    if h0 + (min(sign * coef[1], 0.0) + min(sign * coef[2], 0.0) + min(sign * coef[3], 0.0)
             + min(sign * coef[4], 0.0)) > 0.0:
        return -1.0
    return exit_search(coef, sign, h0)


@njit(cache=True)
def exit_search(coef, sign, h0):
    """``first_exit`` past its cheap rejection: the first root of sign * g, found piece
    by piece between the critical points."""
    crit = np.empty(3)
    n = critical_points(coef, crit)
    a = 0.0
    ha = h0 if h0 > 0.0 else 0.0
    for k in range(n + 1):
        b = crit[k] if k < n else 1.0
        hb = sign * poly(coef, b)
        if hb < 0.0:  # g is monotone on [a, b]: the exit is the one root there
            return _root(coef, sign, a, b, ha, hb)
        a = b
        ha = hb
    return -1.0


@njit(cache=True)
def poly_max(coef, u_end):
    """Largest value of g on [0, u_end], end points and interior maxima included."""
    best = max(poly(coef, 0.0), poly(coef, u_end))
    crit = np.empty(3)
    n = critical_points(coef, crit)
    for k in range(n):
        if crit[k] < u_end:
            best = max(best, poly(coef, crit[k]))
    return best


@njit(cache=True, inline="always")
def earliest_exit(work, A, b, relevance, mode, coef):
    """Earliest exit fraction among watched surfaces, and the mask of surfaces exiting there.

    Returns (u, mask, held); u = -1 when the step stays in its mode; ``coef`` is left
    holding the polynomial of surface ``held`` (the last watched one; -1: none), which
    ``common.track_contact`` then need not compute again.
    """
    watched = relevance[mode]
    best = 2.0
    mask = 0
    held = -1
    for i in range(A.shape[0]):
        if not (watched >> i) & 1:
            continue
        surface_polynomial(work, A, b, i, coef)
        held = i
        u = first_exit(coef, (mode >> i) & 1)
        if u < 0.0:
            continue
        if u < best - 1e-12:
            best = u
            mask = 1 << i
        elif u <= best + 1e-12:
            mask |= 1 << i
    if mask == 0:
        return -1.0, 0, held
    return best, mask, held


@njit(cache=True)
def switch_mode(mode, mask, y, A, b, relevance):
    """Mode after crossing the surfaces in ``mask`` at state ``y``.

    Crossed surfaces flip; surfaces not watched before the switch take their side from
    the state (they were not tracked).
    """
    new_mode = mode ^ mask
    watched = relevance[mode]
    for i in range(A.shape[0]):
        if (watched >> i) & 1:
            continue
        if surface_value(A, b, i, y) >= 0.0:
            new_mode |= 1 << i
        else:
            new_mode &= ~(1 << i)
    return new_mode
