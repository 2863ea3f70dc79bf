"""Rigid impacts: an ``advance`` that stops at every switch and resets velocities there.

``impact_loop(name, advance)`` wraps a method's ``advance`` (same signature, see
``driver``) for systems with rigid stops. The wrapped method runs with a switch budget of
0, so it returns right after every located switch with the state on the surface; when the
switch is a rigid stop's contact surface entered from the free side, this loop makes the
impact (Newton's law with restitution ``r``, momentum of the two bodies kept):

    v+ = v- - (1 + r) g'(v-) w,    g' = a . v (the surface's rate), w = M^-1 a / (a^T M^-1 a)

so that ``g'+ = -r g'-``; a wall's ``a`` has one entry and ``w`` moves that body alone.
The contact bit is then cleared (free flight) unless the impacts accumulate.

**Chattering and sticking.** With ``r < 1`` and the free relative acceleration ``g''``
pushing the bodies together, the impacts form a geometric series (Budd and Dux 1994):
flight times ``2 r^k u / g''`` from a separating speed ``u``, accumulating after
``2 u / ((1 - r) g'')``. The loop follows the impacts until the next flight would rise no
more than ``RESOLUTION * max(1, |y|)`` from the surface (below what positions resolve),
then jumps to the accumulation point: the relative velocity is set to 0 (momentum kept) and
the stop *sticks* (its contact bit set: ``chain.py``'s right-hand side holds the bodies
together, the surface is not watched). The remaining ``2 u / ((1 - r) g'')`` of chatter is
spent stuck, the constrained motion it approximates to O(u). ``r = 0`` sticks at once.
A stuck stop is released when the contact force would pull: when the free ``g''`` turns
negative (below ``-PULL``, see there), located by Illinois on time (re-integrating from
the chunk's start) to rounding. The stuck phase advances in chunks of
``opts[H_MAX] / STUCK_CHUNKS``, the release tested at each chunk's end.

The system packs its **impact table** behind its parameters (``chain.py``), its start as
``p``'s last entry: ``p[at]`` the number of rigid stops, then per stop a block of
``2 + bodies`` entries: its contact surface's index (``SURFACE``), ``r``
(``RESTITUTION``), ``w`` per body (``DIRECTION``).

**Tangent vectors.** With a variational system (``systems/variational.py``: the state is
``z = (y, vec Phi)``, ``y`` the bodies' ``n = 2 bodies`` entries, read from the impact
table's size) the loop carries ``Phi`` across every reset, ``Phi <- S Phi``, S the
saltation matrix of a reset ``y+ = R(y-)`` at ``h(y) = g = 0`` (Fredriksson and Nordmark
1997; Leine and Nijmeijer 2004; di Bernardo et al. 2008, ch. 2; ``saltation.reset_saltation``):

    S = DR + (f+ - DR f-) grad h^T / (grad h . f-),   DR = I - c (0, w)(0, a)^T,

f- the field before the reset at y-, f+ the field after it at y+ (in the mode after: free,
or stuck), ``c`` the reset's factor. What this gives, case by case:

- **an impact** (``c = 1 + r``, free on both sides): for one body on a wall, with
  accelerations a+- just after and before, ``S = [[-r, 0], [(a+ + r a-) / v-, -r]]``,
  ``det S = r^2 = det DR (grad h . DR^-1 f+) / (grad h . f-)``; its multipliers' product
  over a period-1 single-impact orbit is ``r^2 exp(-c T / m)``.
- **entering sticking** (the chatter accumulated, or ``r = 0``; the plastic reset, ``c =
  1``, f+ the stuck field): the position rows of S are ``I - w a^T`` and the velocity rows
  ``(I - w a^T)`` plus a time correction: the tangent vectors lose the relative normal
  displacement and velocity (they lie on the constraint, which the stuck flow keeps), and
  for two bodies whose damping per mass differs the common velocity takes the drift
  ``kappa (a . dx)`` that the relative motion's damping gives it while the gap closes (the
  chatter's integral of ``kappa g'`` is ``kappa`` times the gap closed, whatever the
  cut-off ``RESOLUTION``); for a wall the whole body's row is 0 (every stuck state is the
  same). From a tangential contact (``g' = 0``) S is the projection ``I - w a^T`` on both.
- **while stuck**: the stuck field's variational equations (``chain.chain_jacobian`` sticks
  the Jacobian's columns as the accelerations are): tangents on the constraint stay there.
- **release**: the free ``g''`` crosses ``-PULL`` ~ 0, where the stuck and the free fields
  agree: the field is continuous, S = I (``kernels/lyapunov.py`` sees no crossing there,
  the surface being unwatched while stuck; entering sticking it sees the contact bit set
  and a rate ``a . v+ = 0`` exactly, so its S is I: the impact's S is this loop's).
- a crossing at ``g' <= 0`` (a graze of rounding size): no reset, S = I.

The switch budget is checked after the impacts of a switch are made, so that a caller
stopping at every switch (Benettin's kernel, budget 0) continues from the reset state.

Counters (``istate``): ``N_IMPACTS`` (impacts, resets made), ``N_CHATTERS`` (chatter
sequences ended by an accumulation, ``r > 0``), ``N_STICKS`` (sticking phases begun);
``fstate[T_STUCK]`` the time spent stuck. The switch budget ``opts[MAX_SWITCHES]``
counts every switch (impacts too) of one call, as the wrapped method does.
"""

