"""Continuation of periodic orbits: the single Duffing body's hysteresis loop in F (folds
against brute-force sweeps and harmonic balance), reversibility, the saltation
monodromy against finite differences of the flow, grazing against the critical
distances, a period doubling against a brute-force estimate."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.continuation import Settings, follow, start_point
from softimpact_cli.analysis.continuation_branches import continue_starts
from softimpact_cli.analysis.continuation_sweep import jumps, sweep, sweep_values
from softimpact_cli.analysis.engine import Problem, flow
from softimpact_cli.analysis.lyapunov import finite_difference_monodromy
from softimpact_cli.analysis.shooting import SHOOTING, OrbitMap, salted_monodromy
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems import get_system

BODY = get_system("duffing", 1)
VALUES = BODY.defaults()  # c = 0.05, k1 = 1, k2 = 0.01, F = 1, w = 1.3
SMALL = np.array([-0.14175511, -1.90995831])  # the small period-1 orbit at F = 1 (t = 0)
LARGE = np.array([-6.26, 10.33])  # near the large one


@pytest.fixture(scope="module")
def fold_branch():
    base = OrbitMap(BODY, VALUES, "F", 1)
    settings = Settings((0.2, 3.0), step=0.05, max_step=0.3)
    return continue_starts(base, [("small", SMALL, 1), ("large", LARGE, 1)], 1.0, settings)


def test_small_and_large_orbits_and_the_saddle_are_one_branch_folding_twice(fold_branch):
    branches, fates = fold_branch
    assert fates == {"small": "traced", "large": "on branch small"}
    (branch,) = branches
    folds = [e for e in branch.events if e.kind == "fold"]
    assert [e.kind for e in branch.events] == ["fold", "fold"]
    for e in folds:  # one multiplier on +1, the other e^(-c T) (trace of J is -c)
        mu = np.sort(np.abs(e.point.multipliers))
        assert mu[1] == pytest.approx(1.0, abs=1e-8)
        assert mu[0] == pytest.approx(np.exp(-0.05 * 2 * np.pi / 1.3), abs=1e-8)
    stable = np.array([p.stable for p in branch.points])
    runs = np.flatnonzero(np.diff(stable.astype(int)))
    assert len(runs) == 2 and stable[0] and stable[-1]  # stable, saddle (dashed), stable
    residuals = [np.max(np.abs(p.value.residual)) for p in branch.points]
    assert max(residuals) < 1e-10


def test_folds_are_where_brute_force_sweeps_jump(fold_branch):
    (branch,), _ = fold_branch
    upper, lower = sorted(e.point.parameter for e in branch.events)[::-1]
    integ = IntegratorSettings()
    up = sweep(BODY, VALUES, integ, "F", sweep_values(0.2, 3.0, 1.0, 0.01, True), SMALL)
    down = sweep(BODY, VALUES, integ, "F", sweep_values(0.55, 3.0, 1.0, 0.01, False), LARGE)
    ((a, b),) = jumps(up)
    assert a < upper < b  # the small orbit jumps up past the upper fold only
    ((a, b),) = jumps(down)
    assert b < lower < a
    assert (upper, lower) == (pytest.approx(2.5655883, abs=1e-6),
                              pytest.approx(0.6188944, abs=1e-6))


def test_folds_agree_with_harmonic_balance(fold_branch):
    """One-harmonic balance x = A sin(wt - theta) gives
    F^2 = A^2 [(k1 - w^2 + 3/4 k2 A^2)^2 + (c w)^2]; its folds are where dF^2/dA^2 = 0:
    3 b^2 u^2 + 4 a b u + a^2 + (c w)^2 = 0 (u = A^2, a = k1 - w^2, b = 3/4 k2). The
    neglected third harmonic is about k2 A^2 / (4 (9 w^2 - k1)) ~ 2% of A here."""
    (branch,), _ = fold_branch
    c, k1, k2, w = 0.05, 1.0, 0.01, 1.3
    a, b = k1 - w ** 2, 0.75 * k2
    u = np.roots([3 * b ** 2, 4 * a * b, a ** 2 + (c * w) ** 2])
    hb = np.sort(np.sqrt(u * ((a + b * u) ** 2 + (c * w) ** 2)))
    hb_amp = np.sqrt(u)[np.argsort(np.sqrt(u * ((a + b * u) ** 2 + (c * w) ** 2)))]
    folds = sorted(branch.events, key=lambda e: e.point.parameter)
    for e, f_hb, a_hb in zip(folds, hb, hb_amp, strict=True):
        assert e.point.parameter == pytest.approx(f_hb, rel=0.05)
        problem = Problem(BODY, {**VALUES, "F": e.point.parameter}, SHOOTING)
        amp = _amplitude(problem, e.point.state)
        assert amp == pytest.approx(a_hb, rel=0.03)


def _amplitude(problem, y, samples=400):
    T = problem.period
    xs = [flow(problem, y, 0.0, T * k / samples)[1][0] for k in range(1, samples + 1)]
    return 0.5 * (max(xs) - min(xs))


def test_going_back_along_the_branch_retraces_it():
    orbit_map = OrbitMap(BODY, VALUES, "F", 1)
    settings = Settings((1.0, 2.0), step=0.05, max_step=0.2, tol=1e-11)
    first = start_point(orbit_map, SMALL, 1.0, 1e-11)
    forth = follow(orbit_map, first, settings, +1.0)
    assert forth.end == "parameter bound 2"
    end = forth.points[-1]
    back = follow(orbit_map, start_point(orbit_map, end.state, 2.0, 1e-11), settings, -1.0)
    assert back.end == "parameter bound 1"
    assert np.max(np.abs(back.points[-1].u - first.u)) < 1e-10
    # every point of the way back is the forward branch's orbit at its F (Newton at fixed
    # F from the nearest forward point converges to it)
    lam = np.array([p.parameter for p in forth.points])
    for p in back.points[1:-1]:
        near = forth.points[int(np.argmin(np.abs(lam - p.parameter)))]
        again = start_point(orbit_map, near.state, p.parameter, 1e-11)
        assert np.max(np.abs(again.u - p.u)) < 1e-10


PAIR = get_system("duffing", 2)
FIG07 = {**PAIR.defaults(), "phi": 5 * np.pi / 8, "k_c": 8.0, "c_c": 20.0}
# a stable impacting period-1 orbit of the figure-7 pair at d = 10.2085108944790
IMPACTING = (10.208510894479076, np.array([-0.20540045525227107, -1.9237780956983228,
                                           -4.130717652399685, 10.039799474535227]))


def test_salted_monodromy_matches_finite_differences_of_the_flow():
    d, y = IMPACTING
    problem = Problem(PAIR, {**FIG07, "d": d}, SHOOTING)
    value = OrbitMap(PAIR, {**FIG07, "d": d}, "d", 1).evaluate(y, d)
    assert value.max_g > 0 and np.max(np.abs(value.residual)) < 1e-9
    salted = salted_monodromy(problem, y, 1)
    reference = finite_difference_monodromy(problem, y, 0.0, 1)
    assert np.max(np.abs(salted - reference)) < 1e-5
    assert np.max(np.abs(value.monodromy - salted)) == 0.0
    plain = OrbitMap(PAIR, {**FIG07, "d": d}, "d", 1)
    from softimpact_cli.analysis.engine import flow as plain_flow
    from softimpact_cli.systems.variational import (
        initial_variational_state,
        variational_system,
    )
    var = Problem(variational_system(PAIR), plain.problem(d).values, SHOOTING)
    z = plain_flow(var, initial_variational_state(y), 0.0, problem.period)[1]
    assert np.max(np.abs(z[4:].reshape(4, 4) - reference)) > 1e-2  # saltation matters


def test_period_doubling_of_the_bilinear_body_switches_onto_the_doubled_branch():
    """The single bilinear body (w = 0.86): its period-1 orbit doubles as F rises; on the
    doubled branch the orbit is a fixed point of P^2 and not of P."""
    body = get_system("bilinear", 1)
    values = body.defaults()
    base = OrbitMap(body, values, "F", 1)
    settings = Settings((0.3, 0.518), step=0.02, max_step=0.05)
    branches, _ = continue_starts(base, [("p1", np.array([0.1276, 1.0268]), 1)], 0.518,
                                  settings, switch_depth=1)
    parent, doubled = branches
    (pd,) = [e for e in parent.events if e.kind == "period doubling"]
    assert pd.point.parameter == pytest.approx(0.330735320, abs=1e-8)
    assert np.min(np.abs(pd.point.multipliers + 1.0)) < 1e-8
    assert doubled.periods == 2 and doubled.parent == 0
    point = doubled.points[-1]
    once = base.image(point.state, point.parameter)[1]
    twice = base.with_periods(2).image(point.state, point.parameter)[1]
    assert np.max(np.abs(twice - point.state)) < 1e-9
    assert np.max(np.abs(once - point.state)) > 1e-3


def test_grazing_points_along_d_are_the_critical_distances():
    """Figure 7's scene (phi = 5 pi/8): a non-impacting combination is flat in d until
    max(x1 - x2) = d; the located grazing equals its critical distance (dcrit kind's
    computation on the uncoupled orbit) to 1e-8, and the branch goes on impacting."""
    from softimpact_cli.analysis.catalogue import body_catalogue, body_problem, sample_states
    from softimpact_cli.analysis.critical_distance import critical_distances

    integ = IntegratorSettings()
    left, _ = body_catalogue(body_problem(PAIR, FIG07, integ),
                             sample_states({"x": (-12, 12), "v": (-12, 12)}, 6, 30, 1))
    reference = critical_distances(PAIR, FIG07, left, np.array([FIG07["phi"]]))
    names = [str(n) for n in reference["combination_label"].values]
    d_crit = dict(zip(names, reference["d_crit"].values[:, 0], strict=True))
    from softimpact_cli.analysis.catalogue import combinations, right_attractors

    right = right_attractors(body_problem(PAIR, FIG07, integ), left, FIG07["phi"],
                             PAIR.extra["right_sign"], PAIR.extra["right_phase"])
    combo = next(c for c in combinations(left, right) if c.name == "L1^2 R1-0^2")
    base = OrbitMap(PAIR, {**FIG07, "d": 22.5}, "d", 1)
    settings = Settings((16.0, 22.5), step=0.1, max_step=0.5, max_points=80)
    (branch,), _ = continue_starts(base, [(combo.name, combo.orbit[0], 1)], 22.5, settings,
                                   switch_depth=0)
    grazings = [e for e in branch.events if e.kind == "grazing"]
    assert grazings
    assert grazings[0].point.parameter == pytest.approx(d_crit["L1^2 R1-0^2"], abs=1e-8)
    after = [p for p in branch.points if p.parameter < grazings[0].point.parameter]
    assert after and all(p.impacting for p in after)


UEDA = {**BODY.defaults(), "c": 0.05, "k1": 0.0, "k2": 1.0, "F": 5.0, "w": 1.0}
UEDA_P2 = np.array([0.79271067, 0.73734594])  # its period-2 orbit at F = 5 (t = 0)


def _period_four_split(F: float, y: np.ndarray) -> tuple[float, np.ndarray]:
    """Brute force: iterate P^4 from y until it settles (1e-12), return the distance of
    x between the orbit's points two periods apart (0 on a period-2 orbit) and the end."""
    problem = Problem(BODY, {**UEDA, "F": F}, SHOOTING)
    T = problem.period
    for _ in range(5000):
        y4 = flow(problem, y, 0.0, 4 * T)[1]
        if np.max(np.abs(y4 - y)) < 1e-12:
            break
        y = y4
    return abs(flow(problem, y, 0.0, 2 * T)[1][0] - y[0]), y


