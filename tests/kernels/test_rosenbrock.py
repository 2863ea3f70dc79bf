"""Rodas4 (kernels/rosenbrock.py): tableau, orders, L-stability, stiff stops.

The coefficients are Hairer's (rodas.f, METH = 1) in the transformed form. They are
checked in the standard Rosenbrock form (Hairer & Wanner II, section IV.7): with
``Gamma = (I/gamma - CC)^-1``, ``alpha = A Gamma``, ``b = M Gamma``, the eight order
conditions up to order 4 (Table IV.7.1; ``beta = alpha + Gamma`` off the diagonal), the
embedded solution's conditions up to order 3, stiff accuracy, and L-stability of the
stability function ``R(z) = 1 + z b^T (I - z (alpha + Gamma))^-1 1``.

References: scipy DOP853 at rtol 1e-13 (tests/naive.py, restarted at every switch) for
convergence orders; dopri5 at rtol 1e-12 for the stiff and the contact cases.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp

from softimpact_cli.kernels import dense, dopri5, layout, orbit
from softimpact_cli.kernels import rosenbrock as ro
from softimpact_cli.kernels.codes import CONVERGED, DIVERGED, OK, STEP_BUDGET
from softimpact_cli.kernels.orbit import new_state
from softimpact_cli.systems import get_system
from tests import naive

from .helpers import DUFFING_BODY, DUFFING_PAIR, fit_slope, problem

PERIODS = 3
STIFF = dict(DUFFING_PAIR, k_c=1e6, c_c=1e3)  # d = 1, phi = pi
Y0_PAIR = np.array([2.0, 0.0, -2.0, 0.0])


# ---------------------------------------------------------------------------------------
# the method


def standard_form():
    """(alpha, Gamma, b, b_hat) of the standard form from the transformed coefficients."""
    s = ro.STAGES
    Gamma = np.linalg.inv(np.eye(s) / ro.GAMMA - ro.CC)
    return ro.A @ Gamma, Gamma, ro.M @ Gamma, ro.M_HAT @ Gamma


def rosenbrock_conditions(b, alpha, Gamma):
    """(order, residual) of the order conditions up to 4 (Hairer & Wanner, Table IV.7.1)."""
    g = Gamma[0, 0]
    beta = alpha + Gamma - np.diag(np.diag(Gamma))
    bp = beta.sum(axis=1)
    a = alpha.sum(axis=1)
    return [
        (1, b.sum() - 1.0),
        (2, b @ bp - (0.5 - g)),
        (3, b @ a**2 - 1 / 3),
        (3, b @ (beta @ bp) - (1 / 6 - g + g * g)),
        (4, b @ a**3 - 0.25),
        (4, b @ (a * (alpha @ bp)) - (1 / 8 - g / 3)),
        (4, b @ (beta @ a**2) - (1 / 12 - g / 3)),
        (4, b @ (beta @ (beta @ bp)) - (1 / 24 - g / 2 + 1.5 * g * g - g**3)),
    ]


def stability_function(z, b=None):
    alpha, Gamma, b_sol, _ = standard_form()
    b = b_sol if b is None else b
    s = ro.STAGES
    return 1.0 + z * (b @ np.linalg.solve(np.eye(s) - z * (alpha + Gamma), np.ones(s)))


def test_tableau_invariants():
    alpha, Gamma, b, b_hat = standard_form()
    assert ro.ORDER == 4 and ro.STAGES == 6
    np.testing.assert_allclose(np.diag(Gamma), ro.GAMMA, rtol=0, atol=1e-14)
    assert np.all(np.triu(ro.CC) == 0.0) and np.all(np.triu(ro.A) == 0.0)  # explicit stages
    assert np.abs(np.triu(Gamma, 1)).max() < 1e-14 and np.abs(np.triu(alpha)).max() < 1e-14
    # stage times are alpha's row sums, the f_t weights Gamma's row sums
    np.testing.assert_allclose(alpha.sum(axis=1), ro.C, rtol=0, atol=1e-14)
    np.testing.assert_allclose(Gamma.sum(axis=1), ro.D, rtol=0, atol=1e-14)
    # stiffly accurate: the solution is the last stage's state, the embedded one the 5th's
    np.testing.assert_allclose(b, (alpha + Gamma)[5], rtol=0, atol=1e-13)
    np.testing.assert_allclose(b_hat, (alpha + Gamma)[4], rtol=0, atol=1e-13)
    np.testing.assert_array_equal(ro.M[:5], ro.A[5, :5])
    np.testing.assert_array_equal(ro.M_HAT, ro.A[5])
    np.testing.assert_array_equal(ro.A[5, :4], ro.A[4, :4])
    assert ro.M[5] == 1.0 and ro.A[5, 4] == 1.0 and ro.C[4] == ro.C[5] == 1.0
    assert ro.D2[5] == 0.0 and ro.D3[5] == 0.0


def test_order_conditions():
    alpha, Gamma, b, b_hat = standard_form()
    res = rosenbrock_conditions(b, alpha, Gamma)
    print("order 4 residuals", [f"{r:.1e}" for _, r in res])
    assert max(abs(r) for _, r in res) < 1e-13, res
    res_hat = rosenbrock_conditions(b_hat, alpha, Gamma)
    assert max(abs(r) for q, r in res_hat if q <= 3) < 1e-13, res_hat
    # the embedded solution is exactly order 3 (the error estimate is not identically 0)
    assert max(abs(r) for q, r in res_hat if q == 4) > 1e-3, res_hat


def test_stability_function_is_l_stable():
    _, _, _, b_hat = standard_form()
    for bb in (None, b_hat):  # both the solution and the embedded one
        assert abs(stability_function(-1e12, bb)) < 1e-10
        assert abs(stability_function(-1e6, bb)) < 1e-4
    # A-stable: |R| <= 1 on the imaginary axis (maximum principle for the left half-plane)
    worst = max(abs(stability_function(1j * y)) for y in np.geomspace(1e-3, 1e7, 3000))
    assert worst <= 1.0 + 1e-12, worst
    # R(z) - exp(z) = O(z^5): order 4
    e1 = abs(stability_function(0.1) - np.exp(0.1))
    e2 = abs(stability_function(0.05) - np.exp(0.05))
    assert 4.7 < np.log2(e1 / e2) < 5.3, (e1, e2)


@njit
def linear_rhs(t, y, p, mode, out):
    out[0] = p[0] * y[0] + p[1] * y[1]
    out[1] = p[2] * y[0] + p[3] * y[1]


def kernel_step(rhs, p, t, y0, h, jac, dfdt, mode=0):
    """One step through the kernel's own ``step`` and ``dense_coefficients``."""
    y0 = np.array(y0, float)
    dim = y0.size
    work = np.zeros((layout.work_rows(dim), dim))
    rhs(t, y0, p, mode, work[layout.F0])
    work[layout.JAC:layout.JAC + dim] = jac
    work[layout.DFDT] = dfdt
    ok = ro.rodas_step(rhs, p, t, y0, h, mode, True, np.zeros((0, dim)), np.zeros(0), work)
    assert ok
    ro.dense_coefficients(y0, work)
    return work[layout.YNEW].copy(), work[layout.U0:layout.U0 + ro.STAGES].copy(), work


