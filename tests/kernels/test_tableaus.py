"""Butcher tableaus and dense output: the methods are the ones they claim to be."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact_cli.kernels import dense, dopri5, layout, rk4
from softimpact_cli.systems import get_system
from tests import naive

from .helpers import DUFFING_BODY, fit_slope


def square(A, s):
    M = np.zeros((s, s))
    M[: A.shape[0], : A.shape[1]] = A
    return M


def order_conditions(b, A, c, theta=1.0):
    """(order, residual) of the 17 conditions up to order 5 (Butcher, rooted trees).

    With ``theta``, the conditions of a continuous extension b(theta): Phi(t) =
    theta^order / gamma(t)."""
    Ac = A @ c
    conds = [
        (1, b.sum(), 1),
        (2, b @ c, Fraction(1, 2)),
        (3, b @ c**2, Fraction(1, 3)),
        (3, b @ Ac, Fraction(1, 6)),
        (4, b @ c**3, Fraction(1, 4)),
        (4, b @ (c * Ac), Fraction(1, 8)),
        (4, b @ (A @ c**2), Fraction(1, 12)),
        (4, b @ (A @ Ac), Fraction(1, 24)),
        (5, b @ c**4, Fraction(1, 5)),
        (5, b @ (c**2 * Ac), Fraction(1, 10)),
        (5, b @ (c * (A @ c**2)), Fraction(1, 15)),
        (5, b @ (c * (A @ Ac)), Fraction(1, 30)),
        (5, b @ Ac**2, Fraction(1, 20)),
        (5, b @ (A @ c**3), Fraction(1, 20)),
        (5, b @ (A @ (c * Ac)), Fraction(1, 40)),
        (5, b @ (A @ (A @ c**2)), Fraction(1, 60)),
        (5, b @ (A @ (A @ Ac)), Fraction(1, 120)),
    ]
    return [(q, float(val) - float(want) * theta**q) for q, val, want in conds]


def satisfied_order(b, A, c, tol=1e-14):
    order = 0
    for q in range(1, 6):
        if all(abs(r) < tol for qq, r in order_conditions(b, A, c) if qq == q):
            order = q
        else:
            break
    return order


def test_dopri5_tableau_invariants():
    s = dopri5.STAGES
    A = square(dopri5.A, s)
    c = dopri5.C
    assert dopri5.ORDER == 5
    assert abs(dopri5.B.sum() - 1.0) < 1e-15
    assert abs(dopri5.B_HAT.sum() - 1.0) < 1e-15
    np.testing.assert_allclose(A.sum(axis=1), c, atol=1e-14)
    np.testing.assert_array_equal(dopri5.E, dopri5.B - dopri5.B_HAT)
    assert np.all(np.triu(A) == 0.0)  # explicit
    np.testing.assert_array_equal(A[-1], dopri5.B)  # FSAL: last stage is at the solution
    assert c[-1] == 1.0


def test_dopri5_order_conditions():
    A = square(dopri5.A, dopri5.STAGES)
    res5 = order_conditions(dopri5.B, A, dopri5.C)
    assert max(abs(r) for _, r in res5) < 1e-14, res5
    res4 = [(q, r) for q, r in order_conditions(dopri5.B_HAT, A, dopri5.C) if q <= 4]
    assert max(abs(r) for _, r in res4) < 1e-14, res4
    # the embedded solution is exactly order 4 (the error estimate is not identically 0)
    assert satisfied_order(dopri5.B_HAT, A, dopri5.C) == 4
    assert satisfied_order(dopri5.B, A, dopri5.C) == 5


def test_rk4_tableau_invariants_and_order():
    A = square(rk4.A, rk4.STAGES)
    assert rk4.ORDER == 4
    assert abs(rk4.B.sum() - 1.0) < 1e-15
    np.testing.assert_allclose(A.sum(axis=1), rk4.C, atol=1e-15)
    assert satisfied_order(rk4.B, A, rk4.C) == 4
    # the kernel only reads the subdiagonal: the classical tableau has nothing else
    assert np.count_nonzero(A - np.diag(np.diag(A, -1), -1)) == 0


def dopri5_step(system, p, t, y, h, mode=0):
    """One dopri5 step through the kernel's own stage and dense-output functions."""
    y = np.array(y, float)
    dim = y.size
    work = np.zeros((layout.WORK_ROWS, dim))
    system.rhs(t, y, p, mode, work[layout.K0])
    A_s = np.zeros((0, dim))
    b_s = np.zeros(0)
    dopri5.stages(system.rhs, p, t, y, h, mode, True, A_s, b_s, work)
    dopri5.dense_coefficients(y, h, work)
    return work


def dense_at(work, u):
    out = np.empty(work.shape[1])
    dense.dense_state(work, u, out)
    return out


def dense_rate(work, u):
    M = work[layout.M0: layout.M0 + 5]
    return sum(k * M[k] * u ** (k - 1) for k in range(1, 5))


