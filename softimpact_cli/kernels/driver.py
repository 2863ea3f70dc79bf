"""The integration loops every method shares: one adaptive, one on a fixed grid.

A method is a ``Stepper``: a named tuple of jitted functions, built once in Python by its
module (``STEPPER``) and passed to the kernels like any argument (numba specialises each
loop on the tuple's types, so the calls are static and inlined like direct ones; built
inside jitted code, the tuple would embed object addresses and defeat the disk cache).
Every kernel integrates through ``advance(m, ...)``, which runs ``m.loop``:

* ``loop``: ``adaptive`` or ``fixed`` below.

* ``variant(istate)``: which of its steps the method takes now (``auto``: 0 explicit,
  1 stiff; a single method: 0); every hook below receives it.
* ``begin(jac, rhs, p, t, y, mode, work, variant)``: what a step needs at its start
  (f, and for Rodas4 the Jacobian; ``jac`` is the stepper's Jacobian or None); returns
  the right-hand side evaluations used.
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
* ``accepted(y, h, h_next, work, istate, variant)``: after an accepted step, before the
  state moves on; True asks for a change of method (``auto``'s stiffness tests).
* ``finish(work, istate, variant)``: bookkeeping once the state moved on (FSAL copies,
  counters); True when the next step needs ``begin`` again.
* ``change_method(istate, mode)``, ``enter_mode(istate)``: ``auto``'s method state (True
  from ``enter_mode`` when the new mode changes the method).
* ``jac``: the system's Jacobian function, or None.

Every loop integrates ``y`` in place from ``t`` to exactly ``t_end`` (``surfaces``: the
switching surfaces ``(A, b, relevance, contact)``; ``state``: ``(istate, fstate, work)``
from ``orbit.new_state``; ``samples``: ``(sample_t, sample_y)``) and returns a status.
The mode is frozen over a step; when an accepted step's dense output shows a watched
surface crossed (or grazed), the step is redone up to the crossing, the mode switches
there and the method restarts (no stage is reused across a switch).
"""

from collections import namedtuple
from math import ceil

import numpy as np
from numba import njit

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
    YNEW,
    H,
)
from .switching import earliest_exit

Stepper = namedtuple("Stepper", ["loop", "variant", "begin", "step", "error", "controller", "dense",
                                 "refine", "accepted", "finish", "change_method", "enter_mode",
                                 "jac"])


@njit(cache=True)
def advance(m, rhs, p, y, t, t_end, surfaces, opts, state, samples):
    """Integrate ``y`` in place from ``t`` to exactly ``t_end`` with method ``m``; a status."""
    return m.loop(m, rhs, p, y, t, t_end, surfaces, opts, state, samples)


# ---------------------------------------------------------------------------------------
# what single methods leave out


@njit(cache=True)
def single(istate):
    return 0


@njit(cache=True)
def no_refinement(rhs, p, t, y, h, h_full, mode, surface, work, variant):
    return h, 0


@njit(cache=True)
def no_test(y, h, h_next, work, istate, variant):
    return False


@njit(cache=True)
def no_change(istate, mode):
    pass


@njit(cache=True)
def same_method(istate):
    return False


# ---------------------------------------------------------------------------------------
# pieces of the loops


@njit(cache=True)
def stage_surfaces(A_s, b_s, locate):
    """The surfaces stages read their mode from: none when switches are located."""
    if locate:
        return A_s[:0], b_s[:0]
    return A_s, b_s


@njit(cache=True)
def cross(m, mask, y, surfaces, istate):
    """Cross the surfaces in ``mask`` at ``y`` (``common.apply_switch``); the new mode may
    change the method."""
    A_s, b_s, relevance, contact = surfaces
    apply_switch(mask, y, A_s, b_s, relevance, contact, istate)
    m.enter_mode(istate)


