"""Bookkeeping every method shares after a step: contact tracking, switches, divergence."""

from math import isfinite

from numba import njit

from .layout import MAX_G, MODE, N_CONTACTS, N_SWITCHES
from .switching import mode_of, poly, poly_max, surface_polynomial, surface_value, switch_mode


@njit(cache=True, inline="always")
def track_contact(work, A, b, contacts, fstate, coef, held):
    """Raise the running max of the contact functions (the surfaces in the bit mask
    ``contacts``) with this step's dense output (``coef`` already holds surface ``held``'s
    polynomial)."""
    rest, i = contacts, 0
    while rest != 0:
        if rest & 1:
            if held != i:
                surface_polynomial(work, A, b, i, coef)
                held = i
            raise_running_max(coef, fstate)
        rest >>= 1
        i += 1


@njit(cache=True, inline="always")
def raise_running_max(coef, fstate):
    """``fstate[MAX_G] = max(fstate[MAX_G], max of the polynomial coef on [0, 1])``."""
    # The exact max needs the critical points (root finding); most steps need less, with
    # the same running max bit for bit. On [0, 1], c_k u^k <= max(c_k, 0): a step that
    # cannot raise the max is skipped. |g'(u) - c1| <= 2|c2| + 3|c3| + 4|c4|: where that
    # is below |c1|, g is monotone, has no critical point, and poly_max is its end max.
    if (coef[0] + max(coef[1], 0.0) + max(coef[2], 0.0) + max(coef[3], 0.0)
            + max(coef[4], 0.0)) <= fstate[MAX_G]:
        return
    if abs(coef[1]) > 2.0 * abs(coef[2]) + 3.0 * abs(coef[3]) + 4.0 * abs(coef[4]):
        g = max(poly(coef, 0.0), poly(coef, 1.0))
    else:
        g = poly_max(coef, 1.0)
    if g > fstate[MAX_G]:
        fstate[MAX_G] = g


@njit(cache=True)
def track_contact_at(y, A, b, contacts, fstate):
    """Plain scheme: the contact functions are only known at step ends."""
    rest, i = contacts, 0
    while rest != 0:
        if rest & 1:
            g = surface_value(A, b, i, y)
            if g > fstate[MAX_G]:
                fstate[MAX_G] = g
        rest >>= 1
        i += 1


@njit(cache=True, inline="always")
def onsets(contacts, old, new):
    """How many contact surfaces (bit mask ``contacts``) engage from mode ``old`` to
    ``new``."""
    rest, count = contacts & new & ~old, 0
    while rest != 0:
        count += rest & 1
        rest >>= 1
    return count


@njit(cache=True)
def apply_switch(mask, y, A, b, relevance, contacts, istate):
    """Flip the crossed surfaces' bits; count switches and contact onsets (``contacts``:
    the bit mask of the contact surfaces)."""
    old = istate[MODE]
    new = switch_mode(old, mask, y, A, b, relevance)
    istate[MODE] = new
    istate[N_SWITCHES] += 1
    istate[N_CONTACTS] += onsets(contacts, old, new)


@njit(cache=True)
def plain_mode_update(y, A, b, contacts, istate):
    """Plain scheme: the mode is whatever the state says; count contact onsets."""
    old = istate[MODE]
    new = mode_of(y, A, b)
    if new != old:
        istate[N_SWITCHES] += 1
        istate[N_CONTACTS] += onsets(contacts, old, new)
    istate[MODE] = new


@njit(cache=True, inline="always")
def out_of_bounds(y, bound):
    for i in range(y.shape[0]):
        if not isfinite(y[i]) or abs(y[i]) > bound:
            return True
    return False
