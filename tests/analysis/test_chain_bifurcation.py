"""A chain's bifurcation diagrams (analysis/chain_bifurcation): products followed along a
stop's gap (destroyed at grazing, exactly where the chain starts to touch) and along a
body's forcing (the moving body's points are its own one-body orbit, found apart)."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import refine_orbit
from softimpact_cli.analysis.chain_bifurcation import chain_bifurcation_dataset
from softimpact_cli.analysis.chain_dcrit import (
    TIGHT,
    body_problem,
    chain_products,
    critical_values,
    uncoupled_values,
)
from softimpact_cli.analysis.engine import Problem
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems.chain import ChainModel, Stop, chain_system, chain_values
from tests.analysis.test_chain_dcrit import PHASES, STATES

MODEL = ChainModel(3, stops=(Stop(1, 2), Stop(2, 3)))
SETTINGS = IntegratorSettings(method="dopri5", rtol=1e-10, atol=1e-12)


@pytest.fixture(scope="module")
def chain():
    system = chain_system(MODEL)
    values = chain_values(MODEL, 1.4, {"c": 0.05, "k1": 1.0, "k2": 0.05, "F": 1.5,
                                       "phi": PHASES},
                          stop_values=[{"d": 12.0}, {"d": 12.0}])
    return system, values, chain_products(system, values, STATES)


def test_along_a_gap_each_product_lives_exactly_while_the_gap_exceeds_its_grazing(chain):
    system, values, prods = chain
    steps = np.arange(12.0, 1.9, -1.0)
    ds = chain_bifurcation_dataset(system, values, SETTINGS, prods, "stop.1.d", steps)
    grazing = Problem(system, uncoupled_values(system, values), TIGHT)
    destroyed = 0
    for i, p in enumerate(prods):
        d_crit = critical_values(grazing, p)[0]
        at = float(ds["destroyed_at"].values[i])
        alive = ds["alive"].values[i].astype(bool)
        # the chain itself (its classifier, contacts) says where it touches
        np.testing.assert_array_equal(alive, steps > d_crit)
        if (steps < d_crit).any():
            destroyed += 1
            assert at == pytest.approx(d_crit, abs=1e-12)
            first = int(np.argmin(alive))  # the first step below grazing: it touched, or left
            moved = np.nanmax(np.abs(ds["section_x"].values[i, first, 0, :]
                                     - p.orbit[0, 0::2]))
            assert ds["impacting"].values[i, first] == 1 or moved > 1e-3
            # while alive the points are the product's own, unmoved
            width = p.orbit.shape[0]
            got = ds["section_x"].values[i, alive, :width, :]
            np.testing.assert_allclose(got, np.broadcast_to(
                p.orbit[:, 0::2], got.shape), atol=1e-6)
        else:
            assert np.isnan(at)
    assert destroyed >= 2


def test_along_a_bodys_forcing_its_points_are_its_own_one_body_orbit(chain):
    system, values, prods = chain
    small = [p for p in prods if all(a.amplitude < 3 for a in p.attractors)][0]
    steps = np.array([1.5, 1.4, 1.3])
    ds = chain_bifurcation_dataset(system, values, SETTINGS, [small], "F.2", steps)
    assert ds["alive"].values[0].all() and not ds["impacting"].values[0].any()
    for j, force in enumerate(steps):
        body = body_problem(system, {**values, "F.2": force}, 2, TIGHT)
        x, _, residual = refine_orbit(body, small.attractors[1].points[0], 1)
        assert residual < 1e-9
        assert ds["section_x"].values[0, j, 0, 1] == pytest.approx(x[0], abs=1e-6)
        for b in (0, 2):  # the other bodies do not move
            assert ds["section_x"].values[0, j, 0, b] == pytest.approx(
                small.orbit[0, 2 * b], abs=1e-6)
