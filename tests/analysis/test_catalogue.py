"""The attractor catalogue: periodic orbits, multipliers, right body, combinations, labels."""

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import (
    SHOOTING,
    body_problem,
    catalogue_dataset,
    catalogue_from_dataset,
    label_orbit,
    sample_states,
)
from softimpact_cli.analysis.engine import Problem, classify_state, flow
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.store.catalogues import build_catalogue
from softimpact_cli.systems import get_system

BILINEAR = dict(c=0.02, k1=1.0, k2=29.0, F=0.518, w=0.86, d1=1.26, d=100.0, phi=0.7, k_c=8.0,
                c_c=10.0, law="paper")
DUFFING = dict(c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3, d=100.0, phi=2.0, k_c=8.0, c_c=10.0,
               law="paper")


@pytest.fixture(scope="module")
def bilinear_catalogue():
    states = sample_states({"x": (-3, 3), "v": (-3, 3)}, 8, 40, seed=3)
    return build_catalogue(get_system("bilinear", 2), BILINEAR, IntegratorSettings(), states)


@pytest.fixture(scope="module")
def duffing_catalogue():
    states = sample_states({"x": (-12, 12), "v": (-12, 12)}, 8, 40, seed=3)
    return build_catalogue(get_system("duffing", 2), DUFFING, IntegratorSettings(), states)


def test_bilinear_structure(bilinear_catalogue):
    cat = bilinear_catalogue
    assert [(a.name, a.period) for a in cat.attractors] == [("L2^1", 2), ("L5^2", 5)]
    # 2-2: gcd 2 shifts; 2-5 and 5-2: one each; 5-5: five
    assert len(cat.combinations) == 2 + 1 + 1 + 5
    assert sum(cat.counts.values()) == cat.n_samples
    assert all(a.stable for a in cat.attractors)


def test_duffing_structure(duffing_catalogue):
    cat = duffing_catalogue
    assert [a.period for a in cat.attractors] == [1, 1]
    small, large = cat.attractors
    assert small.amplitude < 2.0 < 8.0 < large.amplitude  # 1 = small, 2 = large
    assert [c.name for c in cat.combinations] == [
        "L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1", "L1^2 R1-0^2"]


@pytest.mark.parametrize("which", ["bilinear", "duffing"])
def test_refined_orbits_are_periodic_to_1e10(which, bilinear_catalogue, duffing_catalogue):
    cat = bilinear_catalogue if which == "bilinear" else duffing_catalogue
    values = BILINEAR if which == "bilinear" else DUFFING
    tight = body_problem(get_system(which, 2), values, SHOOTING.__class__(
        method="dopri5", rtol=1e-13, atol=1e-14))
    T = tight.period
    for a in cat.attractors:
        assert a.residual < 1e-10
        for i, point in enumerate(a.points):
            status, y, _ = flow(tight, point, 0.0, a.period * T)
            assert status == 0
            assert np.max(np.abs(y - point)) < 1e-10, (a.name, i)
            # consecutive canonical points are map images of each other
            _, nxt, _ = flow(tight, point, 0.0, T)
            assert np.max(np.abs(nxt - a.points[(i + 1) % a.period])) < 1e-9
        assert np.argmax(a.points[:, 0]) == 0  # canonical: point 0 has the largest x


def test_multipliers_match_decay_of_nearby_trajectories(bilinear_catalogue, duffing_catalogue):
    for cat, values, model in ((bilinear_catalogue, BILINEAR, "bilinear"),
                               (duffing_catalogue, DUFFING, "duffing")):
        problem = body_problem(get_system(model, 2), values, SHOOTING)
        T = problem.period
        for a in cat.attractors:
            x_star = a.points[0]
            y = x_star + np.array([1e-3, -1e-3])
            logs = []
            for _ in range(max(8, 60 // a.period)):
                _, y, _ = flow(problem, y, 0.0, a.period * T)
                logs.append(np.log(np.max(np.abs(y - x_star))))
            n = np.arange(len(logs))
            rate = np.exp(np.polyfit(n[len(n) // 3:], logs[len(n) // 3:], 1)[0])
            assert rate == pytest.approx(np.max(np.abs(a.multipliers)), rel=0.02), a.name


def test_right_body_points_solve_the_right_equation(bilinear_catalogue):
    """Right attractors come from the mirror transform; check them against the pair."""
    cat = bilinear_catalogue
    pair = Problem(get_system("bilinear", 2), BILINEAR, SHOOTING)
    T = pair.period
    for combo in cat.combinations:
        q = combo.orbit.shape[0]
        status, y, max_g = flow(pair, combo.orbit[0], 0.0, q * T)
        assert status == 0 and max_g < 0  # no contact at d = 100
        assert np.max(np.abs(y - combo.orbit[0])) < 1e-9, combo.name
        _, y1, _ = flow(pair, combo.orbit[0], 0.0, T)
        assert np.max(np.abs(y1 - combo.orbit[1 % q])) < 1e-9, combo.name


def test_every_bilinear_combination_is_labelled_as_itself(bilinear_catalogue):
    cat = bilinear_catalogue
    pair = Problem(get_system("bilinear", 2), BILINEAR, IntegratorSettings())
    for combo in cat.combinations:
        for start in (0, combo.orbit.shape[0] - 1):
            cls = classify_state(pair, combo.orbit[start], 0.0)
            assert cls.status == 0 and cls.period == combo.orbit.shape[0]
            assert not cls.impacting
            assert label_orbit(cat, cls.orbit, cls.impacting).name == combo.name


def test_dataset_round_trip(bilinear_catalogue):
    system = get_system("bilinear", 2)
    ds = catalogue_dataset(bilinear_catalogue, system, IntegratorSettings())
    back = catalogue_from_dataset(ds)
    assert [c.name for c in back.combinations] == [c.name for c in
                                                   bilinear_catalogue.combinations]
    for a, b in zip(back.attractors, bilinear_catalogue.attractors, strict=True):
        assert np.array_equal(a.points, b.points) and a.name == b.name
    assert ds["attractor_curve"].notnull().sum() > 0


def test_duffing_catalogue_stable_under_more_samples_and_tighter_tolerance(duffing_catalogue):
    states = sample_states({"x": (-12, 12), "v": (-12, 12)}, 12, 80, seed=4)
    tighter = IntegratorSettings(rtol=5e-9, atol=5e-11, convergence_tol=5e-7)
    again = build_catalogue(get_system("duffing", 2), DUFFING, tighter, states)
    assert [a.name for a in again.attractors] == [a.name for a in duffing_catalogue.attractors]
    for a, b in zip(again.attractors, duffing_catalogue.attractors, strict=True):
        assert np.max(np.abs(a.points - b.points)) < 1e-8
        assert a.amplitude == pytest.approx(b.amplitude, rel=1e-6)