def test_dopri5_dense_output_consistency():
    system = get_system("duffing", 1)
    p = system.pack(DUFFING_BODY)
    y0 = np.array([1.7, -0.4])
    t, h = 0.3, 0.2
    work = dopri5_step(system, p, t, y0, h)
    f0 = naive.duffing_body_rhs(t, y0, DUFFING_BODY)
    y1 = work[layout.YNEW]
    f1 = naive.duffing_body_rhs(t + h, y1, DUFFING_BODY)
    np.testing.assert_array_equal(dense_at(work, 0.0), y0)
    np.testing.assert_allclose(dense_at(work, 1.0), y1, rtol=0, atol=1e-15)
    np.testing.assert_allclose(dense_rate(work, 0.0), h * f0, rtol=0, atol=1e-14)
    np.testing.assert_allclose(dense_rate(work, 1.0), h * f1, rtol=0, atol=1e-14)
    # FSAL: the last stage is f at the new state
    np.testing.assert_allclose(work[layout.K0 + 6], f1, rtol=0, atol=1e-14)


def dense_weights(theta):
    """The weights b_i(theta) of the kernel's dense output, y(t + theta h) = y + h sum_i
    b_i(theta) K_i, read off by running dense_coefficients on unit stage vectors."""
    s = dopri5.STAGES
    work = np.zeros((layout.WORK_ROWS, s))
    work[layout.K0: layout.K0 + s] = np.eye(s)
    work[layout.YNEW] = dopri5.B  # = y + h sum_j B_j K_j with y = 0, h = 1
    dopri5.dense_coefficients(np.zeros(s), 1.0, work)
    return dense_at(work, theta)


@pytest.mark.parametrize("theta", [0.1, 0.3, 0.5, 0.77, 1.0])
def test_dopri5_dense_output_order_conditions(theta):
    """Hairer's continuous extension is 4th order for every theta: the order conditions
    up to order 4 hold with theta^q / gamma; at theta = 1 it is the step itself (B). This
    pins the D coefficients exactly (not just to a test's tolerance)."""
    A = square(dopri5.A, dopri5.STAGES)
    b = dense_weights(theta)
    res = [(q, r) for q, r in order_conditions(b, A, dopri5.C, theta) if q <= 4]
    assert max(abs(r) for _, r in res) < 1e-14, res
    if theta == 1.0:
        np.testing.assert_allclose(b, dopri5.B, rtol=0, atol=1e-15)
    else:  # and no more than 4th order
        assert max(abs(r) for q, r in order_conditions(b, A, dopri5.C, theta) if q == 5) > 1e-6


def test_dopri5_local_orders_of_step_and_dense_output():
    """Local error of the step ~ h^6, of the dense output at u = 0.4 ~ h^5 (4th order)."""
    system = get_system("duffing", 1)
    par = dict(DUFFING_BODY, k2=0.3)  # make the nonlinearity matter
    p = system.pack(par)
    y0 = np.array([1.2, 0.8])
    t = 0.7
    hs = np.array([0.4, 0.28, 0.2, 0.14, 0.1])
    err_step, err_dense = [], []
    for h in hs:
        work = dopri5_step(system, p, t, y0, h)
        rhs = lambda tt, yy: naive.duffing_body_rhs(tt, yy, par)  # noqa: E731
        ref = solve_ivp(rhs, (t, t + h), y0, method="DOP853", rtol=3e-14, atol=1e-15,
                        dense_output=True)
        err_step.append(np.max(np.abs(work[layout.YNEW] - ref.y[:, -1])))
        err_dense.append(np.max(np.abs(dense_at(work, 0.4) - ref.sol(t + 0.4 * h))))
    s_step, s_dense = fit_slope(hs, err_step), fit_slope(hs, err_dense)
    print(f"dopri5 local slopes: step {s_step:.3f}, dense output {s_dense:.3f}")
    assert min(err_step) > 1e-14  # measured above roundoff
    assert 5.5 < s_step < 6.6, (s_step, err_step)
    assert 4.5 < s_dense < 5.6, (s_dense, err_dense)


@pytest.mark.parametrize("u", [0.0, 0.25, 1.0])
def test_rk4_hermite_extension_interpolates(u):
    y0 = np.array([1.0, -2.0, 0.5])
    y1 = np.array([1.5, -1.0, 0.25])
    f0 = np.array([0.3, 2.0, -1.0])
    f1 = np.array([-0.2, 1.0, 0.1])
    h = 0.37
    work = np.zeros((layout.WORK_ROWS, 3))
    dense.hermite_coefficients(work, y0, y1, f0, f1, h)
    # reference: the cubic Hermite basis
    h00, h10 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u
    h01, h11 = -2 * u**3 + 3 * u**2, u**3 - u**2
    want = h00 * y0 + h10 * h * f0 + h01 * y1 + h11 * h * f1
    np.testing.assert_allclose(dense_at(work, u), want, rtol=0, atol=1e-15)
    np.testing.assert_allclose(dense_rate(work, 0.0), h * f0, atol=1e-15)
    np.testing.assert_allclose(dense_rate(work, 1.0), h * f1, atol=1e-15)
