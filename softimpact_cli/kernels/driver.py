"""The integration loops every method shares: one adaptive, one on a fixed grid.

A method module holds its tableau and its *hooks*, small jitted functions, and builds its
``advance`` from them with ``adaptive_loop`` or ``fixed_loop``:

    advance(rhs, p, y, t, t_end, surfaces, opts, state, samples) -> status

integrates ``y`` in place from ``t`` to exactly ``t_end`` (``surfaces``: the switching
surfaces ``(A, b, relevance, contacts)``, ``contacts`` the bit mask of the contact surfaces;
``state``: ``(istate, fstate, work)`` from
``orbit.new_state``; ``samples``: ``(sample_t, sample_y)``). The loops are closures over
the hooks, so every hook call is a static call numba inlines, exactly as if the loop were
written out in the method's module (a hook passed as a value would cost a call per step
and, built into jitted code, defeat the disk cache). The mode is frozen over a step; when
an accepted step's dense output shows a watched surface crossed (or grazed), the step is
redone up to the crossing, the mode switches there and the method restarts (no stage is
reused across a switch).

Every hook receives ``variant = istate[VARIANT]``, which of its steps the method takes
now (``auto``: 0 explicit, 1 stiff; a single method: always 0):

* ``begin(rhs, p, t, y, mode, work, variant)``: what a step needs at its start (f, and
  for Rodas4 the Jacobian); returns the right-hand side evaluations used.
* ``step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant)``: one step into
  ``work[YNEW]``; returns (ok, evaluations), ok False when its linear algebra failed.
  ``stage_A``, ``stage_b`` are the surfaces each stage reads its mode from (the plain
  scheme); they have no rows when switches are located (the mode is frozen).
* ``error(y, h, work, opts, variant)``: the scaled error norm of the step.
* ``controller(variant)``: its ``control.Controller`` constants.
* ``dense(y, h, work, variant)``: the step's dense output as monomial rows (``dense``).
* ``refine(rhs, p, t, y, h, h_full, mode, surface, work, variant)``: a located crossing
  made exact on the step itself; ``surface`` = (A row, b) of the crossed surface; returns
  (step length, evaluations). ``no_refinement`` when dense output suffices.
* ``accept(y, h, h_next, work, istate, variant)``: take the accepted step: the method's
  tests on it (``auto``'s stiffness tests), ``y`` moves to ``work[YNEW]``, its own
  bookkeeping (FSAL copies, counters); returns (whether to change the method, whether
  the next step needs ``begin`` again).
* ``change_method(istate, mode)``, ``enter_mode(istate)``: ``auto``'s method state
  (``change_method`` returns True: begin again; ``enter_mode`` True when the new mode
  changes the method); ``no_change`` and ``same_method`` for a single method.

A switch budget ``opts[MAX_SWITCHES]`` exceeded ends the call with ``TOO_MANY_SWITCHES``
right after the crossing, ``y`` on the surface in the new mode and the switch time in
``fstate[T_SWITCH]``: with a budget of 0 a caller stops at every switch (Benettin's method
applies the saltation matrix there, ``kernels/lyapunov.py``).

``name`` (the method's, a Python identifier) names the loops in numba's disk cache.
"""

from math import ceil

import numpy as np
from numba import njit

from .borrow import borrow
from .codes import DIVERGED, OK, STEP_BUDGET, STEP_UNDERFLOW, TOO_MANY_SWITCHES
from .common import apply_switch, out_of_bounds, plain_mode_update, track_contact, track_contact_at
from .control import first_step, landing, next_step, reject_factor, rejects
from .dense import write_samples
from .layout import (
    BOUND,
    H_FIXED,
    H_MAX,
    LOCATE,
    MAX_STEPS,
    MAX_SWITCHES,
    MODE,
    N_REJECTED,
    N_RHS,
    N_STEPS,
    T_SWITCH,
    VARIANT,
    H,
)
from .switching import earliest_exit

# ---------------------------------------------------------------------------------------
# what single methods leave out


@njit(cache=True, inline="always")
def no_refinement(rhs, p, t, y, h, h_full, mode, surface, work, variant):
    return h, 0


@njit(cache=True, inline="always")
def no_change(istate, mode):
    return True


@njit(cache=True, inline="always")
def same_method(istate):
    return False


@njit(cache=True, inline="always")
def stopped_at_switch(fstate, t, h_next):
    """The switch budget is spent: record where (``fstate[T_SWITCH]``, for a caller that
    continues from the switch, e.g. to apply a saltation matrix) and the step proposed
    next; the status that says so."""
    fstate[T_SWITCH], fstate[H] = t, h_next
    return TOO_MANY_SWITCHES


# ---------------------------------------------------------------------------------------
# pieces of the loops. Bundles are unpacked once per call of a loop: numba counts the
# references of every array taken out of a tuple, and per step that costs as much as the
# step's arithmetic, so what runs every step takes plain arrays, borrowed (``borrow``):
# numba counts references to every array an inlined hook binds and every row view handed
# to the right-hand side, ~60 ns of a ~370 ns dopri5 step on a 4-variable system.


