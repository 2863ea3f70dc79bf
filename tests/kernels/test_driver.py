"""The integration loops (kernels/driver.py): a method is a set of hooks.

The method here, Bogacki-Shampine 3(2) with a cubic Hermite dense output, is written in
this file only, as a user would add one: it runs through the package's adaptive loop,
with step control, switch location and every counter, and gets its order, its accuracy
through contacts and its bookkeeping right.
"""

from __future__ import annotations

from math import sqrt

import numpy as np
from numba import njit

from softimpact_cli.kernels import dopri5, driver, layout, orbit
from softimpact_cli.kernels.codes import OK, STEP_UNDERFLOW
from softimpact_cli.kernels.control import Controller
from softimpact_cli.kernels.dense import hermite_coefficients
from softimpact_cli.kernels.switching import mode_of

from .helpers import DUFFING_PAIR, fit_slope, problem, stable_identity

K0, YTMP, YNEW = layout.K0, layout.YTMP, layout.YNEW
C = np.array([0.0, 0.5, 0.75, 1.0])
A = np.array([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.75, 0.0], [2 / 9, 1 / 3, 4 / 9]])
E = np.array([2 / 9 - 7 / 24, 1 / 3 - 1 / 4, 4 / 9 - 1 / 3, -1 / 8])  # B - B_hat


@njit(cache=True)
def bs3_begin(rhs, p, t, y, mode, work, variant):
    rhs(t, y, p, mode, work[K0])
    return 1


@njit(cache=True)
def bs3_step(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant):
    """Stages 2..4; the 4th is f at the new state (FSAL), its state the solution."""
    for s in range(1, 4):
        for i in range(y.shape[0]):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * work[K0 + j, i]
            work[YTMP, i] = y[i] + h * acc
        m = mode if stage_A.shape[0] == 0 else mode_of(work[YTMP], stage_A, stage_b)
        rhs(t + C[s] * h, work[YTMP], p, m, work[K0 + s])
    for i in range(y.shape[0]):
        work[YNEW, i] = work[YTMP, i]
    return True, 3


@njit(cache=True)
def bs3_error(y, h, work, opts, variant):
    acc = 0.0
    for i in range(y.shape[0]):
        e = 0.0
        for j in range(4):
            e += E[j] * work[K0 + j, i]
        scale = opts[layout.ATOL] + opts[layout.RTOL] * max(abs(y[i]), abs(work[YNEW, i]))
        acc += (h * e / scale) ** 2
    return sqrt(acc / y.shape[0])


@njit(cache=True)
def bs3_controller(variant):
    return Controller(3, 0.9, 0.2, 5.0, 0.5, False)


@njit(cache=True)
def bs3_dense(y, h, work, variant):
    hermite_coefficients(work, y, work[YNEW], work[K0], work[K0 + 3], h)


@njit(cache=True)
def bs3_accept(y, h, h_next, work, istate, variant):
    for i in range(y.shape[0]):
        y[i] = work[YNEW, i]
        work[K0, i] = work[K0 + 3, i]  # first same as last
    return False, False


@njit(cache=True)
def always_singular(rhs, p, t, y, h, mode, stage_A, stage_b, work, variant):
    return False, 0


stable_identity(repr((C, A, E)), bs3_begin, bs3_step, bs3_error, bs3_controller, bs3_dense,
                bs3_accept, always_singular)


def bs3_loop(name, step):
    return driver.adaptive_loop(f"tests_{name}", bs3_begin, step, bs3_error, bs3_controller,
                                bs3_dense, driver.no_refinement, bs3_accept, driver.no_change,
                                driver.same_method)


BS3 = bs3_loop("bs3", bs3_step)
FAILING = bs3_loop("bs3_failing", always_singular)

LINEAR = dict(c=0.05, k1=1.0, k2=0.0, F=1.0, w=1.3)


def integrate(advance, pr, y0, t1, opts):
    y = np.array(y0, dtype=float)
    surfaces = pr.kernel_args()
    state = orbit.new_state(y, surfaces[0], surfaces[1])
    status = advance(pr.system.rhs, pr.params, y, 0.0, t1, surfaces, opts, state,
                     orbit.no_samples(y.size))
    return int(status), y, state[0]


def steady_state(t):
    """The linear oscillator's periodic solution x = F Im(H e^{iwt}) and its velocity."""
    w = LINEAR["w"]
    H = 1.0 / (LINEAR["k1"] - w**2 + 1j * LINEAR["c"] * w)
    z = LINEAR["F"] * H * np.exp(1j * w * t)
    return np.array([z.imag, (1j * w * z).imag])


def test_a_method_written_outside_the_package_runs_through_the_adaptive_loop():
    pr = problem("duffing", 1, LINEAR, rtol=1e-9, atol=1e-12)
    t1 = 5 * pr.period
    status, y, istate = integrate(BS3, pr, steady_state(0.0), t1, pr.options())
    assert status == OK
    assert np.max(np.abs(y - steady_state(t1))) < 1e-7
    steps, rejected = istate[layout.N_STEPS], istate[layout.N_REJECTED]
    assert steps > 100  # third order at 1e-9: many steps
    assert istate[layout.N_RHS] == 1 + 3 * (steps + rejected)  # FSAL: three per attempt


def test_its_order_on_a_fixed_grid():
    pr = problem("duffing", 1, LINEAR, rtol=1.0, atol=1.0)  # nothing rejected
    t1 = 2 * pr.period
    errors, steps = [], np.array([40, 80, 160, 320])
    for n in steps:
        opts = pr.options()
        opts[layout.H_MAX] = pr.period / n
        status, y, istate = integrate(BS3, pr, steady_state(0.0), t1, opts)
        assert status == OK and istate[layout.N_REJECTED] == 0
        errors.append(np.max(np.abs(y - steady_state(t1))))
    slope = fit_slope(1.0 / steps, errors)
    assert 2.8 < slope < 3.3, (slope, errors)


def test_it_locates_contacts_like_dopri5():
    """Through the soft stop (d = 1, k_c = 8, c_c = 10) for 10 periods: the same contacts
    and the same state as dopri5 at a tight tolerance."""
    pr = problem("duffing", 2, DUFFING_PAIR, rtol=1e-10, atol=1e-12)
    y0 = [2.0, 0.0, -2.0, 0.0]
    t1 = 10 * pr.period
    status, y, istate = integrate(BS3, pr, y0, t1, pr.options())
    tight = pr.with_integrator(rtol=1e-12, atol=1e-14)
    status_d, y_d, istate_d = integrate(dopri5.advance, tight, y0, t1, tight.options())
    assert status == status_d == OK
    assert istate[layout.N_CONTACTS] == istate_d[layout.N_CONTACTS] >= 5
    assert np.max(np.abs(y - y_d)) < 1e-6


def test_a_step_that_breaks_down_halves_until_the_floor():
    """A step whose linear algebra fails is refused and halved (the singular factor); the
    loop ends with STEP_UNDERFLOW once the step is below 1e-13 of the interval."""
    pr = problem("duffing", 1, LINEAR)
    opts = pr.options()
    status, _, istate = integrate(FAILING, pr, [1.0, 0.0], pr.period, opts)
    assert status == STEP_UNDERFLOW
    h0 = min(opts[layout.H_MAX], 0.01 * pr.period)
    expected = int(np.ceil(np.log2(h0 / (1e-13 * pr.period))))
    assert istate[layout.N_REJECTED] == expected and istate[layout.N_STEPS] == 0