@njit(cache=True)
def redo_to_crossing(m, rhs, p, t, y, h, h_full, surfaces, mask, state):
    """Redo the step up to the crossing (fraction found on the dense output), in the same
    frozen mode, refined by the method if it can; returns the step length, or -1 when the
    shorter step broke down (only on breakdown: it is shorter than an accepted one)."""
    A_s, b_s, _, _ = surfaces
    istate, _, work = state
    variant, mode = m.variant(istate), istate[MODE]
    ok, evals = m.step(rhs, p, t, y, h, mode, A_s[:0], b_s[:0], work, variant)
    istate[N_RHS] += evals
    if not ok:
        return -1.0
    m.dense(y, h, work, variant)
    i = 0
    while not (mask >> i) & 1:
        i += 1
    h, evals = m.refine(rhs, p, t, y, h, h_full, mode, (A_s[i], b_s[i]), work, variant)
    istate[N_RHS] += evals
    return h


@njit(cache=True)
def accept(m, y, t, h, h_next, surfaces, opts, state, samples, coef):
    """Take the step [t, t + h]: contact maximum, samples, the state moves on.

    Returns (whether the method asks to change, whether the next step needs ``begin``).
    """
    istate, fstate, work = state
    variant = m.variant(istate)
    if opts[LOCATE] != 0.0:
        track_contact(work, surfaces[0], surfaces[1], surfaces[3], fstate, coef)
    write_samples(work, t, h, opts, istate, samples[0], samples[1])
    change = m.accepted(y, h, h_next, work, istate, variant)
    for i in range(y.shape[0]):
        y[i] = work[YNEW, i]
    need_first = m.finish(work, istate, variant)
    istate[N_STEPS] += 1
    return change, need_first


@njit(cache=True)
def plain_update(m, y, mode, surfaces, fstate, istate):
    """Plain scheme: the mode is the state's; True when that changed the method."""
    A_s, b_s, _, contact = surfaces
    plain_mode_update(y, A_s, b_s, contact, istate)
    track_contact_at(y, A_s, b_s, contact, fstate)
    return istate[MODE] != mode and m.enter_mode(istate)


@njit(cache=True)
def try_step(m, rhs, p, t, y, h, stage, opts, istate, work):
    """Attempt a step of size h; returns (ok, its error norm)."""
    variant = m.variant(istate)
    ok, evals = m.step(rhs, p, t, y, h, istate[MODE], stage[0], stage[1], work, variant)
    istate[N_RHS] += evals
    err = m.error(y, h, work, opts, variant) if ok else np.inf
    return ok, err


# ---------------------------------------------------------------------------------------
# the adaptive loop


@njit(cache=True)
def adaptive(m, rhs, p, y, t, t_end, surfaces, opts, state, samples):
    """Integrate ``y`` in place from ``t`` to exactly ``t_end`` with stepper ``m``."""
    istate, fstate, work = state
    locate = opts[LOCATE] != 0.0
    stage = stage_surfaces(surfaces[0], surfaces[1], locate)
    coef = np.empty(5)
    h_floor, h = first_step(t, t_end, opts, fstate)
    need_first, rejected, steps, switches = True, False, 0, 0
    while t_end - t > 1e-14 * max(1.0, abs(t_end)):
        mode = istate[MODE]
        if need_first:
            istate[N_RHS] += m.begin(m.jac, rhs, p, t, y, mode, work, m.variant(istate))
            need_first = False
        h = min(h, opts[H_MAX])
        h_step, truncated = landing(h, t, t_end)
        ok, err = try_step(m, rhs, p, t, y, h_step, stage, opts, istate, work)
        c = m.controller(m.variant(istate))
        if rejects(ok, err):
            istate[N_REJECTED] += 1
            rejected, h = True, h_step * reject_factor(ok, err, c)
            if h < h_floor:
                fstate[H] = h
                return STEP_UNDERFLOW
            continue
        h_next, rejected = next_step(err, c, h_step, h, rejected, truncated), False
        m.dense(y, h_step, work, m.variant(istate))
        u, mask = -1.0, 0
        if locate and surfaces[0].shape[0] > 0:
            u, mask = earliest_exit(work, surfaces[0], surfaces[1], surfaces[2], mode, coef)
        if mask != 0:  # redo the step up to the crossing; the controller's proposal stands
            h_full, h_step, h_next, truncated = h_step, u * h_step, h, False
            if h_step > 0.0:
                h_step = redo_to_crossing(m, rhs, p, t, y, h_step, h_full, surfaces, mask, state)
                if h_step < 0.0:
                    fstate[H] = u * h_full
                    return STEP_UNDERFLOW
        if h_step > 0.0:  # (a grazing restart, leaving right at the start, takes no step)
            change, need_first = accept(m, y, t, h_step, h_next, surfaces, opts, state, samples,
                                        coef)
            t = t_end if truncated else t + h_step
            steps += 1
            if out_of_bounds(y, opts[BOUND]):
                fstate[H] = h_next
                return DIVERGED
            if change:
                m.change_method(istate, mode)
                need_first = True
            if not locate and surfaces[0].shape[0] > 0:
                need_first = plain_update(m, y, mode, surfaces, fstate, istate) or need_first
        if mask != 0:
            cross(m, mask, y, surfaces, istate)
            need_first, switches = True, switches + 1
            if switches > opts[MAX_SWITCHES]:
                return TOO_MANY_SWITCHES
        h = h_next
        if steps > opts[MAX_STEPS]:
            fstate[H] = h
            return STEP_BUDGET
    fstate[H] = h
    return OK