@pytest.mark.parametrize("h", [0.1, 10.0])
def test_kernel_step_damps_a_stiff_contact_mode(h):
    """The relative mode of the stiff stop, x'' = -2 k_c x - 2 c_c x' (k_c = 1e6,
    c_c = 1e3: eigenvalues -1000 +- 1000i): one step is R(h L) exactly, and it damps."""
    L = np.array([[0.0, 1.0], [-2e6, -2e3]])
    y0 = np.array([1e-3, 2.0])
    ynew, _, _ = kernel_step(linear_rhs, L.ravel().copy(), 0.0, y0, h, L.copy(), np.zeros(2))
    lam, V = np.linalg.eig(L)
    want = (V @ np.diag([stability_function(h * z) for z in lam]) @ np.linalg.solve(V, y0)).real
    np.testing.assert_allclose(ynew, want, rtol=1e-9, atol=1e-15)
    damping = np.linalg.norm(ynew) / np.linalg.norm(y0)
    print(f"h = {h}: |y1|/|y0| = {damping:.2e}")
    assert damping < (0.1 if h == 0.1 else 1e-3)


# ---------------------------------------------------------------------------------------
# orders


def test_local_orders_of_step_dense_output_and_error_estimate():
    """Local error of the step ~ h^5, of the dense output at u = 0.4 ~ h^4 (3rd order),
    the error estimate U_6 ~ h^4 (embedded 3rd order)."""
    system = get_system("duffing", 1)
    par = dict(DUFFING_BODY, k2=0.3)
    p = system.pack(par)
    y0 = np.array([1.2, 0.8])
    t = 0.7
    J = np.empty((2, 2))
    ft = np.empty(2)
    system.jacobian(t, y0, p, 0, J, ft)
    hs = np.array([0.16, 0.113, 0.08, 0.057, 0.04])
    e_step, e_dense, e_est = [], [], []
    for h in hs:
        ynew, U, work = kernel_step(system.rhs, p, t, y0, h, J, ft)
        ref = solve_ivp(lambda tt, yy: naive.duffing_body_rhs(tt, yy, par), (t, t + h), y0,
                        method="DOP853", rtol=3e-14, atol=1e-15, dense_output=True)
        out = np.empty(2)
        dense.dense_state(work, 0.4, out)
        e_step.append(np.max(np.abs(ynew - ref.y[:, -1])))
        e_dense.append(np.max(np.abs(out - ref.sol(t + 0.4 * h))))
        e_est.append(np.max(np.abs(U[5])))
        # the dense output interpolates the step's ends
        dense.dense_state(work, 0.0, out)
        np.testing.assert_array_equal(out, y0)
        dense.dense_state(work, 1.0, out)
        np.testing.assert_allclose(out, ynew, rtol=0, atol=1e-15)
    s_step, s_dense, s_est = fit_slope(hs, e_step), fit_slope(hs, e_dense), fit_slope(hs, e_est)
    print(f"rodas4 local slopes: step {s_step:.2f}, dense {s_dense:.2f}, estimate {s_est:.2f}")
    assert min(e_step) > 1e-13
    assert 4.6 < s_step < 5.6, (s_step, e_step)
    assert 3.6 < s_dense < 4.6, (s_dense, e_dense)
    assert 3.6 < s_est < 4.6, (s_est, e_est)