def test_period_doubling_cascade_of_ueda_matches_a_brute_force_estimate():
    """Ueda's oscillator x'' + 0.05 x' + x^3 = F sin t: a period-1 orbit doubles to the
    period-2 one, which doubles to period 4, and that one to period 8 as F rises. The
    brute-force estimate of the second doubling: the split s of the period-4 orbit found
    by plain iteration (no Newton, no monodromy) at five F beyond the doubling,
    s^2 = a (F - F_PD) + b (F - F_PD)^2 fitted and solved."""
    base = OrbitMap(BODY, UEDA, "F", 1)
    settings = Settings((4.7, 5.4), step=0.02, max_step=0.05)
    branches, _ = continue_starts(base, [("P2", UEDA_P2, 2)], 5.0, settings, switch_depth=2)
    period_two = branches[0]
    # going down, the period-2 branch ends on the period-1 orbit it doubled from, whose
    # multiplier is -1 there (the pitchfork of P^2 seen from the doubled branch)
    assert period_two.ends[0] == "meets the orbit it doubled from"
    (origin,) = [e for e in period_two.events if e.kind == "doubling origin"]
    assert origin.point.parameter == pytest.approx(4.7551195, abs=1e-6)
    mother = base.evaluate(origin.point.state, origin.point.parameter)
    assert np.max(np.abs(mother.residual)) < 1e-9  # a fixed point of P itself
    assert np.min(np.abs(np.linalg.eigvals(mother.monodromy) + 1.0)) < 1e-5
    (pd,) = [e for e in period_two.events if e.kind == "period doubling"]
    assert np.min(np.abs(pd.point.multipliers + 1.0)) < 1e-8
    fourth = [b for b in branches if b.periods == 4]
    eighth = [b for b in branches if b.periods == 8]
    assert fourth and eighth  # the cascade: 2 -> 4 -> 8, each switched onto
    (pd4,) = [e for e in fourth[0].events if e.kind == "period doubling"]
    assert pd.point.parameter < pd4.point.parameter < 5.4
    lam = pd.point.parameter
    offsets = np.array([0.01, 0.008, 0.006, 0.004, 0.002])
    y, squares = pd.point.state + 0.01, []
    for delta in offsets:  # from far to near: each from the last end state
        s, y = _period_four_split(lam + delta, y)
        squares.append(s ** 2)
    fit = np.polyfit(offsets, squares, 2)  # in delta = F - F_PD(continuation)
    roots = np.roots(fit).real
    estimate = lam + roots[np.argmin(np.abs(roots))]
    assert abs(estimate - lam) < 1e-6
    assert squares[-1] > 1e-4  # a genuine period-4 orbit, not the period-2 one