import numpy as np
from numba import njit

from .codes import OK, TOO_MANY_SWITCHES
from .driver import _jit_as
from .layout import (
    H_MAX,
    MAX_G,
    MAX_SWITCHES,
    MODE,
    N_CHATTERS,
    N_IMPACTS,
    N_STICKS,
    T_STUCK,
    T_SWITCH,
)
from .saltation import apply_to_tangents, reset_saltation

SURFACE, RESTITUTION, DIRECTION = 0, 1, 2  # a rigid stop's block in the impact table
RESOLUTION = 1e-12  # a chatter flight rising less than this (x max(1, |y|)): accumulated
# A stuck stop is released once its free g'' is below -PULL * max(1, |y|), not at 0: there the
# body would leave with g = g' = 0 and g'' of rounding size, and the step's dense output,
# its own rounding larger, would cross the surface again and again (seen: 10^4 switches in
# one period of the chattering case). The release comes later by PULL / |d g''/dt|.
PULL = 1e-12
# ... and, leaving the surface tangentially (g = g' = 0), the bodies are moved apart by
# NUDGE * max(1, |y|) (rounding size): the step's dense output, whose rounding is as large
# as its g there, would otherwise see the surface crossed again at every restart.
NUDGE = 1e-15
STUCK_CHUNKS = 8.0  # a stuck phase advances opts[H_MAX] / STUCK_CHUNKS at a time
RELEASE_ITERATIONS = 100


@njit(cache=True)
def table_start(p):
    """Where the impact table begins in ``p`` (its last entry says)."""
    return int(p[p.shape[0] - 1])


@njit(cache=True)
def table_size(p, at):
    """The size of a rigid stop's block in the impact table at ``at``: ``2 + bodies``
    (read from the table's length, ``p``'s end: the table is its tail)."""
    return (p.shape[0] - at - 2) // int(p[at])


@njit(cache=True)
def pull(y, n):
    """The free g'' below which a stuck stop is released (see PULL); ``y[:n]`` the state
    (a variational system's tangent entries behind it are not looked at)."""
    scale = 1.0
    for k in range(n):
        scale = max(scale, abs(y[k]))
    return PULL * scale


