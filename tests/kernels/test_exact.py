"""The closed-form flow of piecewise-linear systems (method "exact", kernels/exact.py).

Checks against what is known without it: a linear oscillator's steady state in closed
form, scipy's DOP853 restarted at every switch (tests/naive.py) on the bilinear pair with
many contacts, dopri5 at rtol 1e-12 for counts, contact maxima and dense samples, a planted
grazing excursion far shorter than a step, and the refusals of systems that are not
piecewise linear.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.config import ConfigError
from softimpact_cli.kernels.codes import OK
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.systems import get_system
from softimpact_cli.systems.piecewise_linear import exact_refusal, mode_generator
from softimpact_cli.systems.variational import variational_system
from tests import naive

from .helpers import BILINEAR_BODY, BILINEAR_PAIR, problem, run_advance

PERIODS = 50


def steady_state(values: dict, t: np.ndarray) -> np.ndarray:
    """(x, v) of the linear oscillator x'' + c x' + k1 x = F sin(w t) on its steady state."""
    c, k1, F, w = values["c"], values["k1"], values["F"], values["w"]
    amplitude = F / np.hypot(k1 - w * w, c * w)
    lag = np.arctan2(c * w, k1 - w * w)
    return np.stack([amplitude * np.sin(w * t - lag), amplitude * w * np.cos(w * t - lag)], -1)


def test_linear_steady_state_is_exact_to_rounding():
    # the second spring never engages: one linear mode, known in closed form
    values = dict(BILINEAR_BODY, F=0.1, d1=5.0)
    pr = problem("bilinear", 1, values, method="exact")
    T = pr.period
    t = np.arange(PERIODS + 1) * T
    tr = record_trajectory(pr, steady_state(values, np.zeros(1))[0], 0.0, PERIODS, 1)
    assert tr.status == OK
    err = np.max(np.abs(tr.section_y - steady_state(values, t)))
    assert err <= 1e-13, err  # dopri5 at rtol 1e-8 is ~1e-9 off here


def test_a_transient_decays_as_the_closed_form_says():
    # start off the steady state: the difference is the free damped oscillation
    values = dict(BILINEAR_BODY, F=0.1, d1=5.0)
    pr = problem("bilinear", 1, values, method="exact")
    y0 = steady_state(values, np.zeros(1))[0] + np.array([0.5, 0.0])
    t1 = 7.3 * pr.period
    status, y, _, _ = run_advance(pr, y0, 0.0, t1)
    c, k1 = values["c"], values["k1"]
    wd = np.sqrt(k1 - c * c / 4)
    decay = np.exp(-c * t1 / 2)
    free = 0.5 * decay * np.array([np.cos(wd * t1) + c / (2 * wd) * np.sin(wd * t1),
                                   -(k1 / wd) * np.sin(wd * t1)])
    assert status == OK
    np.testing.assert_allclose(y, steady_state(values, np.array([t1]))[0] + free, atol=1e-13)


CASES = {
    "paper": dict(BILINEAR_PAIR, d=0.5, phi=1.0),
    "no-tension": dict(BILINEAR_PAIR, d=0.5, phi=1.0, law="no-tension"),
}


@pytest.fixture(scope="module", params=list(CASES))
def pair_case(request):
    par = CASES[request.param]
    y0 = [-1.5, 0.0, 1.5, 0.0]
    pr = problem("bilinear", 2, par, method="exact")
    T = pr.period
    tr = record_trajectory(pr, y0, 0.0, PERIODS, 1)
    ref = naive.solve_model(naive.bilinear_pair_model(par), y0, (0.0, PERIODS * T),
                            t_eval=np.arange(PERIODS + 1) * T)
    tight = record_trajectory(pr.with_integrator(method="dopri5", rtol=1e-12, atol=1e-13),
                              y0, 0.0, PERIODS, 1)
    return pr, tr, ref, tight


def test_pair_with_contacts_matches_the_scipy_referee(pair_case):
    pr, tr, ref, tight = pair_case
    assert tr.status == OK
    err = np.max(np.abs(tr.section_y - ref.y_eval), axis=1)
    # the referee and dopri5 at 1e-12 are ~1e-11 apart; the exact flow is as close
    assert err.max() <= 1e-9, err.max()
    assert np.max(np.abs(tr.section_y - tight.section_y)) <= 1e-9


