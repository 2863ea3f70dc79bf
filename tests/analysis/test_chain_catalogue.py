"""The catalogue of a chain (analysis/chain_catalogue): products of the bodies' orbits,
named with the n-body names, and each stop's critical values deciding which survive.

Independent expectations: a two-body chain's catalogue is the Duffing pair preset's
(names, joint orbits, and survival against the preset's own critical distance); a
three-body chain's products are fixed points of the whole chain's stroboscopic map, and
whether each survives its stops is checked by integrating the chain itself (no contact and
the orbit kept, or contact), also with one stop just beyond and just inside its critical
value.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import (
    body_catalogue,
    body_problem,
    combination_names,
    extend_catalogue,
    label_orbit,
    sample_states,
)
from softimpact_cli.analysis.chain_catalogue import (
    at_values,
    build_chain_catalogue,
    chain_catalogue_dataset,
)
from softimpact_cli.analysis.critical_distance import critical_distance, uncoupled_pair
from softimpact_cli.analysis.engine import Problem, flow, record_trajectory
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems import get_system
from softimpact_cli.systems.chain import ChainModel, Stop, chain_system, chain_values

STATES = sample_states({"x": (-4.0, 4.0), "v": (-4.0, 4.0)}, 4, 0, 0)
SETTINGS = IntegratorSettings()
TIGHT = IntegratorSettings(method="dopri5", rtol=1e-11, atol=1e-12)
BODY = {"c": 0.05, "k1": 1.0, "k2": 0.05, "F": 1.5}
W = 1.4
STOP = {"k_c": 8.0, "c_c": 10.0}

THREE = ChainModel(3, stops=(Stop(1, 2), Stop(2, 3), Stop(3, 0, "left")))


def three_body_values(d1=5.0, d2=6.0, wall=-6.0) -> dict:
    return chain_values(THREE, W, {**{k: [v] * 3 for k, v in BODY.items()},
                                   "phi": [0.0, 5 * np.pi / 8, 5 * np.pi / 4]},
                        stop_values=[{"d": d1, **STOP}, {"d": d2, **STOP},
                                     {"wall": wall, **STOP}])


@pytest.fixture(scope="module")
def three():
    system = chain_system(THREE)
    values = three_body_values()
    return system, values, build_chain_catalogue(system, values, SETTINGS, STATES)


def test_a_pair_chain_has_the_presets_catalogue():
    """Two identical Duffing bodies with one stop between them: the chain's catalogue
    names the preset's combinations (L/R names), with its joint orbits, and a product
    survives exactly when d exceeds the preset's own critical distance."""
    phi, d = np.pi / 2, 4.0
    preset = get_system("duffing", 2)
    pair_values = {**BODY, "w": W, "d": d, "phi": phi, **STOP}
    left, counts = body_catalogue(body_problem(preset, pair_values, SETTINGS), STATES)
    pair = extend_catalogue(preset, pair_values, SETTINGS, left, counts, len(STATES))

    model = ChainModel(2, stops=(Stop(1, 2),))
    system = chain_system(model)
    values = chain_values(model, W, {**{k: [v] * 2 for k, v in BODY.items()},
                                     "phi": [0.0, phi]},
                          stop_values=[{"d": d, **STOP}])
    chain = build_chain_catalogue(system, values, SETTINGS, STATES)

    assert chain.names == pair.names and len(chain.names) == 4  # two P1 attractors each
    for product, combo in zip(chain.products, pair.combinations, strict=True):
        np.testing.assert_allclose(product.orbit, combo.orbit, atol=1e-7)
        d_crit = critical_distance(uncoupled_pair(preset, pair_values, phi), combo.orbit[0],
                                   len(combo.orbit), 256)[0]
        assert chain.critical[chain.names.index(product.name), 0] == pytest.approx(
            d_crit, abs=1e-8)
    survives = dict(zip(chain.names, chain.survives, strict=True))
    assert 0 < sum(survives.values()) < 4  # d = 4 lies among the critical distances
    for combo in pair.combinations:
        d_crit = critical_distance(uncoupled_pair(preset, pair_values, phi), combo.orbit[0],
                                   len(combo.orbit), 256)[0]
        assert survives[combo.name] == (d > d_crit)


def test_products_are_the_chains_non_impacting_solutions(three):
    system, values, cat = three
    assert [len(a) for a in cat.per_body] == [2, 2, 2]
    assert cat.names == combination_names(cat.per_body) and len(cat.names) == 8
    assert cat.names[1] == "B1:P1^1 B2:P1-0^1 B3:P1-0^2"
    free = Problem(system, {**values, "stop.1.d": 1e12, "stop.2.d": 1e12,
                            "stop.3.wall": -1e12}, TIGHT)
    for product in cat.products:  # a fixed point of the uncoupled chain's map, named back
        _, end, _ = flow(free, product.orbit[0], 0.0, free.period)
        assert np.max(np.abs(end - product.orbit[0])) < 1e-8
        assert label_orbit(cat, product.orbit, False).name == product.name


