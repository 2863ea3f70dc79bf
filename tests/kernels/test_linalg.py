"""Dense linear algebra and the difference Jacobian (kernels/linalg.py)."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.kernels import linalg
from softimpact_cli.systems import get_system

from .helpers import DUFFING_PAIR

STIFF = dict(DUFFING_PAIR, k_c=1e6, c_c=1e3)  # d = 1, phi = pi: a large Jacobian in contact


@pytest.mark.parametrize("n", [1, 2, 4, 20])
def test_lu_solves_like_numpy(n):
    rng = np.random.default_rng(n)
    for _ in range(5):
        a = rng.normal(size=(n, n))
        if n > 1:
            a[0, 0] = 0.0  # pivoting is needed
        rhs = rng.normal(size=n)
        lu = a.copy()
        piv = np.empty(n, np.int64)
        assert linalg.lu_factor(lu, piv)
        x = rhs.copy()
        linalg.lu_solve(lu, piv, x)
        np.testing.assert_allclose(x, np.linalg.solve(a, rhs), rtol=1e-10, atol=1e-12)
        # Rodas4 keeps the pivots in a float row of its work array: the same solution
        lu_f, piv_f, x_f = a.copy(), np.empty(n), rhs.copy()
        assert linalg.lu_factor(lu_f, piv_f)
        linalg.lu_solve(lu_f, piv_f, x_f)
        np.testing.assert_array_equal(x_f, x)


def test_lu_reports_a_singular_matrix():
    a = np.array([[1.0, 2.0], [2.0, 4.0]])
    assert not linalg.lu_factor(a, np.empty(2, np.int64))
    assert not linalg.lu_factor(np.zeros((3, 3)), np.empty(3, np.int64))


@pytest.mark.parametrize("mode", [0, 1])
def test_difference_jacobian_matches_the_analytic_one(mode):
    system = get_system("duffing", 2)
    p = system.pack(STIFF)
    y = np.array([2.3, -0.7, 1.2, 0.4])
    for t in (0.37, 1234.5):  # large t: f_t's step must cope with the phase's rounding
        J = np.empty((4, 4))
        ft = np.empty(4)
        system.jacobian(t, y, p, mode, J, ft)
        f0 = np.empty(4)
        system.rhs(t, y, p, mode, f0)
        Jd = np.empty((4, 4))
        ftd = np.empty(4)
        n = linalg.fd_jacobian(system.rhs, p, t, y, mode, f0, Jd, ftd, np.empty(4), np.empty(4))
        assert n == 6
        # Rounding of f's terms (up to k_c |x1 - x2 - d| ~ 1e5 here in contact) sets the
        # scale; the forcing's phase w t carries ~ eps |w t|, so with the step
        # eps^(1/3) |t|^(1/3) the f_t error grows like (eps |t|)^(2/3).
        scale = max(1.0, np.max(np.abs(f0)))
        err_j = np.max(np.abs(Jd - J)) / max(1.0, np.max(np.abs(J)))
        err_t = np.max(np.abs(ftd - ft)) / scale
        print(f"mode {mode}, t = {t}: J error {err_j:.1e}, f_t error {err_t:.1e} (relative)")
        assert err_j < 1e-7 and err_t < 1e-10 * max(1.0, t) ** (2 / 3), (Jd, J, ftd, ft)