def fixed_step(pr, y0, t1, h, locate=True, analytic=False):
    """The adaptive kernel as a fixed-step method: rtol = atol = 1, H_MAX = h."""
    pr = pr.with_integrator(rtol=1.0, atol=1.0, locate_switches=locate)
    opts = pr.options()
    opts[layout.H_MAX] = h
    return run(pr, y0, 0.0, t1, opts, analytic)


def run(pr, y0, t0, t1, opts=None, analytic=False):
    y = np.array(y0, dtype=np.float64)
    surfaces = pr.kernel_args()
    istate, fstate, work = new_state(y, surfaces[0], surfaces[1])
    opts = pr.options() if opts is None else opts
    advance = ro.with_jacobian(pr.system.jacobian) if analytic else ro.advance
    status = advance(pr.system.rhs, pr.params, y, t0, t1, surfaces, opts, (istate, fstate, work),
                     (np.empty(0), np.empty((0, y.size))))
    return int(status), y, istate, fstate


def errors(runner, Ns, ref):
    out = []
    for N in Ns:
        status, y, istate, _ = runner(N)
        assert status == OK
        assert istate[layout.N_REJECTED] == 0  # truly fixed-step
        out.append(np.max(np.abs(y - ref)))
    return np.array(out)


@pytest.mark.parametrize("analytic", [True, False], ids=["analytic-J", "difference-J"])
def test_order_on_a_smooth_trajectory(analytic):
    pr = problem("duffing", 1, DUFFING_BODY)
    y0 = np.array([2.0, 0.0])
    T = pr.period
    ref = solve_ivp(lambda t, y: naive.duffing_body_rhs(t, y, DUFFING_BODY), (0.0, PERIODS * T),
                    y0, method="DOP853", rtol=1e-13, atol=1e-14).y[:, -1]
    Ns = np.unique(np.round(np.geomspace(20, 320, 9)).astype(int))
    err = errors(lambda N: fixed_step(pr, y0, PERIODS * T, T / N, analytic=analytic), Ns, ref)
    slope = fit_slope(1.0 / Ns, err)
    print(f"rodas4 smooth ({'analytic' if analytic else 'difference'} J): slope {slope:.3f}, "
          f"errors {err[0]:.2e}..{err[-1]:.2e}")
    assert err.min() > 1e-10
    assert 3.7 <= slope <= 4.3, (slope, err)
    _, _, istate, _ = fixed_step(pr, y0, PERIODS * T, T / 40, analytic=analytic)
    assert abs(istate[layout.N_STEPS] - PERIODS * 40) <= 1


@pytest.fixture(scope="module")
def impacting():
    pr = problem("duffing", 2, DUFFING_PAIR)
    T = pr.period
    sol = naive.solve_model(naive.duffing_pair_model(DUFFING_PAIR), Y0_PAIR, (0.0, PERIODS * T),
                            rtol=1e-13, atol=1e-13)
    onsets = sum(1 for s, m in zip(sol.event_surface, sol.event_mode, strict=True)
                 if s == 0 and m & 1)
    assert onsets >= 2 and len(sol.event_t) >= 5
    return pr, sol.y_end, onsets


