"""A stiff stop beyond fixed-step RK4's stability is reported as DIVERGED, not raised.

k_c = 1e6, c_c = 1e3: in contact the relative coordinate has eigenvalues
lambda = -c_c +- sqrt(c_c^2 - 2 k_c) = -1000 +- 1000i, and RK4 at T/1440 (h = 3.4e-3)
has h*lambda = -3.4 +- 3.4i, far outside its stability region (|R(h lambda)| >> 1).
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.engine import classify_state
from softimpact_cli.kernels import rk4
from softimpact_cli.kernels.codes import CONVERGED, DIVERGED, STATUS_TABLE, outcome

from .helpers import DUFFING_PAIR, problem

STIFF = dict(DUFFING_PAIR, k_c=1e6, c_c=1e3)  # d = 1, phi = pi
START = [2.0, 0.0, -2.0, 0.0]  # compressed by 3: in contact from the start


def rk4_amplification(z):
    return abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)


def test_the_step_is_really_unstable():
    pr = problem("duffing", 2, STIFF)
    h = pr.period / 1440
    lam = -STIFF["c_c"] + np.sqrt(complex(STIFF["c_c"] ** 2 - 2 * STIFF["k_c"]))
    assert rk4_amplification(h * lam) > 10.0
    assert rk4.ORDER == 4


@pytest.mark.parametrize("locate", [True, False])
@pytest.mark.parametrize("start", [START, [0.0, 2.0, 0.0, -2.0]])
def test_rk4_1440_reports_diverged(locate, start):
    pr = problem("duffing", 2, STIFF, method="rk4", steps_per_period=1440,
                 locate_switches=locate)
    cl = classify_state(pr, start)  # must return, not raise
    assert cl.status == DIVERGED, (cl.status, cl.counters, cl.periods_used)
    assert cl.outcome == "diverged" == outcome(DIVERGED)
    assert "steps_per_period" in STATUS_TABLE[DIVERGED][1]  # the message says what to change
    assert cl.period == 0 and cl.orbit.shape[0] == 0
    assert cl.periods_used <= 3  # blows up at the first contacts
    assert cl.counters["contacts"] >= 1


def test_stable_integrators_agree_on_the_stiff_case():
    """The same problem is fine for the adaptive dopri5 and for located RK4 at a step 10x
    finer (h lambda = 0.34 + 0.34i): both converge to the same period-1 impacting orbit."""
    a = classify_state(problem("duffing", 2, STIFF, method="dopri5"), START)
    b = classify_state(problem("duffing", 2, STIFF, method="rk4", steps_per_period=14400),
                       START)
    assert a.status == b.status == CONVERGED
    assert a.period == b.period == 1
    assert a.impacting and b.impacting
    np.testing.assert_allclose(a.orbit, b.orbit, rtol=0, atol=1e-3)