# ---------------------------------------------------------------------------------------
# the fixed-step loop


@njit(cache=True)
def fixed(m, rhs, p, y, t, t_end, surfaces, opts, state, samples):
    """Integrate ``y`` in place from ``t`` to exactly ``t_end`` on the grid ``t + k (t_end -
    t) / n``, ``n`` the smallest count whose step does not exceed ``opts[H_FIXED]``; a
    located switch inserts a step up to it and the grid goes on from there."""
    istate, fstate, work = state
    locate = opts[LOCATE] != 0.0
    stage = stage_surfaces(surfaces[0], surfaces[1], locate)
    coef = np.empty(5)
    t_start = t
    n = max(1, int(ceil((t_end - t_start) / opts[H_FIXED] - 1e-9)))
    dt = (t_end - t_start) / n
    k, need_first, switches = 1, True, 0
    while k <= n:
        target = t_end if k == n else t_start + k * dt
        h = target - t
        if h <= 1e-14 * max(1.0, abs(target)):
            k += 1
            continue
        mode = istate[MODE]
        if need_first:
            istate[N_RHS] += m.begin(m.jac, rhs, p, t, y, mode, work, 0)
            need_first = False
        _, evals = m.step(rhs, p, t, y, h, mode, stage[0], stage[1], work, 0)
        istate[N_RHS] += evals
        m.dense(y, h, work, 0)
        u, mask = -1.0, 0
        if locate and surfaces[0].shape[0] > 0:
            u, mask = earliest_exit(work, surfaces[0], surfaces[1], surfaces[2], mode, coef)
        if mask != 0:
            h_full, h = h, u * h
            if h > 0.0:  # (a grazing restart, leaving right at the start, takes no step)
                h = redo_to_crossing(m, rhs, p, t, y, h, h_full, surfaces, mask, state)
                accept(m, y, t, h, h, surfaces, opts, state, samples, coef)
                if out_of_bounds(y, opts[BOUND]):
                    return DIVERGED
                t = t + h
            cross(m, mask, y, surfaces, istate)
            need_first, switches = True, switches + 1
            if switches > opts[MAX_SWITCHES]:
                return TOO_MANY_SWITCHES
            continue
        accept(m, y, t, h, h, surfaces, opts, state, samples, coef)
        if out_of_bounds(y, opts[BOUND]):
            return DIVERGED
        t = target
        k += 1
        if not locate and surfaces[0].shape[0] > 0:
            plain_update(m, y, mode, surfaces, fstate, istate)
    return OK
