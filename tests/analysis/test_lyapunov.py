"""Lyapunov exponents of the piecewise-smooth flow, against published values, an
independent Benettin computation (scipy), Floquet multipliers and finite differences."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact_cli.analysis.catalogue import sample_states
from softimpact_cli.analysis.engine import Problem, classify_state
from softimpact_cli.analysis.lyapunov import (
    floquet_exponents,
    lyapunov_spectrum,
    refine_periodic,
)
from softimpact_cli.analysis.lyapunov_scans import Averaging, catalogue_spectra
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.store.catalogues import build_catalogue
from softimpact_cli.systems import get_system

# Ueda's oscillator x'' + 0.05 x' + x^3 = 7.5 cos t (ours: sin t, a quarter period later:
# the same attractor, the same exponents).
UEDA = {"c": 0.05, "k1": 0.0, "k2": 1.0, "F": 7.5, "w": 1.0}
# Published: (0.0999, 0, -0.1499) for the autonomous 3-D form (the 0 is the time
# direction, which our 2-D non-autonomous count leaves out): J. C. Sprott, Chaos and
# Time-Series Analysis (Oxford 2001), pp. 182-183 and 429, after Y. Ueda, J. Stat. Phys.
# 20, 181 (1979); RK4 with step 0.001, four digits, no error bar given.
UEDA_PUBLISHED = (0.0999, -0.1499)
TIGHT = IntegratorSettings(method="dopri5", rtol=1e-10, atol=1e-12)
SHOOT = IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13)


@pytest.fixture(scope="module")
def ueda():
    return Problem(get_system("duffing", 1), UEDA, IntegratorSettings(method="dopri5",
                                                                      rtol=1e-9, atol=1e-11))


@pytest.fixture(scope="module")
def ueda_long(ueda):
    return lyapunov_spectrum(ueda, [2.5, 0.0], 0.0, periods=4000, transient=100,
                             segments=20)


def test_ueda_against_published(ueda_long):
    """Largest exponent within the averaging error of Sprott's 0.0999 (his four digits
    carry no error bar; ours is 3 standard errors of 20 segments of 200 periods, about
    0.006), the other within the same, and the pair sums to -c."""
    s = ueda_long
    assert s.ok and s.exponents[0] > 0.05  # chaotic
    for ours, err, published in zip(s.exponents, s.stderr, UEDA_PUBLISHED, strict=True):
        assert abs(ours - published) <= max(3.0 * err, 0.005), (ours, err, published)
    assert 0.001 < s.stderr[0] < 0.01


def test_ueda_sum_is_minus_damping(ueda_long):
    """Phase-space contraction: trace J = -c, so each segment's exponents sum to -c up to
    the integration error (not only on average)."""
    sums = ueda_long.segments.sum(axis=1)
    assert np.max(np.abs(sums + 0.05)) < 1e-8


def _scipy_benettin(values, y0, periods):
    """Independent Benettin: solve_ivp DOP853 on (x, v, Phi), QR once per period."""
    c, k1, k2, F, w = (values[k] for k in ("c", "k1", "k2", "F", "w"))

    def rhs(t, z):
        x, v = z[0], z[1]
        P = z[2:].reshape(2, 2)
        J = np.array([[0.0, 1.0], [-k1 - 3.0 * k2 * x * x, -c]])
        return np.concatenate([[v, F * np.sin(w * t) - c * v - k1 * x - k2 * x ** 3],
                               (J @ P).ravel()])

    T = 2 * np.pi / w
    z = np.concatenate([y0, np.eye(2).ravel()])
    logs = []
    for k in range(periods):
        sol = solve_ivp(rhs, (k * T, (k + 1) * T), z, method="DOP853", rtol=1e-12,
                        atol=1e-13)
        z = sol.y[:, -1].copy()
        q, r = np.linalg.qr(z[2:].reshape(2, 2))
        sign = np.sign(np.diag(r))
        z[2:] = (q * sign).ravel()
        logs.append(np.log(np.abs(np.diag(r))))
    return np.array(logs) / T


def test_ueda_against_scipy_benettin(ueda):
    """Period by period over 15 periods of the chaotic attractor (short enough that the
    two integrations, both at rtol 1e-12, stay on one trajectory: their difference grows
    like exp(lambda_1 t) from 1e-13), the finite-time exponents of both computations
    agree to 1e-6 (measured: 4e-8)."""
    y0 = np.array([2.5, 0.0])
    ref = _scipy_benettin(UEDA, y0, 15)
    ours = lyapunov_spectrum(Problem(ueda.system, UEDA, SHOOT), y0, 0.0, periods=15,
                             transient=0, segments=15)
    # ours are sorted by their mean, the reference in Gram-Schmidt order: the same here
    assert ref[:, 0].mean() > ref[:, 1].mean()
    assert np.max(np.abs(ours.segments - ref)) < 1e-6


@pytest.fixture(scope="module")
def duffing_body_catalogue():
    values = {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0, "w": 1.3}
    states = sample_states({"x": (-12, 12), "v": (-12, 12)}, 6, 20, seed=3)
    body = get_system("duffing", 1)
    return body, values, build_catalogue(body, values, IntegratorSettings(), states)


def test_catalogue_periodic_orbits_match_floquet(duffing_body_catalogue):
    """The two period-1 Duffing attractors: exponents = ln|mu| / T of the catalogue's
    multipliers (the variational monodromy of its Newton refinement) to 2e-4."""
    body, values, cat = duffing_body_catalogue
    assert [a.period for a in cat.attractors] == [1, 1]
    ds = catalogue_spectra(Problem(body, values, TIGHT), cat,
                           Averaging(periods=200, transient=20, segments=10))
    assert list(ds["solution"].values) == ["L1^1", "L1^2"]
    diff = np.abs(ds["exponent"].values - ds["floquet_exponent"].values)
    assert np.all(diff < 2e-4), diff
    # both attractors are stable: every exponent negative; each pair sums to -c
    assert np.all(ds["exponent"].values < 0)
    np.testing.assert_allclose(ds["exponent"].values.sum(axis=1), -0.05, atol=1e-8)


# An impacting period-1 orbit of figure 14(c) (Duffing pair, phi = 5.28, d = 10.5,
# k_c = 8, c_c = 10): one contact per period, max penetration ~0.25.
FIG14C = {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0, "w": 1.3, "d": 10.5, "phi": 5.28,
          "k_c": 8.0, "c_c": 10.0, "law": "paper"}
FIG14C_START = np.array([-9.7384, 0.5832, 1.3324, -1.7490])


@pytest.fixture(scope="module")
def impacting_orbit():
    pair = get_system("duffing", 2)
    tight = Problem(pair, FIG14C, SHOOT)
    cls = classify_state(tight, FIG14C_START, 0.0)
    assert cls.impacting and cls.period == 1 and cls.contacts == 1
    y, M, residual = refine_periodic(tight, cls.orbit[0], 0.0, 1)
    assert residual < 1e-9
    return pair, y, M


@pytest.mark.parametrize("saltation", [True, False])
def test_impacting_orbit_needs_saltation(impacting_orbit, saltation):
    """With saltation the exponents equal ln|mu| / T of the monodromy by central
    differences of the flow (switches located); without it they do not: the largest
    comes out positive (+0.079) on a stable orbit (-0.044)."""
    pair, y, M = impacting_orbit
    T = 2 * np.pi / FIG14C["w"]
    floquet = floquet_exponents(np.linalg.eigvals(M), 1, T)
    s = lyapunov_spectrum(Problem(pair, FIG14C, TIGHT), y, 0.0, periods=200, transient=20,
                          segments=10, saltation=saltation)
    assert s.ok and s.switches == 2 * 220  # onset and release every period
    # the sum is ln|det M| / T either way: det S = 1 for the paper's law
    assert abs(s.sum - floquet.sum()) < 1e-7
    if saltation:
        assert s.salted == s.switches
        # (-0.0440 twice: a complex pair, -0.0900, -1.4857): the strongly contracting
        # direction and the 3-volume converge fast; the three close exponents share their
        # finite-time error (a complex pair's two exponents oscillate period by period)
        np.testing.assert_allclose(s.exponents[3], floquet[3], atol=1e-6)
        np.testing.assert_allclose(s.exponents[:3].sum(), floquet[:3].sum(), atol=1e-6)
        np.testing.assert_allclose(s.exponents[:3], floquet[:3], atol=1e-3)
    else:
        assert s.salted == 0
        assert s.exponents[0] > 0.05 > -0.04 > floquet[0]
        assert np.max(np.abs(s.exponents - floquet)) > 0.1


# An impacting period-5 orbit of figure 14(a) (bilinear pair, phi = 1, d = 1.5, k_c = 8,
# c_c = 10): contacts and the bilinear springs' gaps (S = I there) every period.
FIG14A = {"c": 0.02, "k1": 1.0, "k2": 29.0, "F": 0.518, "w": 0.86, "d1": 1.26, "d": 1.5,
          "phi": 1.0, "k_c": 8.0, "c_c": 10.0, "law": "paper"}
FIG14A_START = np.array([0.36357, 0.79487, 1.14699, 0.73578])


def test_bilinear_impacting_period_5_orbit():
    """Exponents of the period-5 orbit against ln|mu| / (5 T) of its finite-difference
    monodromy: the resolvable three (|mu| >= 0.5; the fourth, |mu| ~ 1e-7, is below the
    differences' resolution) to 6e-4 with saltation (measured: the complex pair's mean
    3e-5, the third 5e-5); without, the third is off by 0.009."""
    pair = get_system("bilinear", 2)
    tight = Problem(pair, FIG14A, SHOOT)
    cls = classify_state(tight, FIG14A_START, 0.0)
    assert cls.impacting and cls.period == 5
    y, M, residual = refine_periodic(tight, cls.orbit[0], 0.0, 5)
    assert residual < 1e-9
    floquet = floquet_exponents(np.linalg.eigvals(M), 5, tight.period)
    problem = Problem(pair, FIG14A, TIGHT)
    good = lyapunov_spectrum(problem, y, 0.0, periods=200, transient=20, segments=10)
    assert good.ok and good.salted == good.switches > 220  # springs' gaps and contacts
    np.testing.assert_allclose(good.exponents[:3], floquet[:3], atol=6e-4)
    np.testing.assert_allclose(good.exponents[:2].mean(), floquet[:2].mean(), atol=1e-4)
    bad = lyapunov_spectrum(problem, y, 0.0, periods=200, transient=20, segments=10,
                            saltation=False)
    assert abs(bad.exponents[2] - floquet[2]) > 5e-3