def test_test_functions_vanish_exactly_where_their_multipliers_say():
    from softimpact_cli.analysis.continuation_events import multiplier_tests

    theta = 0.7
    fold, pd, ns = multiplier_tests(np.array([1.0, 0.5]))
    assert fold == 0.0 and pd == pytest.approx(3.0) and ns == pytest.approx(-0.5)
    assert multiplier_tests(np.array([-1.0, 0.3]))[1] == 0.0
    on_circle = np.array([np.exp(1j * theta), np.exp(-1j * theta), 0.5, 0.2])
    assert abs(multiplier_tests(on_circle)[2]) < 1e-15  # a complex pair on |mu| = 1
    inside = np.array([0.9 * np.exp(1j * theta), 0.9 * np.exp(-1j * theta), 0.5, 0.2])
    outside = np.array([1.1 * np.exp(1j * theta), 1.1 * np.exp(-1j * theta), 0.5, 0.2])
    assert multiplier_tests(inside)[2] * multiplier_tests(outside)[2] < 0
    # fold and period-doubling tests keep their sign while the pair crosses the circle
    assert multiplier_tests(inside)[0] * multiplier_tests(outside)[0] > 0
    assert multiplier_tests(inside)[1] * multiplier_tests(outside)[1] > 0


def test_folds_of_the_frequency_response_agree_with_harmonic_balance():
    """Continued in w (the stroboscopic period 2 pi / w moves with it) at F = 1: the
    resonance curve bends over and folds twice; one-harmonic balance puts the folds
    where w(A) from (k1 - w^2 + 3/4 k2 A^2)^2 + (c w)^2 = F^2 / A^2 turns."""
    base = OrbitMap(BODY, VALUES, "w", 1)
    settings = Settings((0.8, 2.0), step=0.05, max_step=0.3)
    (branch,), _ = continue_starts(base, [("small", SMALL, 1)], 1.3, settings)
    folds = sorted(e.point.parameter for e in branch.events if e.kind == "fold")
    c, k1, F, b = 0.05, 1.0, 1.0, 0.75 * 0.01
    A = np.linspace(0.5, 20.0, 200_001)
    p = k1 + b * A ** 2  # W = w^2 solves W^2 - (2p - c^2) W + p^2 - F^2/A^2 = 0
    disc = (2 * p - c ** 2) ** 2 - 4 * (p ** 2 - F ** 2 / A ** 2)
    w = np.sqrt(((2 * p - c ** 2) + np.sqrt(np.clip(disc, 0, None))) / 2)[disc >= 0]
    turns = np.flatnonzero(np.diff(np.sign(np.diff(w))) != 0) + 1
    assert len(folds) == 2 and len(turns) == 2
    assert folds == pytest.approx(sorted(w[turns]), rel=0.01)