def test_switches_contacts_and_contact_maximum_equal_a_tight_dopri5(pair_case):
    pr, tr, ref, tight = pair_case
    assert tr.counters["switches"] == tight.counters["switches"] > 100
    assert tr.counters["contacts"] == tight.counters["contacts"] > 10
    np.testing.assert_allclose(tr.max_g, tight.max_g, atol=1e-9)
    # the exact flow takes ~13 steps per period where dopri5 at 1e-12 takes hundreds
    assert tr.counters["steps"] < tight.counters["steps"] / 20


def test_dense_samples_are_on_the_flow():
    pr = problem("bilinear", 2, CASES["paper"], method="exact")
    y0 = [-1.5, 0.0, 1.5, 0.0]
    tr = record_trajectory(pr, y0, 0.0, 4, 97)  # sample times fall anywhere in a step
    tight = record_trajectory(pr.with_integrator(method="dopri5", rtol=1e-12, atol=1e-13),
                              y0, 0.0, 4, 97)
    np.testing.assert_allclose(tr.t, tight.t, rtol=0, atol=1e-12)
    assert np.max(np.abs(tr.y - tight.y)) <= 1e-9


def test_landing_anywhere_and_continuing_is_one_flow():
    pr = problem("bilinear", 2, CASES["paper"], method="exact")
    T = pr.period
    y0 = [-1.5, 0.0, 1.5, 0.0]
    _, whole, _, _ = run_advance(pr, y0, 0.0, 3.3 * T)
    _, part, _, _ = run_advance(pr, y0, 0.0, 1.137 * T)
    # a new call restarts the mode from the state: continue from where the first stopped
    _, rest, _, _ = run_advance(pr, part, 1.137 * T, 3.3 * T)
    _, tight, _, _ = run_advance(pr.with_integrator(method="dopri5", rtol=1e-12, atol=1e-13),
                                 y0, 0.0, 3.3 * T)
    assert np.max(np.abs(whole - rest)) <= 1e-11
    assert np.max(np.abs(whole - tight)) <= 1e-9


def test_a_grazing_excursion_shorter_than_a_quarter_step_is_found():
    # on the linear steady state x dips to -A; the second spring's surface x = -d1 sits
    # 1e-6 inside that dip: each period the trajectory crosses it for ~0.005 time units
    # (a free-flight step here is T / 4 ~ 1.8), so only the extremum search can see it
    values = dict(BILINEAR_BODY, F=0.1)
    c, k1, F, w = values["c"], values["k1"], values["F"], values["w"]
    amplitude = F / np.hypot(k1 - w * w, c * w)
    values["d1"] = amplitude - 1e-6
    values["k2"] = 1e-6  # engaged, the spring barely acts: the dip repeats every period
    y0 = steady_state(values, np.zeros(1))[0]
    pr = problem("bilinear", 1, values, method="exact")
    tight = pr.with_integrator(method="dopri5", rtol=1e-12, atol=1e-14)
    _, y, istate, _ = run_advance(pr, y0, 0.0, 10 * pr.period)
    _, y_tight, istate_tight, _ = run_advance(tight, y0, 0.0, 10 * pr.period)
    assert istate[4] == istate_tight[4] == 20  # in and out, once per period
    assert np.max(np.abs(y - y_tight)) <= 1e-10


def test_modes_are_read_off_the_right_hand_side():
    system = get_system("bilinear", 2)
    params = system.pack(dict(BILINEAR_PAIR))
    G = mode_generator(system, params, 1)  # in contact: the stop's spring and damper
    assert G[1, 0] == pytest.approx(-1.0 - 8.0) and G[1, 1] == pytest.approx(-0.02 - 10.0)
    assert G[3, 0] == pytest.approx(8.0) and G[1, 6] == pytest.approx(8.0 * 1.0)


@pytest.mark.parametrize("model, coupling, message", [
    ("duffing", "", "not piecewise linear"),
    ("bilinear", 'law = "hunt-crossley"\n', "not linear in the state"),
])
def test_systems_that_are_not_piecewise_linear_are_refused(model, coupling, message):
    text = (f'[system]\nmodel = "{model}"\nbodies = 2\n[coupling]\n{coupling}'
            '[integrator]\nmethod = "exact"\n[analysis]\nstate = [0.1, 0.0, 0.2, 0.0]\n')
    with pytest.raises(ConfigError, match=r"\[integrator\] method = \"exact\".*" + message):
        parse_scene(text)