@njit(cache=True)
def surface_rate(A, s, y, n):
    """``g_s'`` at state ``y[:n]`` (positions and velocities interleaved: ``x_k = y[2 k]``,
    ``v_k = y[2 k + 1]``; a stop's surface reads positions only)."""
    rate = 0.0
    for k in range(n // 2):
        rate += A[s, 2 * k] * y[2 * k + 1]
    return rate


@njit(cache=True)
def free_acceleration(rhs, p, t, y, mode, A, s, f, n):
    """``g_s''`` of the flow with stop ``s`` free (its bit cleared from ``mode``); > 0:
    the bodies are pushed into the stop."""
    rhs(t, y, p, mode & ~(1 << s), f)
    acc = 0.0
    for k in range(n // 2):
        acc += A[s, 2 * k] * f[2 * k + 1]
    return acc


@njit(cache=True)
def plastic(p, block, y, n):
    """Relative velocity 0 across the stop, momentum kept: a wall's body at rest, two
    bodies at their momentum-weighted mean velocity, the same float for both."""
    n = n // 2
    first, second = -1, -1
    for k in range(n):
        if p[block + DIRECTION + k] != 0.0:
            if first < 0:
                first = k
            else:
                second = k
    if second < 0:
        y[2 * first + 1] = 0.0
        return
    # w_k = (a_k / m_k) / sum(a^2 / m): the masses' weights are |w| of the other body
    w1, w2 = abs(p[block + DIRECTION + first]), abs(p[block + DIRECTION + second])
    common = (w2 * y[2 * first + 1] + w1 * y[2 * second + 1]) / (w1 + w2)
    y[2 * first + 1] = common
    y[2 * second + 1] = common


@njit(cache=True)
def leave(p, block, y, n, gap):
    """Move the bodies of a stop apart along the surface's normal (momentum-weighted,
    ``DIRECTION``) to ``g = min(gap, 0) - NUDGE * max(1, |y|)`` (``a . w = 1``), ``gap``
    its ``g`` now: a stop stuck or grazed a location error inside the surface (seen:
    2e-13 where an impact was located on a variational system's step, whose size its
    tangents' error sets) would be seen crossing it again at once, for ever."""
    step = NUDGE * pull(y, n) / PULL + max(gap, 0.0)
    for k in range(n // 2):
        y[2 * k] -= step * p[block + DIRECTION + k]


@njit(cache=True)
def surface_gap(A, b, s, y, n):
    """``g_s = A[s] . y[:n] + b[s]``."""
    g = b[s]
    for k in range(n):
        g += A[s, k] * y[k]
    return g


@njit(cache=True)
def leave_released(p, table, released, y, A, b):
    """``leave`` for every stop in the mask ``released``."""
    at, size, _ = table
    n = 2 * (size - 2)
    for k in range(int(p[at])):
        block = at + 1 + k * size
        s = int(p[block + SURFACE])
        if (released >> s) & 1:
            leave(p, block, y, n, surface_gap(A, b, s, y, n))


@njit(cache=True)
def impact(rhs, p, t, y, n, block, surface, mode, istate, f):
    """The reset at a crossing into rigid stop surface ``s`` (``surface = (A, b, s)``: the
    surfaces' rows and offsets, and its index; ``block`` its table entry) of the state
    ``y[:n]``; returns (whether the stop sticks (the chatter accumulated, or ``r =
    0`` with the bodies pushed together), the factor c of the velocity reset made, ``v+ =
    v- - c g'(v-) w``: 1 + r, or 0 when no reset)."""
    A, b, s = surface
    r = p[block + RESTITUTION]
    rate = surface_rate(A, s, y, n)
    factor = 0.0
    if rate > 0.0:  # approaching (a crossing at rate <= 0 is a graze of rounding size)
        factor = 1.0 + r
        for k in range(n // 2):
            y[2 * k + 1] -= factor * rate * p[block + DIRECTION + k]
        istate[N_IMPACTS] += 1
    else:
        rate = 0.0
    acc = free_acceleration(rhs, p, t, y, mode, A, s, f, n)
    if acc <= -pull(y, n):  # it leaves (between -PULL and 0 it sticks: see PULL)
        if rate == 0.0:  # tangentially: see NUDGE
            leave(p, block, y, n, surface_gap(A, b, s, y, n))
        return False, factor
    speed = r * rate
    scale = 1.0
    for k in range(n):
        scale = max(scale, abs(y[k]))
    if r < 1.0 and speed * speed <= 2.0 * acc * RESOLUTION * scale:
        if speed > 0.0:
            istate[N_CHATTERS] += 1
        plastic(p, block, y, n)
        istate[N_STICKS] += 1
        return True, factor
    return False, factor


@njit(cache=True)
def impact_tangents(rhs, p, t, states, n, block, a, modes, reset):
    """Carry the tangent vectors of a variational state ``z = (y, vec Phi)`` across an
    impact: ``Phi <- S Phi``, S the saltation matrix of the reset (see the module's doc).
    ``states``: (z before the reset, z after it, changed in place); ``a``: the stop's
    surface row; ``modes``: the modes before and after it; ``reset``: (whether it stuck,
    ``impact``'s factor; a stuck stop's reset, plastic in all, has 1)."""
    before, z = states
    sticks, factor = reset
    S = np.empty((n, n))
    DR = np.zeros((n, n))
    for i in range(n):
        DR[i, i] = 1.0
    c = 1.0 if sticks else factor
    bodies = n // 2
    for i in range(bodies):
        w = p[block + DIRECTION + i]
        for j in range(bodies):
            DR[2 * i + 1, 2 * j + 1] -= c * w * a[2 * j]
    fb = np.empty(z.shape[0])
    fa = np.empty(z.shape[0])
    rhs(t, before, p, modes[0], fb)
    rhs(t, z, p, modes[1], fa)
    rate = reset_saltation(DR, fb, fa, a, n, S)
    if sticks and rate <= 0.0:  # stuck from a tangential contact: on the constraint
        for i in range(bodies):
            w = p[block + DIRECTION + i]
            for j in range(bodies):
                S[2 * i, 2 * j] -= w * a[2 * j]
    apply_to_tangents(S, z, n)


@njit(cache=True)
def releasing(rhs, p, t, y, mode, stuck, A, table, f):
    """The mask of the stuck stops (bits of ``stuck``) whose free ``g''`` is below
    ``-pull(y)`` at ``(t, y)`` in ``mode``, and the smallest free ``g'' + pull(y)`` over
    them (< 0: released)."""
    at, size, _ = table
    n = 2 * (size - 2)
    released, lowest, margin = 0, np.inf, pull(y, n)
    for k in range(int(p[at])):
        s = int(p[at + 1 + k * size + SURFACE])
        if not (stuck >> s) & 1:
            continue
        acc = free_acceleration(rhs, p, t, y, mode, A, s, f, n)
        lowest = min(lowest, acc + margin)
        if acc + margin < 0.0:
            released |= 1 << s
    return released, lowest


def impact_loop(name, advance):
    """The ``advance`` of method ``name`` with rigid impacts (see the module's doc)."""

    @_jit_as(f"{name}_impacts")
    def run_to(rhs, p, y, t, t_end, surfaces, inner, state, samples, saved):
        """Restore the saved (y, istate, fstate) and advance from ``t`` to ``t_end``."""
        istate, fstate, _ = state
        y[:] = saved[0]
        istate[:] = saved[1]
        fstate[:] = saved[2]
        return advance(rhs, p, y, t, t_end, surfaces, inner, state, samples)

    @_jit_as(f"{name}_impacts")
    def stuck_chunk(rhs, p, y, span, surfaces, opts, inner, state, samples, impacts):
        """Advance a stuck phase by one chunk, or to its release; (status, time reached).
        ``span``: (t, t_end); ``impacts``: (the impact table's (at, size, rigid mask), the
        work vector f). The status is the wrapped method's (TOO_MANY_SWITCHES: another
        surface switched)."""
        t, t_end = span
        table, f = impacts
        A_s = surfaces[0]
        istate, fstate, _ = state
        rigid = table[2]
        stuck = istate[MODE] & rigid
        released, _ = releasing(rhs, p, t, y, istate[MODE], stuck, A_s, table, f)
        if released != 0:  # the force pulls already (a switch elsewhere changed it)
            istate[MODE] &= ~released
            leave_released(p, table, released, y, A_s, surfaces[1])
            return OK, t
        t_b = min(t + opts[H_MAX] / STUCK_CHUNKS, t_end)
        saved = (y.copy(), istate.copy(), fstate.copy())
        status = advance(rhs, p, y, t, t_b, surfaces, inner, state, samples)
        if status == TOO_MANY_SWITCHES:
            t_b = fstate[T_SWITCH]
        elif status != OK:
            return status, t_b
        # the stuck bits again (a switch elsewhere set the unwatched ones from the state);
        # a rigid stop just hit keeps its bit for the caller to see
        istate[MODE] |= stuck
        mode = (istate[MODE] & ~rigid) | stuck
        released, _ = releasing(rhs, p, t_b, y, mode, stuck, A_s, table, f)
        if released == 0:
            fstate[T_STUCK] += t_b - t
            return status, t_b
        # Illinois on the smallest free g'' + pull over [t, t_b]: >= 0 at t, < 0 at t_b
        lo, hi = t, t_b
        _, g_lo = releasing(rhs, p, t, saved[0], saved[1][MODE], stuck, A_s, table, f)
        _, g_hi = releasing(rhs, p, t_b, y, mode, stuck, A_s, table, f)
        side = 0
        for _ in range(RELEASE_ITERATIONS):
            if hi - lo <= 4e-16 * max(1.0, abs(hi)):
                break
            mid = hi - g_hi * (hi - lo) / (g_hi - g_lo)
            if not lo < mid < hi:
                mid = 0.5 * (lo + hi)
            run_to(rhs, p, y, t, mid, surfaces, inner, state, samples, saved)
            _, g_mid = releasing(rhs, p, mid, y, saved[1][MODE], stuck, A_s, table, f)
            if g_mid < 0.0:
                hi, g_hi = mid, g_mid
                if side == -1:
                    g_lo *= 0.5
                side = -1
            else:
                lo, g_lo = mid, g_mid
                if side == 1:
                    g_hi *= 0.5
                side = 1
        status = run_to(rhs, p, y, t, hi, surfaces, inner, state, samples, saved)
        if status == TOO_MANY_SWITCHES:
            hi = fstate[T_SWITCH]
        istate[MODE] |= stuck
        released, _ = releasing(rhs, p, hi, y, (istate[MODE] & ~rigid) | stuck, stuck, A_s,
                                table, f)
        istate[MODE] &= ~released
        leave_released(p, table, released, y, A_s, surfaces[1])
        fstate[T_STUCK] += hi - t
        return status, hi

    @_jit_as(f"{name}_impacts")
    def advance_impacts(rhs, p, y, t, t_end, surfaces, opts, state, samples):
        """Integrate ``y`` in place from ``t`` to exactly ``t_end`` with rigid impacts; a
        status code."""
        A_s = surfaces[0]
        istate, fstate, _ = state
        dim = y.shape[0]
        at = table_start(p)
        size = table_size(p, at)
        n = 2 * (size - 2)  # the bodies' state; a variational system's tangents follow
        rigid = 0
        for k in range(int(p[at])):
            rigid |= 1 << int(p[at + 1 + k * size + SURFACE])
        table = (at, size, rigid)
        inner = opts.copy()
        inner[MAX_SWITCHES] = 0.0
        f = np.empty(dim)
        switches = 0
        while t_end - t > 1e-14 * max(1.0, abs(t_end)):
            before = istate[MODE]
            stuck = before & rigid
            if stuck != 0:
                status, t = stuck_chunk(rhs, p, y, (t, t_end), surfaces, opts, inner, state,
                                        samples, (table, f))
                stuck = istate[MODE] & rigid
                before = (before & ~rigid) | stuck
            else:
                status = advance(rhs, p, y, t, t_end, surfaces, inner, state, samples)
                if status == OK:
                    return OK
                t = fstate[T_SWITCH]
            if status == OK:
                continue
            if status != TOO_MANY_SWITCHES:
                return status
            switches += 1
            after = istate[MODE]
            hits = after & rigid & ~before
            istate[MODE] = (after & ~rigid) | stuck  # free until the impact says
            if hits != 0:
                fstate[MAX_G] = max(fstate[MAX_G], 0.0)
            for k in range(int(p[at])):
                block = at + 1 + k * size
                s = int(p[block + SURFACE])
                if not (hits >> s) & 1:
                    continue
                mode = istate[MODE]
                before_reset = y.copy() if dim > n else y
                sticks, factor = impact(rhs, p, t, y, n, block, (A_s, surfaces[1], s), mode,
                                        istate, f)
                if sticks:
                    istate[MODE] |= 1 << s
                if dim > n:  # a variational state: its tangents cross the impact too
                    impact_tangents(rhs, p, t, (before_reset, y), n, block, A_s[s],
                                    (mode, istate[MODE]), (sticks, factor))
            # the budget is checked once the impacts are made: a caller stopping at every
            # switch (kernels/lyapunov.py, budget 0) continues from the reset state
            if switches > opts[MAX_SWITCHES]:
                fstate[T_SWITCH] = t
                return TOO_MANY_SWITCHES
        return OK

    return advance_impacts
