"""Continuation on chains (analysis/continuation*.py with a chain's surfaces), against
independent references:

(a) stops that never engage: the chain's branch is the product of the single Duffing
    body's branches (each body's state a fixed point of the preset body's map, the
    multipliers the union of the bodies', the folds the body's own folds), and a body's
    period doubling is the chain's, switched onto;
(b) an impacting branch (two stops, one a wall, and a kink): the salted monodromy against
    central differences of the stroboscopic map, wherever the section point lies off
    every switching surface (on one, the map itself has a corner);
(c) grazing of each stop, located where chain_dcrit's critical value of the non-impacting
    orbit equals the stop's gap or wall.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.chain_dcrit import (
    TIGHT,
    Product,
    critical_values,
    uncoupled_values,
)
from softimpact_cli.analysis.continuation import Settings, follow, section_corner, start_point
from softimpact_cli.analysis.continuation_branches import continue_starts
from softimpact_cli.analysis.continuation_dataset import continuation_dataset
from softimpact_cli.analysis.engine import Problem, flow
from softimpact_cli.analysis.lyapunov import finite_difference_monodromy
from softimpact_cli.analysis.shooting import SHOOTING, OrbitMap
from softimpact_cli.systems import get_system
from softimpact_cli.systems.chain import ChainModel, Kink, Stop, chain_system, chain_values
from softimpact_cli.systems.variational import initial_variational_state, variational_system

BODY = get_system("duffing", 1)
SMALL = np.array([-0.14175511, -1.90995831])  # near the body's small P1 orbit (F = 1, w = 1.3)
FORCES = (1.0, 0.3)  # body 1 folds twice in w within [1.15, 1.6], body 2 not at all


def _sorted(mu: np.ndarray) -> np.ndarray:
    return np.sort_complex(np.round(np.asarray(mu, dtype=complex), 9))


def test_a_chain_whose_stop_never_engages_continues_as_the_product_of_its_bodies():
    model = ChainModel(2, stops=(Stop(1, 2),))
    values = chain_values(model, 1.3, {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": list(FORCES),
                                       "phi": 0.0}, stop_values=[{"d": 50.0}])
    chain = OrbitMap(chain_system(model), values, "w", 1)
    settings = Settings((1.15, 1.6), step=0.05, max_step=0.3)
    (branch,), fates = continue_starts(chain, [("product", np.concatenate(
        [SMALL, FORCES[1] * SMALL]), 1)], 1.3, settings)
    assert fates == {"product": "traced"}
    assert branch.ends == ("parameter bound 1.15", "parameter bound 1.6")
    bodies = [OrbitMap(BODY, {**BODY.defaults(), "F": f}, "w", 1) for f in FORCES]
    for point in branch.points[::4]:
        assert not point.impacting and np.all(point.stop_gaps < -30.0)
        union = []
        for i, body in enumerate(bodies):
            own = body.evaluate(point.state[2 * i: 2 * i + 2], point.parameter,
                                parameter_derivative=False)
            assert np.max(np.abs(own.residual)) < 1e-9  # each body on its own orbit
            union.extend(np.linalg.eigvals(own.monodromy))
        np.testing.assert_allclose(_sorted(point.multipliers), _sorted(union), atol=2e-8)
    # the single body's own continuation (the preset): its folds are the chain's
    (alone,), _ = continue_starts(bodies[0], [("small", SMALL, 1)], 1.3, settings)
    own_folds = sorted(e.point.parameter for e in alone.events if e.kind == "fold")
    chain_folds = sorted(e.point.parameter for e in branch.events if e.kind == "fold")
    assert len(own_folds) == 2 and [e.kind for e in branch.events] == ["fold", "fold"]
    assert chain_folds == pytest.approx(own_folds, abs=1e-8)
    for e in branch.events:  # a multiplier on +1, the other three the bodies' others
        assert np.min(np.abs(e.point.multipliers - 1.0)) < 1e-7


UEDA_P2 = np.array([0.79271067, 0.73734594])  # Ueda's period-2 orbit at F = 5 (t = 0)


def test_a_period_doubling_of_one_body_is_the_chains_and_is_switched_onto():
    """Body 2 is Ueda's oscillator (x'' + 0.05 x' + x^3 = F.2 sin t), body 1 a linear one,
    the stop far apart: along F.2 the chain's period-2 product doubles where the single
    body's own continuation doubles (multiplier -1), and the switched branch holds
    fixed points of P^4 that are not fixed points of P^2, body 1 still on its orbit."""
    model = ChainModel(2, stops=(Stop(1, 2),))
    values = chain_values(model, 1.0, {"c": 0.05, "k1": [2.0, 0.0], "k2": [0.0, 1.0],
                                       "F": [0.2, 5.0], "phi": 0.0},
                          stop_values=[{"d": 50.0}])
    chain = OrbitMap(chain_system(model), values, "F.2", 1)
    settings = Settings((5.0, 5.3), step=0.02, max_step=0.05)
    start = np.concatenate([np.zeros(2), UEDA_P2])
    branches, _ = continue_starts(chain, [("product", start, 2)], 5.0, settings,
                                  switch_depth=1)
    ueda = OrbitMap(BODY, {**BODY.defaults(), "c": 0.05, "k1": 0.0, "k2": 1.0, "F": 5.0,
                           "w": 1.0}, "F", 1)
    (alone,), _ = continue_starts(ueda, [("P2", UEDA_P2, 2)], 5.0, settings, switch_depth=0)
    (own,) = [e.point.parameter for e in alone.events if e.kind == "period doubling"]
    parent, doubled = branches
    (pd,) = [e for e in parent.events if e.kind == "period doubling"]
    assert pd.point.parameter == pytest.approx(own, abs=1e-8)
    assert np.min(np.abs(pd.point.multipliers + 1.0)) < 1e-8
    assert doubled.periods == 4 and doubled.parent == 0
    point = doubled.points[-1]
    twice = chain.with_periods(2).image(point.state, point.parameter)[1]
    four = chain.with_periods(4).image(point.state, point.parameter)[1]
    assert np.max(np.abs(four - point.state)) < 1e-9
    assert np.max(np.abs(twice - point.state)) > 1e-3
    assert np.max(np.abs(twice[:2] - point.state[:2])) < 1e-9  # body 1: period 1


IMPACTING = ChainModel(2, kinks=(Kink(1, "left"),), stops=(Stop(1, 2), Stop(2, 0, "left")))


def impacting_values() -> dict:
    return chain_values(IMPACTING, 1.3, {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": [1.0, 0.5],
                                         "phi": [0.0, 2.0]}, kinks=[{"x": -0.5, "k": 2.0}],
                        stop_values=[{"d": 0.5, "k_c": 8.0, "c_c": 2.0},
                                     {"wall": -0.9, "k_c": 8.0, "c_c": 2.0}])


# an impacting period-1 orbit at phi.2 = 2 (stop 1 engaged once a period, the kink crossed)
IMPACTING_START = np.array([-1.74602951, -1.14065545, -0.15170035, -0.9600022])


@pytest.mark.slow
def test_an_impacting_branchs_monodromy_is_the_derivative_of_the_stroboscopic_map():
    """Followed down in phi.2 from 2, the branch grazes the wall (stop 2), folds, comes
    back with both stops engaged, crosses the corner where its section point crosses stop
    2's surface, folds again and goes down to the bound: at each point whose section lies
    off every surface (by 1e-3) the salted monodromy equals the central differences of P
    to 1e-6, while the variational flow without saltation is far from it."""
    system = chain_system(IMPACTING)
    orbit_map = OrbitMap(system, impacting_values(), "phi.2", 1)
    settings = Settings((1.7, 2.0), step=0.05, max_step=0.2, max_points=60,
                        cross_corners=True)
    (branch,), _ = continue_starts(orbit_map, [("impacting", IMPACTING_START, 1)], 2.0,
                                   settings, switch_depth=0)
    assert branch.ends == ("parameter bound 1.7", "parameter bound 2")
    kinds = [(e.kind, e.stop) for e in branch.events]
    assert sorted(kinds) == [("fold", 0), ("fold", 0), ("grazing", 2)]
    for fold in (e for e in branch.events if e.kind == "fold"):
        assert np.min(np.abs(fold.point.multipliers - 1.0)) < 1e-6
    stable = [p.stable for p in branch.points]
    assert stable[0] and stable[-1] and not all(stable)  # stable, unstable, stable
    corners = [i for i in range(len(branch.points) - 1)
               if section_corner(orbit_map, branch.points[i].u, branch.points[i + 1].u)]
    assert len(corners) == 1  # the section point crossed stop 2's surface once
    both = [p for p in branch.points if np.all(p.stop_gaps > 0.05)]
    assert both, "the branch comes back with both stops engaged"
    checked = 0
    for point in branch.points[::3] + both[-1:]:
        problem = orbit_map.problem(point.parameter)
        off = np.min(np.abs(problem.surfaces.A @ point.state + problem.surfaces.b))
        if off < 1e-3:
            continue
        reference = finite_difference_monodromy(problem, point.state, 0.0, 1)
        assert np.max(np.abs(point.value.monodromy - reference)) < 1e-6
        checked += 1
    assert checked >= 6
    last = both[-1]
    var = Problem(variational_system(system), orbit_map.problem(last.parameter).values,
                  SHOOTING)
    plain = flow(var, initial_variational_state(last.state), 0.0, var.period)[1][4:]
    assert np.max(np.abs(plain.reshape(4, 4) - last.value.monodromy)) > 1e-2


# the unstable impacting orbit between the branch's two folds at phi.2 = 1.87 (both stops
# engaged; its section point reaches stop 2's surface near phi.2 = 1.915)
MIDDLE = np.array([-2.021846440957898, -1.4972851505335925, -0.5364178306508768,
                   -1.4671759760229692])


def test_the_presets_step_control_ends_at_a_corner_that_chains_cross():
    """From the unstable orbit up in phi.2: with the presets' step control the leg ends
    where its section point reaches stop 2's surface; crossing corners, it passes it
    (the tangent turning by ~60 degrees there) and reaches the fold beyond."""
    orbit_map = OrbitMap(chain_system(IMPACTING), impacting_values(), "phi.2", 1)
    first = start_point(orbit_map, MIDDLE, 1.87, 1e-10)
    assert first is not None and not first.stable
    legs = {}
    for cross in (False, True):
        settings = Settings((1.7, 1.95), step=0.05, min_step=1e-4, max_step=0.2,
                            max_points=12, cross_corners=cross)
        legs[cross] = follow(orbit_map, first, settings, +1.0)
        crossed = [section_corner(orbit_map, a.u, b.u) for a, b in
                   zip(legs[cross].points[:-1], legs[cross].points[1:], strict=True)]
        assert crossed.count(True) == int(cross)
    assert legs[False].end == "step too small" and legs[True].end == "max points"
    # across the corner the branch goes on to its fold (it turns back in phi.2)
    lam = [p.parameter for p in legs[True].points]
    assert max(lam) > max(p.parameter for p in legs[False].points) and lam[-1] < max(lam)


GRAZING = ChainModel(2, stops=(Stop(1, 2), Stop(2, 0, "left")))


def grazing_values(d: float, wall: float, force: float) -> dict:
    return chain_values(GRAZING, 1.3, {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": [1.0, force],
                                       "phi": [0.0, 2.0]},
                        stop_values=[{"d": d, "k_c": 8.0, "c_c": 2.0},
                                     {"wall": wall, "k_c": 8.0, "c_c": 2.0}])


def dcrit_of(system, values: dict, state: np.ndarray) -> np.ndarray:
    """chain_dcrit's critical values (every stop) of the uncoupled orbit through state."""
    problem = Problem(system, uncoupled_values(system, values), TIGHT)
    return critical_values(problem, Product((), (0,), np.asarray(state)[None, :]))