@njit(cache=True, inline="always")
def borrowed(p, y, opts, surfaces, state, samples):
    """A loop's arrays without reference counting (``borrow``: the loop's caller holds
    them for the whole call): (p, y, opts), surfaces, state, samples."""
    (A_s, b_s, relevance, contact), (istate, fstate, work), (sample_t, sample_y) = \
        surfaces, state, samples
    return ((borrow(p), borrow(y), borrow(opts)),
            (borrow(A_s), borrow(b_s), borrow(relevance), contact),
            (borrow(istate), borrow(fstate), borrow(work)),
            (borrow(sample_t), borrow(sample_y)))


@njit(cache=True, inline="always")
def stage_surfaces(A_s, b_s, locate):
    """The surfaces stages read their mode from: none when switches are located (empty
    slices of the loop's borrowed ``A_s``, ``b_s``: no reference counting either; new
    empty arrays, counted, cost ~5 ns per step)."""
    if locate:
        return A_s[:0], b_s[:0]
    return A_s, b_s


def _jit_as(name):
    """``njit(cache=True)`` for a closure of the method ``name``, under its own name: its
    own file in numba's disk cache (``warmup.missing_kernels`` can tell which method is
    compiled) and a stable identity (see ``numba_cache``), since its callers' cache keys
    and its own index key pickle it."""
    def decorate(function):
        function.__name__ = function.__qualname__ = f"{function.__name__}_{name}"
        dispatcher = njit(cache=True)(function)
        dispatcher._set_uuid(f"softimpact:kernels.driver.{function.__name__}")
        return dispatcher
    return decorate


def crossing_pieces(name, step, dense, refine, enter_mode):
    """(redo, cross) of a method: redo a step up to a located crossing; cross there."""

    @_jit_as(name)
    def redo(rhs, p, t, y, h, h_full, surfaces, mask, state, stage):
        """Redo the step up to the crossing (fraction found on the dense output), in the
        same frozen mode, refined by the method if it can; returns the step length (0: a
        grazing restart, leaving right at the start, takes no step), or -1 when the
        shorter step broke down (only on breakdown: it is shorter than an accepted one).
        ``stage``: the loop's (empty) stage surfaces."""
        A_s, b_s, _, _ = surfaces
        istate, fstate, work = state
        if h <= 0.0:
            return h
        variant, mode = istate[VARIANT], istate[MODE]
        ok, evals = step(rhs, p, t, y, h, mode, stage[0], stage[1], work, variant)
        istate[N_RHS] += evals
        if not ok:
            fstate[H] = h
            return -1.0
        dense(y, h, work, variant)
        i = 0
        while not (mask >> i) & 1:
            i += 1
        h, evals = refine(rhs, p, t, y, h, h_full, mode, (A_s[i], b_s[i]), work, variant)
        istate[N_RHS] += evals
        return h

    @_jit_as(name)
    def cross(mask, y, surfaces, istate):
        """Cross the surfaces in ``mask`` at ``y`` (``common.apply_switch``); the new mode
        may change the method."""
        A_s, b_s, relevance, contact = surfaces
        apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
        enter_mode(istate)

    return redo, cross


# ---------------------------------------------------------------------------------------
# the adaptive loop


