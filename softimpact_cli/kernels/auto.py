"""auto: Dormand-Prince while its step is accuracy bound, Rodas4 while it is stability bound.

A stop is stiff only while it is engaged, so stiffness belongs to a contact *mode*; free
flight stays non-stiff. ``advance`` therefore decides step by step and remembers per mode:

* **explicit** (``dopri5``'s steps, arithmetic identical to ``dopri5.advance``): after
  every ``TEST_EVERY``-th accepted step (every step once one looked stiff), Hairer's
  estimate ``h |lambda| ~ h ||k7 - k6|| / ||y7 - y6||`` from the two stages at ``t + h``
  (the test of ``dopri5.f``; Hairer & Wanner, *Solving ODEs II*, section IV.2). Above
  ``STIFF_EDGE`` = 3.25 (the stability region ends near -3.3 on the real axis) the
  controller is holding the step at the stability limit. With Hairer's counting
  (``STIFF_HITS`` such steps, forgotten after ``CALM_STEPS`` calm ones in a row) the
  method switches to Rodas4 and flags the mode.
* **stiff** (``rosenbrock``'s steps, Jacobian by differences, as ``rosenbrock.advance``):
  after every accepted step, an upper bound of the spectral radius of the step's
  Jacobian, ``rho <= ||J^16||_inf^(1/16)`` (Gelfand's formula, four rescaled squarings).
  When ``h_next rho < BACK`` for ``BACK_STEPS`` steps in a row, the explicit step would be
  stable with margin and cheaper (6 right-hand sides against ~12 and a factorisation):
  back to dopri5, the mode's flag cleared, and the next ``COOLDOWN`` tests are skipped
  (hysteresis: no ping-pong within a phase).
* **a mode switch** starts the new phase with the method its mode's flag names, so after
  the first stiff contact every later one begins with Rodas4 at once.

Counters (``layout``): ``N_STIFF_STEPS`` accepted Rodas4 steps (the explicit ones are
``N_STEPS`` minus these), ``N_METHOD_SWITCHES``. The running state (``AUTO_*``) lives in
``istate`` so that it carries across calls, one forcing period each.
"""

from math import exp, isfinite, log, sqrt

from numba import njit

from . import dopri5 as dp
from . import rosenbrock as ro
from .driver import adaptive_loop
from .layout import (
    AUTO_CALM,
    AUTO_COOLDOWN,
    AUTO_HITS,
    AUTO_STIFF,
    AUTO_STIFF_MODES,
    JAC,
    K0,
    MODE,
    N_METHOD_SWITCHES,
    N_STEPS,
    YNEW,
)
from .linalg import inf_norm, matmul_into

# traits of the method (kernels.method_traits): rtol/atol steer its steps; steps_per_period
# fixed steps per forcing period; the closed-form flow of piecewise-linear systems
HAS_TOLERANCE = True
FIXED_STEP = False
CLOSED_FORM = False

ORDER = 4  # the lower of the two methods' orders (dopri5 5, rodas4 4)
STIFF_EDGE = 3.25  # h |lambda| above which dopri5's step is stability bound (dopri5.f)
STIFF_HITS = 15  # dopri5.f's count of stability-bound steps before declaring stiffness
CALM_STEPS = 6  # ... forgotten after this many calm steps in a row
TEST_EVERY = 16  # test every 16th explicit step (cost ~1 %), every step once one hit
BACK = 1.0  # rodas4 -> dopri5 when h_next * rho_bound < BACK ...
BACK_STEPS = 4  # ... for this many accepted steps in a row (not on a transient's first steps)
COOLDOWN = 4  # tests skipped after a return to dopri5 (~ 64 explicit steps)
SQUARINGS = 4  # rho <= ||J^(2^SQUARINGS)||^(1/2^SQUARINGS)


# ---------------------------------------------------------------------------------------
# stiffness estimates


@njit(cache=True)
def explicit_stiffness(y, h, work):
    """Hairer's h |lambda| ~ h ||k7 - k6|| / ||y7 - y6|| of the dopri5 step just taken.

    ``y`` is the step's start; ``work`` holds its stages (rows K0..K0+6) and solution
    (YNEW). Stage 6's state is rebuilt from the stages (``dopri5.stages`` overwrote it).
    """
    num = 0.0
    den = 0.0
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(5):
            acc += dp.A[5, j] * work[K0 + j, i]
        dk = work[K0 + 6, i] - work[K0 + 5, i]
        dy = work[YNEW, i] - (y[i] + h * acc)
        num += dk * dk
        den += dy * dy
    if den > 0.0:
        return h * sqrt(num / den)
    return 0.0


@njit(cache=True)
def spectral_radius_bound(jac, a, b):
    """Upper bound ``||J^(2^k)||_inf^(1/2^k) >= rho(J)``, k = SQUARINGS (Gelfand).

    Each squaring is rescaled to norm 1 and the scale kept as a logarithm, so nothing
    overflows; ``a``, ``b`` are (dim, dim) scratch. Tight within (dim kappa)^(1/16) for a
    diagonalisable J with eigenvector condition number kappa.
    """
    n = jac.shape[0]
    norm = inf_norm(jac)
    if norm == 0.0 or not isfinite(norm):
        return norm
    log_c = log(norm)
    for i in range(n):
        for j in range(n):
            a[i, j] = jac[i, j] / norm
    for _ in range(SQUARINGS):
        matmul_into(a, a, b)
        m = inf_norm(b)
        if m == 0.0:
            return 0.0  # nilpotent
        log_c = 2.0 * log_c + log(m)
        for i in range(n):
            for j in range(n):
                a[i, j] = b[i, j] / m
    return exp(log_c / 2.0**SQUARINGS)


