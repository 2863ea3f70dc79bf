"""The pair's equations, written once for both presets (``duffing.py``, ``bilinear.py``).

    x1'' + c x1' + k1 x1 + s1 + F_C = F sin(w t)
    x2'' + c x2' + k1 x2 + s2 - F_C = F sin(w t + phi)

A preset passes its springs beyond the linear one (``s1``, ``s2``: Duffing's ``k2 x^3``,
the bilinear body's second spring) and, for the Jacobian, their slopes; the stop force
``F_C`` is the law's (``stops.py``). Both presets pack ``c, k1, k2, F, w`` first (indices
below) and the coupling block at ``stop_at``. The arithmetic is the presets' own, in the
same order (their results are unchanged bit for bit). The chain family
(``chain.py``) holds the pair too; these specialised kernels are kept because they are
faster (``benchmarks/bench_chain.py``).
"""

from __future__ import annotations

from math import cos, sin

from numba import njit

from . import stops
from .stops import stop_force, stop_slopes

C, K1, K2, F, W = 0, 1, 2, 3, 4  # the body block both presets begin with


@njit(cache=True)
def pair_rhs_with(t, y, p, mode, stop_at, law_bit, s1, s2, out):
    """The pair's right-hand side, the springs beyond k1 given (``s1``, ``s2``)."""
    # One sine and one cosine serve both bodies: sin(wt + phi) = s cos(phi) + c sin(phi).
    wt = p[W] * t
    s = sin(wt)
    co = cos(wt)
    x1 = y[0]
    v1 = y[1]
    x2 = y[2]
    v2 = y[3]
    fc = stop_force(p, stop_at, mode, law_bit, x1 - x2 - p[stop_at + stops.D], v1 - v2)
    out[0] = v1
    out[1] = p[F] * s - p[C] * v1 - p[K1] * x1 - s1 - fc
    out[2] = v2
    forcing2 = p[F] * (s * p[stop_at + stops.COS_PHI] + co * p[stop_at + stops.SIN_PHI])
    out[3] = forcing2 - p[C] * v2 - p[K1] * x2 - s2 + fc


@njit(cache=True)
def pair_jacobian_with(t, y, p, mode, stop_at, law_bit, slope1, slope2, jac, dfdt):
    """The pair's Jacobian and time derivative, the springs' slopes beyond k1 given."""
    kc, cc = stop_slopes(p, stop_at, mode, law_bit, y[0] - y[2] - p[stop_at + stops.D],
                         y[1] - y[3])
    jac[:, :] = 0.0
    jac[0, 1] = 1.0
    jac[2, 3] = 1.0
    jac[1, 0] = -p[K1] - slope1 - kc
    jac[1, 1] = -p[C] - cc
    jac[1, 2] = kc
    jac[1, 3] = cc
    jac[3, 0] = kc
    jac[3, 1] = cc
    jac[3, 2] = -p[K1] - slope2 - kc
    jac[3, 3] = -p[C] - cc
    wt = p[W] * t
    fw = p[F] * p[W]
    dfdt[0] = 0.0
    dfdt[1] = fw * cos(wt)
    dfdt[2] = 0.0
    dfdt[3] = fw * (cos(wt) * p[stop_at + stops.COS_PHI] - sin(wt) * p[stop_at + stops.SIN_PHI])
