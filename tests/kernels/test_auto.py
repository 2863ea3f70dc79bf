"""auto (kernels/auto.py): dopri5's steps while accuracy bound, Rodas4 while stability bound.

Checked: on non-stiff scenes auto takes exactly dopri5's steps (bit for bit, so the same
labels, and no switch); its two stiffness estimates (Hairer's secant test, the Gelfand
bound); on stiff stops it switches per contact phase, converges, agrees with a tight
reference, takes far fewer steps than dopri5, and returns to dopri5 when a phase is not
stiff; the counters reach the engine's results.
"""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit

from softimpact_cli.analysis.engine import COUNTER_NAMES, classify_state, record_trajectory
from softimpact_cli.kernels import auto, dopri5, layout, orbit
from softimpact_cli.kernels.codes import CONVERGED, DIVERGED, OK, STEP_BUDGET
from softimpact_cli.systems import get_system

from .helpers import BILINEAR_PAIR, DUFFING_PAIR, problem, run_advance

Y0 = np.array([2.0, 0.0, -2.0, 0.0])
STIFF = dict(DUFFING_PAIR, k_c=1e6, c_c=1e3)  # d = 1, phi = pi: the acceptance scene
OVERDAMPED = dict(DUFFING_PAIR, k_c=1e6, c_c=1e4)  # eigenvalues ~ -100, -2e4: bodies stick
TIGHT = dict(method="dopri5", rtol=1e-12, atol=1e-14, convergence_tol=1e-10)


# ---------------------------------------------------------------------------------------
# non-stiff: exactly dopri5


@pytest.mark.parametrize("model, values, y0", [
    ("duffing", DUFFING_PAIR, Y0),
    ("duffing", dict(DUFFING_PAIR, d=6.0, phi=0.0), [8.0, 0.0, -4.0, 0.0]),  # figure 6(d)
    ("duffing", dict(DUFFING_PAIR, law="no-tension", k_c=1e5), Y0),  # hard but short impacts
    ("bilinear", BILINEAR_PAIR, [1.5, 0.0, -1.5, 0.0]),
], ids=["impacting", "fig6d", "no-tension", "bilinear"])
@pytest.mark.parametrize("locate", [True, False], ids=["located", "plain"])
def test_non_stiff_runs_take_dopri5s_steps_exactly(model, values, y0, locate):
    runs = {m: classify_state(problem(model, 2, values, method=m, locate_switches=locate), y0)
            for m in ("auto", "dopri5")}
    a, d = runs["auto"], runs["dopri5"]
    assert a.status == d.status == CONVERGED and a.period == d.period
    np.testing.assert_array_equal(a.orbit, d.orbit)
    assert a.periods_used == d.periods_used and a.max_penetration == d.max_penetration
    assert a.counters["stiff_steps"] == a.counters["method_switches"] == 0
    assert a.counters == d.counters
    if values is DUFFING_PAIR:
        assert a.contacts > 0


# ---------------------------------------------------------------------------------------
# the estimates


@njit
def linear_rhs(t, y, p, mode, out):
    out[0] = p[0] * y[0] + p[1] * y[1]
    out[1] = p[2] * y[0] + p[3] * y[1]


def explicit_estimate(L, y0, h):
    work = np.zeros((layout.WORK_ROWS, 2))
    y0 = np.array(y0, float)
    linear_rhs(0.0, y0, L.ravel().copy(), 0, work[layout.K0])
    dopri5.stages(linear_rhs, L.ravel().copy(), 0.0, y0, h, 0, True, np.zeros((0, 2)),
                  np.zeros(0), work)
    return auto.explicit_stiffness(y0, h, work)


def test_hairers_estimate_sees_the_stiff_eigenvalue():
    """For y' = L y the estimate is ||L dy|| / ||dy|| along the difference of the last two
    stages, which the step's error makes point along the stiff mode."""
    L = np.diag([-1.0, -1000.0])
    for h in (1e-3, 3e-3):
        est = explicit_estimate(L, [1.0, 1.0], h)
        assert abs(est - 1000.0 * h) < 0.01 * 1000.0 * h, (h, est)
    # only the slow mode excited: nothing stiff to see
    assert abs(explicit_estimate(L, [1.0, 0.0], 3e-3) - 3e-3) < 1e-6
    # the contact's relative mode (eigenvalues -1000 +- 1000 i, |lambda| = 1414): far from
    # normal (||C|| = 2e6), so the secant over-reads, but by a small factor, not ||C|| h
    C = np.array([[0.0, 1.0], [-2e6, -2e3]])
    est = explicit_estimate(C, [1e-3, 2.0], 2e-3)
    assert 1414 * 2e-3 < est < 5 * 1414 * 2e-3, est