def test_the_plain_scheme_is_refused():
    with pytest.raises(ConfigError, match="locate_switches"):
        parse_scene('[system]\nmodel = "bilinear"\n[integrator]\nmethod = "exact"\n'
                    "locate_switches = false\n[analysis]\nstate = [0.1, 0.0, 0.2, 0.0]\n")


def test_variational_equations_fall_back_to_dopri5():
    system = get_system("bilinear", 1)
    pr = Problem(variational_system(system), system.defaults(),
                 problem("bilinear", 1, BILINEAR_BODY, method="exact").integrator)
    assert pr.integrator.resolved_method == "dopri5"
    assert exact_refusal(system, system.pack(BILINEAR_BODY)) is None


def test_info_names_the_exact_flow_steps(tmp_path):
    from softimpact_cli.api import run
    from softimpact_cli.kinds.results import describe

    ds = run('[system]\nmodel = "bilinear"\nbodies = 1\n[analysis]\nkind = "trajectory"\n'
             "state = [0.5, 0.0]\nperiods = 4\n")
    assert ds.attrs["integrator_resolved_method"] == "exact"  # the bilinear default
    steps = describe(ds)["steps_by_method"]["record"]
    assert steps["exact flow"] > 0 and steps["stiff"] == 0 and "explicit" not in steps


def test_a_quarters_taylor_polynomial_is_its_propagator_and_finds_roots_to_rounding():
    # the switch search runs Newton on the quarter's series in powers of u = x / span:
    # at u = 1 it must be the quarter propagator's node, and a root it returns must put g
    # at zero to rounding (the state left in FLOW on the surface)
    from softimpact_cli.kernels import exact

    pr = problem("bilinear", 2, dict(BILINEAR_PAIR, d=0.5, phi=1.0), method="exact")
    p = pr.params
    A, b = pr.kernel_args()[0], pr.kernel_args()[1]
    base = exact.block_start(p)
    aug = int(p[base + 1])
    rng = np.random.default_rng(7)
    roots = 0
    for mode in (0, 1, 5):
        at = exact.mode_offset(p, base, mode)
        G, Q, R = exact.mode_matrices(p, at)
        np.testing.assert_allclose(R, A @ G[:4, :], rtol=0, atol=1e-15)
        span = 0.25 * p[at]
        for _ in range(5):
            buf = exact.scratch(aug)
            wt = rng.uniform(0, 2 * np.pi)
            buf[exact.NODES, :aug] = [*rng.uniform(-2, 2, 4), np.sin(wt), np.cos(wt), 1.0]
            terms = exact.quarter_series(G, buf, exact.NODES, span)
            exact.series_state(G, buf, terms, 1.0)
            node = Q @ buf[exact.NODES, :aug]
            np.testing.assert_allclose(buf[exact.FLOW, :aug], node, rtol=0,
                                       atol=1e-14 * np.max(np.abs(node)))
            # a surface through the state halfway along: its root is there
            buf[exact.NODES + 1, :aug] = buf[exact.FLOW, :aug]
            exact.series_state(G, buf, terms, 0.5)
            mid = buf[exact.FLOW, :4].copy()
            b_mid = b.copy()
            b_mid[1] = -A[1] @ mid  # g_1 = A_1 y + b_1 is zero at the midpoint
            g0 = A[1] @ buf[exact.NODES, :4] + b_mid[1]
            g1 = A[1] @ buf[exact.NODES + 1, :4] + b_mid[1]
            if g0 * g1 >= 0 or abs(g0) < 1e-3 or abs(g1) < 1e-3:
                continue  # not a single clean crossing on this quarter
            x = exact.newton_on_quarter(G, (A, b_mid, 1, 1.0), buf, exact.NODES, span,
                                        (0.0, span, g0, g1), False, -1.0)
            assert x == pytest.approx(0.5 * span, rel=1e-12)
            assert abs(A[1] @ buf[exact.FLOW, :4] + b_mid[1]) <= 1e-14
            roots += 1
    assert roots >= 10