def test_order_is_kept_through_located_contacts(impacting):
    """Each located switch is put on the surface by Newton on the step length: without it
    the 3rd-order dense output's crossing error shows up as erratic, ~3rd-order errors."""
    pr, ref, onsets = impacting
    T = pr.period
    Ns = np.unique(np.round(np.geomspace(64, 640, 12)).astype(int))
    err = errors(lambda N: fixed_step(pr, Y0_PAIR, PERIODS * T, T / N), Ns, ref)
    slope = fit_slope(1.0 / Ns, err)
    print(f"rodas4 located: slope {slope:.3f}, errors {err[0]:.2e}..{err[-1]:.2e}")
    assert err.min() > 3e-12
    assert slope >= 3.7, (slope, err)
    _, _, istate, _ = fixed_step(pr, Y0_PAIR, PERIODS * T, T / 200)
    assert istate[layout.N_CONTACTS] == onsets
    # the plain scheme (no location) is far off at the finest step
    status, y, _, _ = fixed_step(pr, Y0_PAIR, PERIODS * T, T / Ns[-1], locate=False)
    assert status == OK and np.max(np.abs(y - ref)) > 1e-5


# ---------------------------------------------------------------------------------------
# against dopri5


def classify(pr, method, rtol, atol, tol, max_periods=3000):
    """(status, q, periods used, orbit, contacts, max_g, counters), seconds."""
    p2 = pr.with_integrator(rtol=rtol, atol=atol)
    t0 = time.perf_counter()
    out = orbit.classified(orbit.classify(method, pr.system.rhs, pr.params,
                                          (Y0_PAIR.copy(), 0.0, pr.period), pr.kernel_args(),
                                          p2.options(), (max_periods, 30, tol)))
    return tuple(out)[:7], time.perf_counter() - t0


def warm_up(pr):
    for method in (ro.advance, dopri5.advance):
        classify(pr, method, 1e-6, 1e-8, 1e-6, max_periods=1)


@pytest.mark.parametrize("c_c", [1e3, 1e4])
def test_stiff_stop_converges_and_agrees_with_a_tight_reference(c_c):
    """k_c = 1e6, d = 1, phi = pi from (2, 0, -2, 0). With c_c = 1e3 the stop acts in
    short impacts (~ms); c_c = 1e4 makes it overdamped (eigenvalues ~ -100 and -2e4):
    the bodies stick for ~5 % of each period and dopri5 becomes stability bound there.
    Reference: dopri5 at rtol 1e-12, atol 1e-14, convergence tol 1e-10."""
    pr = problem("duffing", 2, dict(STIFF, c_c=c_c))
    warm_up(pr)
    ref, t_ref = classify(pr, dopri5.advance, 1e-12, 1e-14, 1e-10)
    assert ref[0] == CONVERGED
    q = ref[1]
    # production settings: rtol 1e-8, atol 1e-10, convergence tol 1e-6
    (st, q_r, n_r, orb_r, contacts, max_g, cnt_r), t_r = classify(pr, ro.advance, 1e-8, 1e-10,
                                                                   1e-6)
    (st_d, q_d, n_d, orb_d, _, _, cnt_d), t_d = classify(pr, dopri5.advance, 1e-8, 1e-10, 1e-6)
    assert st == CONVERGED and st_d == CONVERGED and q_r == q_d == q
    assert max_g > 0.0 and contacts == ref[4] >= 1  # an impacting orbit
    assert abs(max_g - ref[5]) < 1e-6 * max(1.0, abs(ref[5]))
    diff = np.max(np.abs(orb_r[:q] - ref[3][:q]))
    # tight Rosenbrock too
    (st_t, _, _, orb_t, _, _, _), _ = classify(pr, ro.advance, 1e-10, 1e-12, 1e-10)
    diff_t = np.max(np.abs(orb_t[:q] - ref[3][:q]))
    print(f"\nk_c=1e6 c_c={c_c:g}: period {q}, orbit {orb_r[0]}, max penetration {max_g:.3e}")
    print(f"  rodas4 rtol 1e-8: {t_r * 1e3:.2f} ms, {n_r} periods, {cnt_r[layout.N_STEPS]} steps, "
          f"{cnt_r[layout.N_REJECTED]} rejected, {cnt_r[layout.N_RHS]} rhs; "
          f"|orbit - ref| {diff:.1e}")
    print(f"  dopri5 rtol 1e-8: {t_d * 1e3:.2f} ms, {n_d} periods, {cnt_d[layout.N_STEPS]} steps, "
          f"{cnt_d[layout.N_REJECTED]} rejected, {cnt_d[layout.N_RHS]} rhs; "
          f"|orbit - ref| {np.max(np.abs(orb_d[:q] - ref[3][:q])):.1e}")
    print(f"  reference dopri5 rtol 1e-12: {t_ref * 1e3:.2f} ms; rodas4 rtol 1e-10: "
          f"|orbit - ref| {diff_t:.1e}")
    assert diff < 1e-6, diff
    assert st_t == CONVERGED and diff_t < 1e-8, diff_t
    if c_c == 1e4:  # stability bound: the L-stable method needs far fewer steps
        assert cnt_r[layout.N_STEPS] * 3 < cnt_d[layout.N_STEPS], (cnt_r, cnt_d)


