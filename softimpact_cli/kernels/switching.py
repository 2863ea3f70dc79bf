"""Switching surfaces along a step: mode bits, first exit, grazing, penetration.

A surface is affine in the state, ``g_i(y) = A[i] @ y + b[i]``, so along a step's dense
output ``g_i`` is a polynomial of degree <= 4 in the step fraction ``u``. Bit ``i`` of the
mode is set on the engaged side ``g_i >= 0``. A step *exits* its mode when some watched
surface changes side anywhere inside it, including a grazing excursion that comes back
before the step ends (both end values on the same side): that is why each step is split
into sub-intervals and every interior extremum of the polynomial is checked.
"""

from numba import njit

from .layout import M0

SUBINTERVALS = 4  # a step's polynomial has at most 3 extrema; 4 pieces isolate them
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


@njit(cache=True)
def surface_polynomial(work, A, b, i, coef):
    """Monomial coefficients of g_i along the step (from the dense output in ``work``)."""
    dim = A.shape[1]
    for k in range(5):
        s = 0.0
        for j in range(dim):
            s += A[i, j] * work[M0 + k, j]
        coef[k] = s
    coef[0] += b[i]


@njit(cache=True)
def poly(coef, u):
    return coef[0] + u * (coef[1] + u * (coef[2] + u * (coef[3] + u * coef[4])))


@njit(cache=True)
def poly_rate(coef, u):
    return coef[1] + u * (2.0 * coef[2] + u * (3.0 * coef[3] + u * 4.0 * coef[4]))


@njit(cache=True)
def _critical_point(coef, sign, lo, hi):
    """Bisect on the derivative of sign*g: it goes from < 0 at lo to > 0 at hi."""
    for _ in range(100):
        if hi - lo < ROOT_TOL:
            break
        mid = 0.5 * (lo + hi)
        if sign * poly_rate(coef, mid) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


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


@njit(cache=True)
def first_exit(coef, engaged):
    """Fraction u in [0, 1] where g first leaves the side given by ``engaged``; -1 if never.

    The step starts on its mode's side by construction (a restart right at a switch may
    leave a residual of rounding size on the wrong side; it is treated as zero).
    """
    sign = 1.0 if engaged else -1.0
    h0 = sign * coef[0]
    # Cheap rejection: |g(u) - g(0)| <= sum |c_k| on [0, 1].
    if h0 > abs(coef[1]) + abs(coef[2]) + abs(coef[3]) + abs(coef[4]):
        return -1.0
    a = 0.0
    ha = h0 if h0 > 0.0 else 0.0
    da = sign * poly_rate(coef, 0.0)
    for k in range(1, SUBINTERVALS + 1):
        ub = k / SUBINTERVALS
        hb = sign * poly(coef, ub)
        if hb < 0.0:
            return _root(coef, sign, a, ub, ha, hb)
        db = sign * poly_rate(coef, ub)
        if da < 0.0 and db > 0.0:
            um = _critical_point(coef, sign, a, ub)
            hm = sign * poly(coef, um)
            if hm < 0.0:  # grazing excursion across the surface and back
                return _root(coef, sign, a, um, ha, hm)
        a = ub
        ha = hb
        da = db
    return -1.0


@njit(cache=True)
def poly_max(coef, u_end):
    """Largest value of g on [0, u_end], end points and interior maxima included."""
    best = max(poly(coef, 0.0), poly(coef, u_end))
    a = 0.0
    da = poly_rate(coef, 0.0)
    for k in range(1, SUBINTERVALS + 1):
        ub = u_end * k / SUBINTERVALS
        db = poly_rate(coef, ub)
        if da > 0.0 and db < 0.0:
            um = _critical_point(coef, -1.0, a, ub)
            gm = poly(coef, um)
            if gm > best:
                best = gm
        a = ub
        da = db
    return best


@njit(cache=True)
def earliest_exit(work, A, b, relevance, mode, coef):
    """Earliest exit fraction among watched surfaces, and the mask of surfaces exiting there.

    Returns (u, mask); u = -1 when the step stays in its mode.
    """
    watched = relevance[mode]
    best = 2.0
    mask = 0
    for i in range(A.shape[0]):
        if not (watched >> i) & 1:
            continue
        surface_polynomial(work, A, b, i, coef)
        u = first_exit(coef, (mode >> i) & 1)
        if u < 0.0:
            continue
        if u < best - 1e-12:
            best = u
            mask = 1 << i
        elif u <= best + 1e-12:
            mask |= 1 << i
    if mask == 0:
        return -1.0, 0
    return best, mask


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
