"""Step-size control of the adaptive driver: the first step, landing on the end time, and
the elementary controller ``h_new = h * clip(safety * err^(-1/order))``.

A method declares its constants as a ``Controller`` (``order`` of the error estimate's
exponent, ``safety``, the factor bounds, the factor after a singular step and whether it
forbids growth right after a rejection); the functions here apply them.
"""

from collections import namedtuple
from math import isfinite

from numba import njit

from .layout import H_MAX, H

H_FLOOR = 1e-13  # smallest step, relative to the interval being advanced

Controller = namedtuple(
    "Controller", ["order", "safety", "fac_min", "fac_max", "singular_fac", "calm_after_reject"])


@njit(cache=True, inline="always")
def first_step(t, t_end, opts, fstate):
    """(the step floor, the first proposal): the step carried over from the last call, else
    1 % of the interval (at most the largest step)."""
    span = t_end - t
    h = fstate[H]
    if h <= 0.0:
        h = min(opts[H_MAX], 0.01 * span)
    return H_FLOOR * max(span, 1e-300), h


@njit(cache=True, inline="always")
def landing(h, h_max, t, t_end):
    """(the proposal capped at h_max, the step to take, whether it lands on t_end): a
    step within 0.01 % of the end time is stretched or shortened onto it, so the section
    times are hit exactly."""
    h = min(h, h_max)
    if t + 1.0001 * h >= t_end:
        return h, t_end - t, True
    return h, h, False


@njit(cache=True, inline="always")
def rejects(ok, err):
    """A step is refused when its linear algebra failed or its error is not below 1."""
    return not ok or not isfinite(err) or err > 1.0


@njit(cache=True, inline="always")
def reject_factor(ok, err, c):
    """Shrink factor after a refused step (``c`` a Controller)."""
    if not ok:
        return c.singular_fac
    if not isfinite(err):
        return c.fac_min
    return max(c.fac_min, c.safety * err ** (-1.0 / c.order))


@njit(cache=True, inline="always")
def accept_factor(err, c):
    """Growth factor after an accepted step."""
    if err == 0.0:
        return c.fac_max
    return min(c.fac_max, max(c.fac_min, c.safety * err ** (-1.0 / c.order)))


@njit(cache=True, inline="always")
def next_step(err, c, h_step, h, rejected, truncated):
    """The step proposed after an accepted step ``h_step`` (``h`` was proposed before it)."""
    h_next = h_step * accept_factor(err, c)
    if rejected and c.calm_after_reject:
        h_next = min(h_next, h_step)  # no growth right after a rejection
    if truncated:
        h_next = max(h_next, h)  # landing on t_end says nothing against the old step
    return h_next