# ---------------------------------------------------------------------------------------
# the method's state machine


@njit(cache=True)
def explicit_says_stiff(y, h, work, istate):
    """Hairer's counting on the explicit step just taken; True: switch to the stiff method."""
    h_lambda = explicit_stiffness(y, h, work)
    if istate[AUTO_COOLDOWN] > 0:
        istate[AUTO_COOLDOWN] -= 1
        return False
    if h_lambda > STIFF_EDGE:
        istate[AUTO_CALM] = 0
        istate[AUTO_HITS] += 1
        return istate[AUTO_HITS] >= STIFF_HITS
    istate[AUTO_CALM] += 1
    if istate[AUTO_CALM] >= CALM_STEPS:
        istate[AUTO_HITS] = 0
    return False


@njit(cache=True)
def stiff_says_explicit(h_next, work, istate):
    """True when the explicit step h_next would have been stable BACK_STEPS times in a row.

    The bound reads the step's Jacobian (rows JAC..) and overwrites its LU factors."""
    dim = work.shape[1]
    rho = spectral_radius_bound(work[JAC:JAC + dim], work[JAC + dim:JAC + 2 * dim],
                                work[JAC + 2 * dim:JAC + 3 * dim])
    if h_next * rho < BACK:
        istate[AUTO_CALM] += 1
        return istate[AUTO_CALM] >= BACK_STEPS
    istate[AUTO_CALM] = 0
    return False


@njit(cache=True)
def switch_method(istate, mode):
    """Flip the method within a phase in ``mode``; the mode's flag follows. True: the
    next step begins afresh."""
    if istate[AUTO_STIFF] != 0:
        istate[AUTO_STIFF] = 0
        istate[AUTO_STIFF_MODES] &= ~(1 << mode)
        istate[AUTO_COOLDOWN] = COOLDOWN
    else:
        istate[AUTO_STIFF] = 1
        istate[AUTO_STIFF_MODES] |= 1 << mode
    istate[AUTO_HITS] = 0
    istate[AUTO_CALM] = 0
    istate[N_METHOD_SWITCHES] += 1
    return True  # the new method begins afresh


@njit(cache=True)
def enter_mode(istate):
    """A new phase: the method the mode's flag names. True when the method changed."""
    want = (istate[AUTO_STIFF_MODES] >> istate[MODE]) & 1
    istate[AUTO_HITS] = 0
    istate[AUTO_CALM] = 0
    istate[AUTO_COOLDOWN] = 0
    if want == istate[AUTO_STIFF]:
        return False
    istate[AUTO_STIFF] = want
    istate[N_METHOD_SWITCHES] += 1
    return True


# ---------------------------------------------------------------------------------------
# the hooks for the driver (see ``driver``): variant 0 takes dopri5's steps, 1 Rodas4's


@njit(cache=True, inline="always")
def begin(rhs, p, t, y, mode, work, variant):
    if variant:
        return ro.begin(rhs, p, t, y, mode, work, variant)
    return dp.begin(rhs, p, t, y, mode, work, variant)


@njit(cache=True, inline="always")
def step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant):
    if variant:
        return ro.step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant)
    return dp.step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant)


@njit(cache=True, inline="always")
def error(y, h, work, opts, variant):
    if variant:
        return ro.error(y, h, work, opts, variant)
    return dp.error(y, h, work, opts, variant)


@njit(cache=True, inline="always")
def controller(variant):
    if variant:
        return ro.controller(variant)
    return dp.controller(variant)


@njit(cache=True, inline="always")
def dense(y, h, work, variant):
    if variant:
        ro.dense(y, h, work, variant)
    else:
        dp.dense(y, h, work, variant)


@njit(cache=True, inline="always")
def refine(rhs, p, t, y, h, h_full, mode, surface, work, variant):
    if variant:
        return ro.refine_crossing(rhs, p, t, y, h, h_full, mode, surface, work, variant)
    return h, 0


@njit(cache=True, inline="always")
def accept(y, h, h_next, work, istate, variant):
    """The stiffness tests on the step just accepted (before ``y`` moves on), then the
    method's own acceptance."""
    if variant:
        change = stiff_says_explicit(h_next, work, istate)
        return change, ro.accept(y, h, h_next, work, istate, variant)[1]
    change = False
    if istate[AUTO_HITS] > 0 or istate[N_STEPS] % TEST_EVERY == 0:
        change = explicit_says_stiff(y, h, work, istate)
    return change, dp.accept(y, h, h_next, work, istate, variant)[1]


advance = adaptive_loop("auto", begin, step, error, controller, dense, refine, accept,
                        switch_method, enter_mode)