def contact_jacobian(values, mode=1):
    system = get_system("duffing", 2)
    J, ft = np.empty((4, 4)), np.empty(4)
    system.jacobian(0.3, np.array([2.0, 0.5, 0.9, -0.1]), system.pack(values), mode, J, ft)
    return J


def test_spectral_radius_bound():
    rng = np.random.default_rng(7)
    scratch = np.empty((2, 5, 5))
    cases = [contact_jacobian(STIFF), contact_jacobian(OVERDAMPED), contact_jacobian(STIFF, 0),
             np.diag([-3.0, 2.0, -1e8]), *(rng.normal(size=(n, n)) for n in (2, 4, 5, 5))]
    for J in cases:
        n = J.shape[0]
        rho = np.max(np.abs(np.linalg.eigvals(J)))
        bound = auto.spectral_radius_bound(J, scratch[0, :n, :n].copy(), scratch[1, :n, :n].copy())
        print(f"rho {rho:.4g}, bound {bound:.4g}")
        assert rho * (1 - 1e-12) <= bound <= 2.0 * rho, (rho, bound)
    # the stiff stop's bound is tight enough to tell contact from free flight
    assert auto.spectral_radius_bound(contact_jacobian(STIFF), np.empty((4, 4)),
                                      np.empty((4, 4))) > 1000.0
    assert auto.spectral_radius_bound(contact_jacobian(STIFF, 0), np.empty((4, 4)),
                                      np.empty((4, 4))) < 2.0
    assert auto.spectral_radius_bound(np.array([[0.0, 1.0], [0.0, 0.0]]), np.empty((2, 2)),
                                      np.empty((2, 2))) == 0.0


# ---------------------------------------------------------------------------------------
# stiff stops


@pytest.fixture(scope="module")
def references():
    """Tight dopri5 classifications of both stiff scenes from Y0."""
    return {c_c: classify_state(problem("duffing", 2, dict(STIFF, c_c=c_c), **TIGHT), Y0)
            for c_c in (1e3, 1e4)}


@pytest.mark.parametrize("c_c", [1e3, 1e4])
def test_stiff_stop_converges_and_agrees_with_a_tight_reference(c_c, references):
    """The acceptance scene (k_c = 1e6, c_c = 1e3, phi = pi, d = 1) and its overdamped
    sibling: auto converges at production settings, to within 1e-6 of the reference at the
    stroboscopic points; where the contact is stability bound (c_c = 1e4) it switches to
    Rodas4 there and needs far fewer steps than dopri5."""
    ref = references[c_c]
    values = dict(STIFF, c_c=c_c)
    a = classify_state(problem("duffing", 2, values), Y0)
    d = classify_state(problem("duffing", 2, values, method="dopri5"), Y0)
    q = ref.period
    assert ref.status == a.status == CONVERGED and a.period == q and a.impacting
    diff = np.max(np.abs(a.orbit - ref.orbit))
    print(f"c_c = {c_c:g}: |orbit - ref| {diff:.1e}; auto {a.counters}; dopri5 steps "
          f"{d.counters['steps']}")
    assert diff < 1e-6, diff
    assert a.contacts == ref.contacts
    if c_c == 1e4:
        c = a.counters
        assert c["stiff_steps"] > 0 and c["steps"] - c["stiff_steps"] > 0  # both methods
        assert c["method_switches"] >= 2 * (a.periods_used - 1)  # into and out of contact
        assert 3 * c["steps"] < d.counters["steps"]


def test_flags_follow_the_modes():
    """On the overdamped orbit the contact mode (bit 1) is flagged stiff and free flight is
    not; every period uses both methods, switching in pairs (into and out of Rodas4)."""
    pr = problem("duffing", 2, OVERDAMPED)
    surfaces = pr.kernel_args()
    y = Y0.copy()
    state = orbit.new_state(y, surfaces[0], surfaces[1])
    istate = state[0]
    opts = pr.options()
    for n in range(4):
        before = istate.copy()
        status = auto.advance(pr.system.rhs, pr.params, y, n * pr.period,
                                (n + 1) * pr.period, surfaces, opts, state,
                                orbit.no_samples(4))
        step = istate - before
        assert status == OK and istate[layout.AUTO_STIFF_MODES] == 0b10
        assert step[layout.N_CONTACTS] == 1  # Y0 starts in contact: one onset per period
        assert 0 < step[layout.N_STIFF_STEPS] < step[layout.N_STEPS]
        assert step[layout.N_METHOD_SWITCHES] >= 2 and step[layout.N_METHOD_SWITCHES] % 2 == 0


