"""Critical distances against an independent computation (scipy, brute-force sampling)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact_cli.analysis.catalogue import sample_states
from softimpact_cli.analysis.critical_distance import critical_distances
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.store.catalogues import build_catalogue
from softimpact_cli.systems import get_system

DUFFING = dict(c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3, d=6.0, phi=0.0, k_c=8.0, c_c=10.0,
               law="paper")


def uncoupled_duffing(t, y, phi):
    c, k1, k2, F, w = 0.05, 1.0, 0.01, 1.0, 1.3
    x1, v1, x2, v2 = y
    return [v1, F * np.sin(w * t) - c * v1 - k1 * x1 - k2 * x1**3,
            v2, F * np.sin(w * t + phi) - c * v2 - k1 * x2 - k2 * x2**3]


@pytest.fixture(scope="module")
def catalogue():
    return build_catalogue(get_system("duffing", 2), DUFFING, IntegratorSettings(),
                           sample_states({"x": (-12, 12), "v": (-12, 12)}, 8, 40, seed=3))


@pytest.mark.parametrize("phi", [np.pi / 4, 3 * np.pi / 4, np.pi, 5.28])
def test_matches_brute_force_scipy(catalogue, phi):
    system = get_system("duffing", 2)
    ds = critical_distances(system, DUFFING, list(catalogue.attractors), np.array([phi]))
    T = 2 * np.pi / 1.3
    from softimpact_cli.analysis.catalogue import body_problem, combinations, right_attractors
    from softimpact_cli.analysis.critical_distance import TIGHT

    right = right_attractors(body_problem(system, DUFFING, TIGHT), list(catalogue.attractors),
                             phi, 1.0, 0.0)
    for i, combo in enumerate(combinations(list(catalogue.attractors), right)):
        q = combo.orbit.shape[0]
        sol = solve_ivp(uncoupled_duffing, (0.0, q * T), combo.orbit[0], args=(phi,),
                        method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
        t = np.linspace(0.0, q * T, 100_000 * q, endpoint=False)
        y = sol.sol(t)
        reference = float(np.max(y[0] - y[2]))
        assert str(ds["combination_label"].values[i]) == combo.name
        assert ds["d_crit"].values[i, 0] == pytest.approx(reference, abs=1e-6), combo.name
        # and the located maximum is not below the brute-force one (it is the true max)
        assert ds["d_crit"].values[i, 0] >= reference - 1e-9


def test_synchronous_large_pair_touches_zero_at_phi_zero(catalogue):
    """At phi = 0 the two bodies on the same attractor move identically: x1 - x2 = 0."""
    ds = critical_distances(get_system("duffing", 2), DUFFING, list(catalogue.attractors),
                            np.array([0.0]))
    names = list(ds["combination_label"].values)
    for same in ("L1^1 R1-0^1", "L1^2 R1-0^2"):
        assert abs(ds["d_crit"].values[names.index(same), 0]) < 1e-8
