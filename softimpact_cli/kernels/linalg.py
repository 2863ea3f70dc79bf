"""Small dense linear algebra: LU with partial pivoting and the difference Jacobian of a
right-hand side in a frozen mode (the implicit methods), a norm and a product (auto's
spectral bound, the exact flow's propagators).

The systems have a handful of state variables, so plain loops beat any call into LAPACK.
"""

from math import isfinite

from numba import njit

SQRT_EPS = 1.4901161193847656e-08
CBRT_EPS = 6.055454452393343e-06


@njit(cache=True)
def inf_norm(a):
    """Largest absolute row sum of ``a``."""
    worst = 0.0
    for i in range(a.shape[0]):
        s = 0.0
        for j in range(a.shape[1]):
            s += abs(a[i, j])
        worst = max(worst, s)
    return worst


@njit(cache=True)
def matmul_into(x, y, out):
    """``out = x @ y`` for small square matrices (``out`` not ``x`` or ``y``)."""
    n = x.shape[0]
    for i in range(n):
        for j in range(n):
            s = 0.0
            for k in range(n):
                s += x[i, k] * y[k, j]
            out[i, j] = s


@njit(cache=True, inline="always")
def lu_factor(a, piv):
    """In-place LU with partial pivoting (Doolittle, L unit lower); False if singular.

    ``piv[k]`` receives the row swapped with row k (a float array works: the indices are
    exact).
    """
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


@njit(cache=True, inline="always")
def lu_solve(a, piv, x):
    """Solve with the factors of ``lu_factor``; ``x`` holds the right-hand side on entry."""
    n = a.shape[0]
    for k in range(n):
        m = int(piv[k])
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


@njit(cache=True, inline="always")
def fd_jacobian(rhs, p, t, y, mode, f0, jac, dfdt, ytmp, ftmp):
    """Forward-difference d rhs/dy and central-difference d rhs/dt in ``mode``.

    ``f0`` is rhs(t, y); ``jac`` (dim, dim) and ``dfdt`` (dim,) receive the derivatives,
    ``ytmp`` and ``ftmp`` (dim,) are scratch. Column ``j`` steps by ``sqrt(eps) max(1,
    |y_j|)``; ``t`` by ``eps^(1/3) max(1, |t|)^(1/3)`` (the forcing's phase carries a
    rounding error ~ eps |w t|, so the step must grow slowly with |t|; a forward difference
    in t would cost ~ 1e-4 of f_t at t ~ 1e4). Returns the rhs evaluations used (dim + 2).
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
