"""Linear special case (k2 = 0): the steady state is the textbook particular solution.

x'' + c x' + k1 x = F sin(w t) has the periodic solution x = F Im(H e^{i w t}) with
H = 1 / (k1 - w^2 + i c w): amplitude F |H| = F / sqrt((k1 - w^2)^2 + (c w)^2), and at
every section t = n T the state is (F Im H, F w Re H).
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.engine import classify_state, record_trajectory
from softimpact_cli.kernels.codes import CONVERGED, OK

from .helpers import problem

C, K1, F = 0.05, 1.0, 1.0


def linear_problem(w):
    return problem("duffing", 1, dict(c=C, k1=K1, k2=0.0, F=F, w=w), method="dopri5",
                   rtol=1e-10, atol=1e-12, convergence_tol=1e-11, max_periods=5000,
                   max_orbit_period=4)


def amplitude(w):
    return F / np.sqrt((K1 - w**2) ** 2 + (C * w) ** 2)


@pytest.fixture(scope="module", params=[1.3, 0.8])
def steady(request):
    w = request.param
    pr = linear_problem(w)
    cl = classify_state(pr, [0.0, 0.0])
    return w, pr, cl


def test_converges_to_a_period_one_orbit(steady):
    w, pr, cl = steady
    assert cl.status == CONVERGED, cl
    assert cl.period == 1
    # the transient decays like exp(-c t / 2): it cannot converge to 1e-11 in a few periods
    assert cl.periods_used > 50


def test_section_point_is_the_particular_solution(steady):
    w, pr, cl = steady
    H = 1.0 / (K1 - w**2 + 1j * C * w)
    x, v = cl.orbit[0]
    np.testing.assert_allclose([x, v], [F * H.imag, F * w * H.real], rtol=0,
                               atol=1e-8 * F * abs(H))


def test_amplitude_from_the_section_point(steady):
    w, pr, cl = steady
    x, v = cl.orbit[0]
    amp = np.hypot(x, v / w)
    assert abs(amp / amplitude(w) - 1.0) < 1e-7, (amp, amplitude(w))


def test_amplitude_from_dense_sampling(steady):
    """max |x| over one period of the recorded dense output, refined by a parabola
    through the largest sample and its neighbours (error ~ (2 pi / n)^4)."""
    w, pr, cl = steady
    n = 2048
    tr = record_trajectory(pr, cl.orbit[0], 0.0, 1, n)
    assert tr.status == OK
    x = tr.y[:, 0]
    assert x.size == n + 1 and np.all(np.isfinite(x))
    np.testing.assert_allclose(tr.t, np.arange(n + 1) * pr.period / n, rtol=0, atol=1e-12)
    a = np.abs(x[:-1])  # periodic: drop the repeated end point
    k = int(np.argmax(a))
    ym, y0, yp = a[k - 1], a[k], a[(k + 1) % n]
    peak = y0 + 0.125 * (yp - ym) ** 2 / (2 * y0 - ym - yp)
    assert abs(peak / amplitude(w) - 1.0) < 1e-7, (peak, amplitude(w), y0)
    # and the whole sampled curve is the particular solution
    H = 1.0 / (K1 - w**2 + 1j * C * w)
    exact = F * np.imag(H * np.exp(1j * w * tr.t))
    assert np.max(np.abs(x - exact)) < 1e-8 * amplitude(w)
    # the section after one period is the start again
    np.testing.assert_allclose(tr.section_y[1], cl.orbit[0], rtol=0, atol=1e-9)
