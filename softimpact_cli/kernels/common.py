"""Bookkeeping every method shares after a step: contact tracking, switches, divergence."""

from math import isfinite

from numba import njit

from .layout import MAX_G, MODE, N_CONTACTS, N_SWITCHES
from .switching import mode_of, poly, poly_max, surface_polynomial, surface_value, switch_mode


@njit(cache=True, inline="always")
def track_contact(work, A, b, contact, fstate, coef, held):
    """Raise the running max of the contact function with this step's dense output
    (``coef`` already holds its polynomial when ``held`` is ``contact``)."""
    if contact < 0:
        return
    if held != contact:
        surface_polynomial(work, A, b, contact, coef)
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
def track_contact_at(y, A, b, contact, fstate):
    """Plain scheme: the contact function is only known at step ends."""
    if contact < 0:
        return
    g = surface_value(A, b, contact, y)
    if g > fstate[MAX_G]:
        fstate[MAX_G] = g


@njit(cache=True)
def apply_switch(mask, y, A, b, relevance, contact, istate):
    """Flip the crossed surfaces' bits; count switches and contact onsets."""
    old = istate[MODE]
    new = switch_mode(old, mask, y, A, b, relevance)
    istate[MODE] = new
    istate[N_SWITCHES] += 1
    if contact >= 0 and not (old >> contact) & 1 and (new >> contact) & 1:
        istate[N_CONTACTS] += 1


@njit(cache=True)
def plain_mode_update(y, A, b, contact, istate):
    """Plain scheme: the mode is whatever the state says; count contact onsets."""
    old = istate[MODE]
    new = mode_of(y, A, b)
    if new != old:
        istate[N_SWITCHES] += 1
        if contact >= 0 and not (old >> contact) & 1 and (new >> contact) & 1:
            istate[N_CONTACTS] += 1
    istate[MODE] = new


@njit(cache=True, inline="always")
def out_of_bounds(y, bound):
    for i in range(y.shape[0]):
        if not isfinite(y[i]) or abs(y[i]) > bound:
            return True
    return False
