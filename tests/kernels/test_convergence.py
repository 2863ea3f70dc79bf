"""Observed convergence orders: slope of log(error) against log(step).

The adaptive dopri5 kernel is run as a fixed-step method (rtol = atol = 1: nothing is
rejected; H_MAX = T/N). References are scipy DOP853 at rtol 1e-13, restarted at every
switch (tests/naive.py), whose own error is ~2e-14 (checked against rtol 3e-14); the
kernels reach a roundoff floor of ~1e-12 after ~10^4 steps, and every fitted range keeps
the errors well above that.

Smooth problem: one Duffing body. With contacts: the Duffing pair at d = 1, phi = pi,
k_c = 8, c_c = 10 from (2, 0, -2, 0): starts compressed, separates, touches twice more in
3 periods. The paper law's force jumps at the onset of contact (c_c (v1 - v2) != 0), so a
step that straddles a switch loses the order unless the switch is located.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact_cli.kernels import layout
from softimpact_cli.kernels.codes import OK
from tests import naive

from .helpers import DUFFING_BODY, DUFFING_PAIR, dopri5_fixed, fit_slope, problem, rk4_fixed

PERIODS = 3


def steps_per_period(lo, hi, n=16):
    return np.unique(np.round(np.geomspace(lo, hi, n)).astype(int))


@pytest.fixture(scope="module")
def smooth():
    pr = problem("duffing", 1, DUFFING_BODY)
    y0 = np.array([2.0, 0.0])
    T = pr.period
    ref = solve_ivp(lambda t, y: naive.duffing_body_rhs(t, y, DUFFING_BODY), (0.0, PERIODS * T),
                    y0, method="DOP853", rtol=1e-13, atol=1e-14).y[:, -1]
    return pr, y0, ref


@pytest.fixture(scope="module")
def impacting():
    pr = problem("duffing", 2, DUFFING_PAIR)
    y0 = np.array([2.0, 0.0, -2.0, 0.0])
    T = pr.period
    sol = naive.solve_model(naive.duffing_pair_model(DUFFING_PAIR), y0, (0.0, PERIODS * T),
                            rtol=1e-13, atol=1e-13)
    onsets = sum(1 for s, m in zip(sol.event_surface, sol.event_mode, strict=True)
                 if s == 0 and m & 1)
    assert onsets >= 2 and len(sol.event_t) >= 5, sol.event_t  # really an impacting case
    return pr, y0, sol.y_end, onsets


def errors(run, Ns, ref):
    out = []
    for N in Ns:
        status, y, istate, _ = run(N)
        assert status == OK
        assert istate[layout.N_REJECTED] == 0  # truly fixed-step
        out.append(np.max(np.abs(y - ref)))
    return np.array(out)


def test_rk4_order_on_a_smooth_trajectory(smooth):
    pr, y0, ref = smooth
    T = pr.period
    Ns = steps_per_period(20, 320, 9)
    err = errors(lambda N: rk4_fixed(pr, y0, 0.0, PERIODS * T, N), Ns, ref)
    slope = fit_slope(1.0 / Ns, err)
    print(f"rk4 smooth: slope {slope:.3f}, errors {err[0]:.2e}..{err[-1]:.2e}")
    assert err.min() > 1e-10
    assert 3.7 <= slope <= 4.3, f"rk4 smooth slope {slope:.3f}, errors {err}"


def test_dopri5_fixed_step_order_on_a_smooth_trajectory(smooth):
    pr, y0, ref = smooth
    T = pr.period
    Ns = steps_per_period(20, 160, 9)
    err = errors(lambda N: dopri5_fixed(pr, y0, 0.0, PERIODS * T, T / N), Ns, ref)
    slope = fit_slope(1.0 / Ns, err)
    print(f"dopri5 smooth: slope {slope:.3f}, errors {err[0]:.2e}..{err[-1]:.2e}")
    assert err.min() > 1e-10
    assert 4.6 <= slope <= 5.5, f"dopri5 smooth slope {slope:.3f}, errors {err}"
    # and the fixed-step driver takes the steps it is asked to take
    _, _, istate, _ = dopri5_fixed(pr, y0, 0.0, PERIODS * T, T / 40)
    assert abs(istate[layout.N_STEPS] - PERIODS * 40) <= 1


def test_dopri5_keeps_its_order_through_located_contacts(impacting):
    pr, y0, ref, onsets = impacting
    T = pr.period
    Ns = steps_per_period(64, 360)
    err = errors(lambda N: dopri5_fixed(pr, y0, 0.0, PERIODS * T, T / N, locate=True), Ns, ref)
    slope = fit_slope(1.0 / Ns, err)
    print(f"dopri5 located: slope {slope:.3f}, errors {err[0]:.2e}..{err[-1]:.2e}")
    assert err.min() > 3e-12  # above the reference's own error
    assert slope >= 4.5, f"dopri5 located slope {slope:.3f}, errors {err}"
    _, _, istate, _ = dopri5_fixed(pr, y0, 0.0, PERIODS * T, T / 200, locate=True)
    assert istate[layout.N_CONTACTS] == onsets


def test_rk4_keeps_its_order_through_located_contacts(impacting):
    pr, y0, ref, onsets = impacting
    T = pr.period
    Ns = steps_per_period(80, 640)
    err = errors(lambda N: rk4_fixed(pr, y0, 0.0, PERIODS * T, N, locate=True), Ns, ref)
    slope = fit_slope(1.0 / Ns, err)
    print(f"rk4 located: slope {slope:.3f}, errors {err[0]:.2e}..{err[-1]:.2e}")
    assert err.min() > 3e-12
    assert slope >= 3.7, f"rk4 located slope {slope:.3f}, errors {err}"


@pytest.mark.parametrize("method", ["dopri5", "rk4"])
def test_plain_scheme_loses_the_order_at_contacts(impacting, method):
    """Without location the error is first order at best, and erratic (it depends on
    where each switch falls in its step): fitted slopes measure ~0.3..1.4."""
    pr, y0, ref, _ = impacting
    T = pr.period
    Ns = steps_per_period(100, 1600)

    def run(N, locate):
        if method == "dopri5":
            return dopri5_fixed(pr, y0, 0.0, PERIODS * T, T / N, locate=locate)
        return rk4_fixed(pr, y0, 0.0, PERIODS * T, N, locate=locate)

    plain = errors(lambda N: run(N, False), Ns, ref)
    slope = fit_slope(1.0 / Ns, plain)
    print(f"{method} plain: slope {slope:.3f}, errors {plain[0]:.2e}..{plain[-1]:.2e}")
    assert slope <= 2.0, f"{method} plain slope {slope:.3f}, errors {plain}"
    # at the finest step the plain scheme is still far off; the located one is not
    located = errors(lambda N: run(N, True), Ns[-1:], ref)[0]
    assert plain[-1] > 1e-5 and located < 1e-10, (plain[-1], located)
