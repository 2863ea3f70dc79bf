"""The saltation matrix: how a perturbation jumps where the vector field jumps.

A trajectory of a piecewise-smooth flow crosses the switching surface ``h(y) = 0`` at
time t*, leaving the field f- (the mode before) for f+ (the mode after). A neighbouring
trajectory crosses a little earlier or later, so the fundamental matrix jumps by

    Phi(t*+) = S Phi(t*-),   S = I + (f+ - f-) grad h^T / (grad h . f-),

f+- evaluated at (t*, y(t*)) (Aizerman and Gantmakher 1958; Leine and Nijmeijer 2004,
ch. 7; di Bernardo et al. 2008, ch. 2). The systems are non-autonomous only through the
forcing, which is continuous in t, and the surfaces do not depend on t, so the state
formula holds as it is. The surfaces are affine, ``h = A[i] . y + b[i]``, so grad h is
the row ``A[i]`` (its first ``n`` entries: the rows of a variational system carry zeros
for the fundamental matrix).

The surfaces the registered systems have, and what S is on each:

- **contact** ``delta = x1 - x2 - d = 0``, grad h = (1, 0, -1, 0). With the paper's law
  the stop force jumps from 0 to ``c_c delta'`` at onset (and back at release), so
  ``f+ - f- = c_c delta' (0, -1, 0, 1)`` and ``grad h . f- = delta'``: S = I + c_c e a^T
  at onset and I - c_c e a^T at release (e = (0, -1, 0, 1), a = grad h), independent of
  the crossing speed (finite even at a grazing contact) and of determinant 1.
  Hunt-Crossley's force is continuous at onset (delta^n = 0): S = I. No-tension: onset
  as the paper's law while ``delta' > 0``; its release happens where the force has
  already reached zero (below), so S = I there.
- **no-tension force surface** ``k_c delta + c_c delta' = 0``: the force is 0 on both
  sides, the field is continuous, S = I.
- **bilinear springs** ``x1 = -d1``, ``x2 = d1``: the extra spring's force ``k2 (x1 +
  d1) H(-x1 - d1)`` is continuous across its gap, S = I.

The kernels need no case analysis: :func:`saltation` evaluates the general formula, which
gives exactly I wherever f+ = f-. The variational right-hand side writes f in its first
``n`` outputs, so it serves for f+-.
"""

from numba import njit


@njit(cache=True)
def saltation(rhs, p, t, z, n, mode_before, mode_after, a, S):
    """Write the saltation matrix of a crossing at (t, y = z[:n]) into ``S`` (n, n).

    rhs : the (variational or base) right-hand side, ``rhs(t, z, p, mode, out)`` writing
    f into ``out[:n]``; a : (>= n,) the crossed surface's gradient (row of A). Returns
    ``grad h . f-``: S is I where it is 0 (a tangency with no transversal crossing).
    """
    before = z.copy()
    after = z.copy()
    fb = z.copy()
    fa = z.copy()
    rhs(t, before, p, mode_before, fb)
    rhs(t, after, p, mode_after, fa)
    rate = 0.0
    for k in range(n):
        rate += a[k] * fb[k]
    for i in range(n):
        for j in range(n):
            S[i, j] = 1.0 if i == j else 0.0
    if rate == 0.0:
        return rate
    for i in range(n):
        jump = (fa[i] - fb[i]) / rate
        for j in range(n):
            S[i, j] += jump * a[j]
    return rate


@njit(cache=True)
def apply_to_tangents(S, z, n):
    """``Phi <- S Phi`` for the fundamental matrix stored row-major in ``z[n:]``."""
    col = z[:n].copy()
    for j in range(n):
        for i in range(n):
            col[i] = z[n + i * n + j]
        for i in range(n):
            acc = 0.0
            for k in range(n):
                acc += S[i, k] * col[k]
            z[n + i * n + j] = acc


@njit(cache=True)
def reset_saltation(DR, fb, fa, a, n, S):
    """The saltation matrix of a reset ``y+ = R(y-)`` on the surface ``h(y) = 0`` into
    ``S`` (n, n):

        S = DR + (f+ - DR f-) grad h^T / (grad h . f-),

    DR (n, n) the reset's Jacobian, fb = f- before it, fa = f+ after it (their first ``n``
    entries), a the gradient of h (Leine and Nijmeijer 2004, ch. 7; di Bernardo et al.
    2008, ch. 2; Fredriksson and Nordmark 1997). With ``DR = I`` it is :func:`saltation`'s
    matrix. Returns ``grad h . f-``; where it is 0 (a tangency) ``S = DR``, no time
    correction.
    """
    rate = 0.0
    for k in range(n):
        rate += a[k] * fb[k]
    for i in range(n):
        jump = 0.0
        if rate != 0.0:
            jump = fa[i]
            for k in range(n):
                jump -= DR[i, k] * fb[k]
            jump /= rate
        for j in range(n):
            S[i, j] = DR[i, j] + jump * a[j]
    return rate