def adaptive_loop(name, begin, step, error, controller, dense, refine, accept, change_method,
                  enter_mode):
    """The ``advance`` of an adaptive method with these hooks (see the module's doc)."""
    redo, cross = crossing_pieces(name, step, dense, refine, enter_mode)

    @_jit_as(name)
    def advance(rhs, p, y, t, t_end, surfaces, opts, state, samples):
        """Integrate ``y`` in place from ``t`` to exactly ``t_end``; a status code."""
        (p, y, opts), (A_s, b_s, relevance, contact), (istate, fstate, work), \
            (sample_t, sample_y) = borrowed(p, y, opts, surfaces, state, samples)
        locate = opts[LOCATE] != 0.0
        stage_A, stage_b = stage_surfaces(A_s, b_s, locate)
        coef = np.empty(5)
        h_floor, h = first_step(t, t_end, opts, fstate)
        need_first, rejected, steps, switches = True, False, 0, 0
        while t_end - t > 1e-14 * max(1.0, abs(t_end)):
            mode, v = istate[MODE], istate[VARIANT]
            if need_first:
                istate[N_RHS] += begin(rhs, p, t, y, mode, work, v)
                need_first = False
            h, h_step, truncated = landing(h, opts[H_MAX], t, t_end)
            ok, evals = step(rhs, p, t, y, h_step, mode, stage_A, stage_b, work, v)
            istate[N_RHS] += evals
            err, c = error(y, h_step, work, opts, v) if ok else np.inf, controller(v)
            if rejects(ok, err):
                istate[N_REJECTED] += 1
                rejected, h = True, h_step * reject_factor(ok, err, c)
                if h < h_floor:
                    fstate[H] = h
                    return STEP_UNDERFLOW
                continue
            h_next, rejected = next_step(err, c, h_step, h, rejected, truncated), False
            dense(y, h_step, work, v)
            u, mask, held = -1.0, 0, -1
            if locate and A_s.shape[0] > 0:
                u, mask, held = earliest_exit(work, A_s, b_s, relevance, mode, coef)
            if mask != 0:  # redo the step up to the crossing; the proposal stands
                h_full, h_next, truncated, held = h_step, h, False, -1
                h_step = redo(rhs, p, t, y, u * h_step, h_full, surfaces, mask, state,
                              (stage_A, stage_b))
                if h_step < 0.0:
                    return STEP_UNDERFLOW
            if h_step > 0.0:  # (a grazing restart takes no step)
                if locate:
                    track_contact(work, A_s, b_s, contact, fstate, coef, held)
                write_samples(work, t, h_step, opts, istate, sample_t, sample_y)
                change, need_first = accept(y, h_step, h_next, work, istate, v)
                istate[N_STEPS] += 1
                t, steps = t_end if truncated else t + h_step, steps + 1
                if out_of_bounds(y, opts[BOUND]):
                    fstate[H] = h_next
                    return DIVERGED
                if change:
                    need_first = change_method(istate, mode)
                if not locate and A_s.shape[0] > 0:  # plain scheme: the mode is the state's
                    plain_mode_update(y, A_s, b_s, contact, istate)
                    track_contact_at(y, A_s, b_s, contact, fstate)
                    if istate[MODE] != mode and enter_mode(istate):
                        need_first = True
            if mask != 0:
                cross(mask, y, surfaces, istate)
                need_first, switches = True, switches + 1
                if switches > opts[MAX_SWITCHES]:
                    return stopped_at_switch(fstate, t, h_next)
            h = h_next
            if steps > opts[MAX_STEPS]:
                fstate[H] = h
                return STEP_BUDGET
        fstate[H] = h
        return OK

    return advance


# ---------------------------------------------------------------------------------------
# the fixed-step loop


def fixed_loop(name, begin, step, dense, accept):
    """The ``advance`` of a fixed-step method with these hooks: steps on the grid ``t + k
    (t_end - t) / n``, ``n`` the smallest count whose step does not exceed
    ``opts[H_FIXED]``; a located switch inserts a step up to it and the grid goes on."""
    redo, cross = crossing_pieces(name, step, dense, no_refinement, same_method)

    @_jit_as(name)
    def advance(rhs, p, y, t, t_end, surfaces, opts, state, samples):
        """Integrate ``y`` in place from ``t`` to exactly ``t_end``; a status code."""
        (p, y, opts), (A_s, b_s, relevance, contact), (istate, fstate, work), \
            (sample_t, sample_y) = borrowed(p, y, opts, surfaces, state, samples)
        locate = opts[LOCATE] != 0.0
        stage_A, stage_b = stage_surfaces(A_s, b_s, locate)
        coef = np.empty(5)
        n = max(1, int(ceil((t_end - t) / opts[H_FIXED] - 1e-9)))
        t_start, dt = t, (t_end - t) / n
        k, need_first, switches = 1, True, 0
        while k <= n:
            target = t_end if k == n else t_start + k * dt
            h = target - t
            if h <= 1e-14 * max(1.0, abs(target)):
                k += 1
                continue
            mode = istate[MODE]
            if need_first:
                istate[N_RHS] += begin(rhs, p, t, y, mode, work, 0)
                need_first = False
            _, evals = step(rhs, p, t, y, h, mode, stage_A, stage_b, work, 0)
            istate[N_RHS] += evals
            dense(y, h, work, 0)
            u, mask, held = -1.0, 0, -1
            if locate and A_s.shape[0] > 0:
                u, mask, held = earliest_exit(work, A_s, b_s, relevance, mode, coef)
            if mask != 0:
                h, held = redo(rhs, p, t, y, u * h, h, surfaces, mask, state,
                               (stage_A, stage_b)), -1
            if h > 0.0:  # (a grazing restart takes no step)
                if locate:
                    track_contact(work, A_s, b_s, contact, fstate, coef, held)
                write_samples(work, t, h, opts, istate, sample_t, sample_y)
                accept(y, h, h, work, istate, 0)
                istate[N_STEPS] += 1
                if out_of_bounds(y, opts[BOUND]):
                    return DIVERGED
            if mask != 0:
                t = t + h
                cross(mask, y, surfaces, istate)
                need_first, switches = True, switches + 1
                if switches > opts[MAX_SWITCHES]:
                    return stopped_at_switch(fstate, t, fstate[H])
                continue
            t, k = target, k + 1
            if not locate and A_s.shape[0] > 0:  # plain scheme: the mode is the state's
                plain_mode_update(y, A_s, b_s, contact, istate)
                track_contact_at(y, A_s, b_s, contact, fstate)
        return OK

    return advance