def test_agrees_with_dopri5_on_a_soft_contact_case(impacting):
    """d = 1, k_c = 8, c_c = 10 from (2, 0, -2, 0): state at t = 20 T, contacts counted."""
    pr, _, _ = impacting
    T = pr.period
    surfaces = pr.kernel_args()
    tight = pr.with_integrator(rtol=1e-12, atol=1e-14).options()
    st_d, y_d, g_d, c_d = orbit.flow(dopri5.advance, pr.system.rhs, pr.params, Y0_PAIR.copy(),
                                     0.0, 20 * T, surfaces, tight)
    assert st_d == OK
    for rtol, lim in ((1e-8, 1e-6), (1e-10, 1e-8)):
        opts = pr.with_integrator(rtol=rtol, atol=rtol * 1e-2).options()
        st, y, g, c = orbit.flow(ro.advance, pr.system.rhs, pr.params, Y0_PAIR.copy(), 0.0,
                                 20 * T, surfaces, opts)
        diff = np.max(np.abs(y - y_d))
        print(f"rodas4 rtol {rtol:g}: |y(20T) - dopri5| = {diff:.1e}, {c[layout.N_STEPS]} steps")
        assert st == OK and diff < lim, diff
        assert c[layout.N_CONTACTS] == c_d[layout.N_CONTACTS] > 5
        assert abs(g - g_d) < 1e-9
    # the analytic-Jacobian entry point agrees with the difference one
    st_a, y_a, _, _ = run(pr, Y0_PAIR, 0.0, 20 * T, opts, analytic=True)
    assert st_a == OK and np.max(np.abs(y_a - y)) < 1e-9


def test_records_samples_and_sections_like_dopri5(impacting):
    pr, _, _ = impacting
    T = pr.period
    spp = 64
    cap = PERIODS * spp + 1
    out = {}
    for name, method, rtol in (("rodas4", ro.advance, 1e-10), ("dopri5", dopri5.advance, 1e-12)):
        opts = pr.with_integrator(rtol=rtol, atol=rtol * 1e-2).options(T / spp, 0.0)
        out[name] = orbit.recorded(orbit.record(method, pr.system.rhs, pr.params,
                                                (Y0_PAIR.copy(), 0.0, T), PERIODS,
                                                pr.kernel_args(), opts, cap))
    r, d = out["rodas4"], out["dopri5"]
    assert r[0] == OK and r[3] == cap
    np.testing.assert_allclose(r[1], d[1], rtol=0, atol=1e-12)  # sample times
    np.testing.assert_allclose(r[2], d[2], rtol=0, atol=1e-7)  # dense samples
    np.testing.assert_array_equal(r[4], np.arange(PERIODS + 1) * T)  # lands on n T exactly
    np.testing.assert_allclose(r[5], d[5], rtol=0, atol=1e-8)
    np.testing.assert_array_equal(r[6], d[6])  # contacts per period
    np.testing.assert_allclose(r[7], d[7], rtol=0, atol=1e-8)  # max penetration per period


def test_status_codes():
    pr = problem("duffing", 2, STIFF)
    T = pr.period
    opts = pr.options()
    opts[layout.MAX_STEPS] = 10
    assert run(pr, Y0_PAIR, 0.0, T, opts)[0] == STEP_BUDGET
    opts = pr.options()
    opts[layout.BOUND] = 1.0
    assert run(pr, Y0_PAIR, 0.0, T, opts)[0] == DIVERGED
    status, y, istate, fstate = run(pr, Y0_PAIR, 0.0, T)
    assert status == OK and fstate[layout.H] > 0.0 and istate[layout.N_SWITCHES] >= 1
