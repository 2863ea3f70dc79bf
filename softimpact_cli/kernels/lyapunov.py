"""Benettin's method on the variational equations of a piecewise-smooth flow.

The state is ``z = (y, vec Phi)`` of a variational system (``systems/variational.py``:
``Phi' = J(t, y, mode) Phi``, ``Phi`` row-major, its columns the tangent vectors). From
``t0`` the kernel advances ``z`` over ``n_intervals`` intervals of length ``interval``;
at the end of each it re-orthonormalises the columns (Gram-Schmidt, ``Phi = Q R``,
``Phi <- Q``) and writes ``ln R_jj``, the growth of the j-th volume direction over the
interval (Benettin, Galgani, Giorgilli and Strelcyn 1980; Shimada and Nagashima 1979).
The exponents are the sums of these logarithms over a stretch, divided by its duration
(``analysis/lyapunov.py`` averages them over segments).

Switches: the driver's ``advance`` is called with a switch budget of 0
(``opts[MAX_SWITCHES] = 0``), so it returns ``TOO_MANY_SWITCHES`` right after crossing a
surface, the state on the surface in the new mode and the switch time in
``fstate[T_SWITCH]``. The kernel then applies the saltation matrix of that crossing to
the tangent vectors (``saltation.py``; ``use_saltation = False`` leaves them as they are,
which is wrong wherever the field jumps: kept to show it) and advances on. The crossed
surface is the one watched before the switch whose side changed; when two surfaces are
crossed at the same instant, the first one's S is applied (a codimension-two event).
The real switch budget ``opts[MAX_SWITCHES]`` still bounds the switches per interval.

Rigid stops: ``advance`` is then the impact loop (``impacts.py``), which returns after each
switch with the impact's reset made and the tangent vectors carried across it by the
reset's saltation matrix; here the mode before and after such an impact agree on the
stop's bit (no S applied), or the stop sticks, where the velocity across it is 0 exactly
and :func:`saltation` gives I.
"""

from math import log, sqrt

import numpy as np
from numba import njit

from .codes import OK, TOO_MANY_SWITCHES
from .layout import MAX_SWITCHES, MODE, T_SWITCH
from .orbit import new_state, no_samples
from .saltation import apply_to_tangents, saltation


@njit(cache=True)
def orthonormalise(z, n, logs):
    """Columns of ``Phi`` (row-major in ``z[n:]``) to an orthonormal basis, in place, by
    modified Gram-Schmidt with one reorthogonalisation; ``logs[j] = ln R_jj``."""
    Q = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            Q[i, j] = z[n + i * n + j]
    for j in range(n):
        for _ in range(2):  # "twice is enough" (Giraud et al. 2005)
            for k in range(j):
                r = 0.0
                for i in range(n):
                    r += Q[i, k] * Q[i, j]
                for i in range(n):
                    Q[i, j] -= r * Q[i, k]
        norm = 0.0
        for i in range(n):
            norm += Q[i, j] * Q[i, j]
        norm = sqrt(norm)
        logs[j] = log(norm) if norm > 0.0 else -np.inf
        for i in range(n):
            Q[i, j] = Q[i, j] / norm if norm > 0.0 else 0.0
    for i in range(n):
        for j in range(n):
            z[n + i * n + j] = Q[i, j]


@njit(cache=True)
def _lowest_bit(mask):
    i = 0
    while not (mask >> i) & 1:
        i += 1
    return i


@njit(cache=True)
def benettin(advance, rhs, p, z0, n, start, surfaces, opts, use_saltation):
    """Benettin's method from ``z0 = (y0, vec Q0)`` at ``start = (t0, interval,
    n_intervals, per_section)``.

    advance : an adaptive method's ``advance`` (the variational system has no Jacobian
    for the implicit ones); rhs : the variational right-hand side; n : dimension of y;
    surfaces : the variational system's (A, b, relevance, contact); opts : its options
    (``opts[MAX_SWITCHES]``: the switch budget per interval).

    Returns ``(status, intervals done, salted, switches), (logs (n_intervals, n),
    sections (n_intervals // per_section, n)), z, istate``: ``logs[k, j] = ln R_jj`` of interval
    k; ``sections`` the state every ``per_section`` intervals; ``salted`` the switches at
    which a saltation matrix was applied (it differed from I or not), ``switches`` all.
    Rows after a failure are NaN.
    """
    t0, interval, n_intervals, per_section = start
    z = z0.copy()
    A_s, b_s, relevance, _ = surfaces
    state = new_state(z, A_s, b_s)
    istate, fstate, _ = state
    samples = no_samples(z.shape[0])
    stop = opts.copy()
    stop[MAX_SWITCHES] = 0.0
    budget = opts[MAX_SWITCHES]
    logs = np.full((n_intervals, n), np.nan)
    sections = np.full((n_intervals // per_section, n), np.nan)
    S = np.empty((n, n))
    salted, switches, t = 0, 0, t0
    for k in range(n_intervals):
        t_end = t0 + (k + 1) * interval
        in_interval = 0
        while t_end - t > 1e-14 * max(1.0, abs(t_end)):
            before = istate[MODE]
            status = advance(rhs, p, z, t, t_end, surfaces, stop, state, samples)
            if status == OK:
                break
            if status != TOO_MANY_SWITCHES:
                return (status, k, salted, switches), (logs, sections), z, istate
            t = fstate[T_SWITCH]
            crossed = (before ^ istate[MODE]) & relevance[before]
            switches += 1
            in_interval += 1
            if use_saltation and crossed != 0:
                saltation(rhs, p, t, z, n, before, istate[MODE], A_s[_lowest_bit(crossed)], S)
                apply_to_tangents(S, z, n)
                salted += 1
            if in_interval > budget:
                return (TOO_MANY_SWITCHES, k, salted, switches), (logs, sections), z, istate
        t = t_end
        orthonormalise(z, n, logs[k])
        if (k + 1) % per_section == 0:
            sections[(k + 1) // per_section - 1] = z[:n]
    return (OK, n_intervals, salted, switches), (logs, sections), z, istate