def test_the_stops_decide_which_products_survive_by_brute_force(three):
    """At the scene's stops (gaps 5 and 6, a left wall at -6) half the products survive;
    each is integrated on the chain with its stops: a survivor never touches them and
    stays on its orbit, the others make contact within two periods."""
    system, values, cat = three
    assert 0 < cat.survives.sum() < len(cat.products)
    problem = Problem(system, values, TIGHT)
    for product, survives in zip(cat.products, cat.survives, strict=True):
        run = record_trajectory(problem, product.orbit[0], 0.0, 3, 64)
        if survives:
            assert run.contacts.sum() == 0
            assert np.max(np.abs(run.section_y[-1] - product.orbit[0])) < 1e-8
        else:
            assert run.contacts[:2].sum() >= 1


@pytest.mark.parametrize("stop", [1, 2, 3])
def test_each_stop_just_beyond_or_inside_its_critical_value(three, stop):
    """One stop at its critical value plus or minus 1e-3 (the others out of reach): the
    catalogue says survives, then not, and the chain's integration agrees."""
    system, values, cat = three
    key = f"stop.{stop}.{'wall' if stop == 3 else 'd'}"
    sign = -1.0 if stop == 3 else 1.0  # the left wall's critical position is a minimum
    far = {"stop.1.d": 1e12, "stop.2.d": 1e12, "stop.3.wall": -1e12}
    for k in (0, 3, 6):  # three products of different critical values
        product, crit = cat.products[k], cat.critical[k, stop - 1]
        for offset, expected in ((1e-3, True), (-1e-3, False)):
            at = {**values, **far, key: crit + sign * offset}
            assert bool(at_values(cat, system, at).survives[k]) is expected
            run = record_trajectory(Problem(system, at, TIGHT), product.orbit[0], 0.0, 3, 64)
            assert bool(run.contacts.sum() == 0) is expected


def test_the_dataset_holds_every_body_and_product(three):
    system, _, cat = three
    ds = chain_catalogue_dataset(cat, system)
    assert list(ds["attractor_name"].values) == ["B1:P1^1", "B1:P1^2", "B2:P1^1",
                                                 "B2:P1^2", "B3:P1^1", "B3:P1^2"]
    assert list(ds["combination_name"].values) == list(cat.names)
    assert ds["combination_orbit"].dims == ("combination", "joint_point", "variable")
    assert list(ds["variable"].values) == ["x1", "v1", "x2", "v2", "x3", "v3"]
    np.testing.assert_array_equal(ds["combination_critical"].values, cat.critical)
    np.testing.assert_array_equal(ds["combination_survives"].values, cat.survives)
    assert list(ds["stop_value"].values) == [5.0, 6.0, -6.0]


def test_identical_bodies_number_one_orbit_alike():
    """Three identical double-well Duffing bodies (k1 = -1, k2 = 1) forced at phases 0,
    2 pi/3, 4 pi/3 have the same two in-well P1 orbits, mirror images of one amplitude;
    body i's are body 1's shifted in time by phi_i / w. Each body's attractor number k
    must be body 1's number k: the point of body 1's orbit flowed over that shift lies on
    body i's orbit of the same number (the sampling of max |x|, which differs with the
    phase, decided the order before)."""
    body = {"c": 0.2, "k1": -1.0, "k2": 1.0, "F": 0.1}
    w, phases = 1.0, [0.0, 2 * np.pi / 3, 4 * np.pi / 3]
    model = ChainModel(3, stops=())
    system = chain_system(model)
    values = chain_values(model, w, {**{k: [v] * 3 for k, v in body.items()},
                                     "phi": phases})
    states = sample_states({"x": (-2.0, 2.0), "v": (-2.0, 2.0)}, 5, 0, 0)
    cat = build_chain_catalogue(system, values, SETTINGS, states)
    first = cat.per_body[0]
    assert [a.period for a in first] == [1, 1]  # the two wells
    assert abs(first[0].amplitude - first[1].amplitude) < 1e-9  # mirror images
    one = Problem(get_system("duffing", 1), {**body, "w": w}, TIGHT)
    for i, phi in enumerate(phases[1:], 2):
        assert len(cat.per_body[i - 1]) == 2
        for attractor in first:
            _, shifted, _ = flow(one, attractor.points[0], 0.0, phi / w)
            own = cat.per_body[i - 1][attractor.number - 1]
            assert own.number == attractor.number
            np.testing.assert_allclose(own.points[0], shifted, atol=1e-6)