def test_grazing_along_a_gap_is_its_critical_value():
    """Along stop 1's gap the non-impacting orbit does not move: the branch grazes where
    the gap equals chain_dcrit's critical value, and goes on impacting below it."""
    system = chain_system(GRAZING)
    values = grazing_values(2.0, -1.2, 0.5)
    orbit_map = OrbitMap(system, values, "stop.1.d", 1)
    first = start_point(orbit_map, np.concatenate([SMALL, 0.5 * SMALL]), 2.0, 1e-11)
    critical = dcrit_of(system, values, first.state)
    assert critical[0] < 2.0 and critical[1] > -1.2  # apart at the start
    settings = Settings((1.85, 2.0), step=0.05, max_step=0.1, max_points=8)
    (branch,), _ = continue_starts(orbit_map, [("product", first.state, 1)], 2.0, settings,
                                   switch_depth=0)
    grazing = [e for e in branch.events if e.kind == "grazing"]
    assert [e.stop for e in grazing] == [1]
    assert grazing[0].point.parameter == pytest.approx(critical[0], abs=1e-8)
    below = [p for p in branch.points if p.parameter < critical[0] - 1e-6]
    assert below and all(p.impacting and p.stop_gaps[0] > 0 for p in below)


def test_grazing_of_a_wall_along_a_bodys_forcing_is_where_its_critical_value_reaches_it():
    """Along F.2 the orbit moves: the wall (stop 2) is grazed first, where the critical
    wall position of the orbit there (chain_dcrit, min x_2) is the wall's, and stop 1 is
    still apart; the dataset names the stop."""
    system = chain_system(GRAZING)
    values = grazing_values(2.3, -1.2, 0.75)
    orbit_map = OrbitMap(system, values, "F.2", 1)
    first = start_point(orbit_map, np.concatenate([SMALL, 0.75 * SMALL]), 0.75, 1e-11)
    settings = Settings((0.75, 0.83), step=0.02, max_step=0.04, max_points=6)
    branches, fates = continue_starts(orbit_map, [("product", first.state, 1)], 0.75,
                                      settings, switch_depth=0)
    events = branches[0].events
    assert events[0].kind == "grazing" and events[0].stop == 2
    at = events[0].point
    critical = dcrit_of(system, {**values, "F.2": at.parameter}, at.state)
    assert critical[1] == pytest.approx(-1.2, abs=1e-8) and critical[0] < 2.3
    ds = continuation_dataset(orbit_map, branches, fates, [], 0.75, (0.75, 0.83))
    assert list(ds["stop"].values) == [1, 2] and list(ds["body"].values) == ["x1", "x2"]
    assert int(ds["event_stop"].values[0]) == 2
    assert ds["stop_gap"].values[0, 1] < 0 < ds["stop_gap"].values[-1, 1]