def test_entering_a_mode_picks_its_flagged_method():
    istate = np.zeros(layout.N_ISTATE, dtype=np.int64)
    istate[layout.AUTO_STIFF_MODES] = 0b10
    istate[layout.AUTO_HITS] = 3
    istate[layout.MODE] = 1
    assert auto.enter_mode(istate) and istate[layout.AUTO_STIFF] == 1
    assert istate[layout.AUTO_HITS] == 0 and istate[layout.N_METHOD_SWITCHES] == 1
    assert not auto.enter_mode(istate)  # same mode again: nothing changes
    istate[layout.MODE] = 0
    assert auto.enter_mode(istate) and istate[layout.AUTO_STIFF] == 0
    assert istate[layout.N_METHOD_SWITCHES] == 2


def test_a_phase_that_is_not_stiff_returns_to_dopri5():
    """Started in Rodas4 with free flight flagged stiff, auto finds h rho < 1 and returns
    within a few steps, clears the flag, and lands where dopri5 lands."""
    pr = problem("duffing", 2, dict(DUFFING_PAIR, d=50.0))  # never in contact
    surfaces = pr.kernel_args()
    y = Y0.copy()
    state = orbit.new_state(y, surfaces[0], surfaces[1])
    istate = state[0]
    istate[layout.AUTO_STIFF] = 1
    istate[layout.AUTO_STIFF_MODES] = 0b1
    status = auto.advance(pr.system.rhs, pr.params, y, 0.0, 3 * pr.period,
                            surfaces, pr.options(), state, orbit.no_samples(4))
    assert status == OK
    assert auto.BACK_STEPS <= istate[layout.N_STIFF_STEPS] <= auto.BACK_STEPS + 2
    assert istate[layout.AUTO_STIFF] == 0 and istate[layout.AUTO_STIFF_MODES] == 0
    assert istate[layout.N_METHOD_SWITCHES] == 1
    _, y_d, _, _ = run_advance(pr.with_integrator(method="dopri5"), Y0, 0.0, 3 * pr.period)
    assert np.max(np.abs(y - y_d)) < 1e-7


def test_records_the_overdamped_stop_like_a_tight_reference():
    pr = problem("duffing", 2, OVERDAMPED)
    a = record_trajectory(pr, Y0, 0.0, 3, 64)
    r = record_trajectory(pr.with_integrator(**TIGHT), Y0, 0.0, 3, 64)
    assert a.status == r.status == OK
    np.testing.assert_array_equal(a.section_t, np.arange(4) * pr.period)
    np.testing.assert_allclose(a.y, r.y, rtol=0, atol=1e-6)
    np.testing.assert_array_equal(a.contacts, r.contacts)
    assert a.counters["stiff_steps"] > 0 and a.counters["samples"] == 3 * 64 + 1


def test_plain_scheme_switches_too():
    a = classify_state(problem("duffing", 2, OVERDAMPED, locate_switches=False), Y0)
    assert a.status == CONVERGED and a.counters["stiff_steps"] > 0


# ---------------------------------------------------------------------------------------
# counters and status codes


def test_counters_name_every_reported_slot():
    assert len(COUNTER_NAMES) == layout.N_COUNTERS
    assert COUNTER_NAMES[layout.N_STIFF_STEPS] == "stiff_steps"
    assert COUNTER_NAMES[layout.N_METHOD_SWITCHES] == "method_switches"
    r = classify_state(problem("duffing", 2, STIFF, method="stiff"), Y0)
    assert r.counters["stiff_steps"] == r.counters["steps"] > 0
    assert r.counters["method_switches"] == 0


def test_status_codes():
    pr = problem("duffing", 2, OVERDAMPED)
    T = pr.period
    opts = pr.options()
    opts[layout.MAX_STEPS] = 10
    assert run_advance(pr, Y0, 0.0, T, opts)[0] == STEP_BUDGET
    opts = pr.options()
    opts[layout.BOUND] = 1.0
    assert run_advance(pr, Y0, 0.0, T, opts)[0] == DIVERGED
