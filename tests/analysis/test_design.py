"""Control design: region from critical distances, candidates, ranking, and a small
end-to-end design of the Duffing pair checked against the study's figure 6(f) choice."""

import numpy as np
import pytest

from softimpact_cli.analysis.critical_distance import critical_distances
from softimpact_cli.analysis.design import (
    Region,
    candidate_points,
    group_counts,
    halton,
    margins,
    perturbed_points,
    phase_grid,
    ranking,
)
from softimpact_cli.analysis.engine import Problem, flow
from softimpact_cli.analysis.stability import wilson_interval
from softimpact_cli.kernels.codes import IMPACTING_BASE, UNRESOLVED_LABEL
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.report.info import design_summary

# ------------------------------------------------------------------ pure parts


def synthetic_region(points=72):
    """Target curve 1 + sin^2(phi/2), one other at 4 - 2 sin^2(phi): alone where between."""
    phi = phase_grid(points)
    target = 1.0 + np.sin(phi / 2) ** 2
    other = 4.0 - 2.0 * np.sin(phi) ** 2
    return Region(phi, ("T", "O"), np.array([target, other]), 0)


def test_halton_radical_inverse():
    assert [halton(i, 2) for i in (1, 2, 3, 4)] == [0.5, 0.25, 0.75, 0.125]
    assert halton(5, 3) == pytest.approx(2 / 3 + 1 / 9)


def test_region_edges_and_phi_distance():
    region = synthetic_region()
    assert np.allclose(region.low, 1.0 + np.sin(region.phi / 2) ** 2)
    assert np.allclose(region.high, 4.0 - 2.0 * np.sin(region.phi) ** 2)
    inside = region.inside(1.5)
    # d = 1.5 lies above the target curve only where sin^2(phi/2) < 0.5: |phi| < pi/2
    assert inside[region.index(0.2)] and not inside[region.index(np.pi)]
    gap = region.phi_to_boundary(1.5, 0.0)
    step = 2 * np.pi / 72
    assert np.pi / 2 - step <= gap <= np.pi / 2 + step
    assert region.phi_to_boundary(1.5, 2 * np.pi - 0.1) == pytest.approx(
        region.phi_to_boundary(1.5, -0.1))  # circular
    # the whole circle inside at d = 2.1? no: the other curve dips to 2 at pi/2
    assert region.phi_to_boundary(2.5, np.pi) == pytest.approx(np.pi) or \
        not region.inside(2.5).all()


def test_margins_of_a_point():
    region = synthetic_region()
    column = region.d_crit[:, region.index(0.0)]  # target 1, other 4
    m = margins(region, column, 2.0, 0.0)
    assert m["d_to_target"] == pytest.approx(1.0)
    assert m["d_to_boundary"] == pytest.approx(1.0)  # min(2 - 1, 4 - 2)
    assert m["relative"] == pytest.approx(min(0.5, m["phi_to_boundary"] / np.pi))
    outside = margins(region, column, 0.5, 0.0)  # below the target's critical distance
    assert outside["d_to_target"] < 0 and outside["relative"] < 0


def test_candidates_lie_inside_with_margin_and_bounds():
    region = synthetic_region(180)
    bounds = {"d": (1.2, 3.5), "phi": (-1.0, 1.0), "k_c": (2.0, 20.0), "c_c": (5.0, 5.0)}
    pts = candidate_points(region, bounds, 25, 0.05, seed=3)
    assert len(pts) == 25
    for p in pts:
        assert -1.0 <= p["phi"] <= 1.0 and 1.2 <= p["d"] <= 3.5
        assert 2.0 <= p["k_c"] <= 20.0 and p["c_c"] == 5.0
        j = region.index(p["phi"])
        m = margins(region, region.d_crit[:, j], p["d"], p["phi"])
        assert m["relative"] >= 0.05 - 1e-12
    assert pts == candidate_points(region, bounds, 25, 0.05, seed=3)  # reproducible
    assert pts != candidate_points(region, bounds, 25, 0.05, seed=4)
    # a box where the target is never alone gives no candidate
    assert candidate_points(region, {**bounds, "d": (4.1, 5.0)}, 5, 0.0, 0) == []


def test_perturbed_points():
    pick = {"d": 5.0, "phi": 1.0, "k_c": 8.0, "c_c": 0.0}
    pts = perturbed_points(pick, 0.02, 2)
    d = [p["d"] for axis, _, p in pts if axis == "d"]
    assert d == pytest.approx([4.8, 4.9, 5.1, 5.2])
    phi = [p["phi"] for axis, _, p in pts if axis == "phi"]
    assert phi == pytest.approx([1 - 0.04 * np.pi, 1 - 0.02 * np.pi, 1 + 0.02 * np.pi,
                                 1 + 0.04 * np.pi])
    assert not any(axis == "c_c" for axis, _, _ in pts)  # zero: nothing to scale
    assert all(sum(p[a] != pick[a] for a in pick) == 1 for _, _, p in pts)


def test_group_counts():
    names = ("L1^1 R1-0^1", "L1^2 R1-0^2")
    codes = np.array([[0, 0, 1, IMPACTING_BASE + 1, IMPACTING_BASE + 2, UNRESOLVED_LABEL]])
    groups, counts = group_counts(codes, names)
    c = dict(zip(groups, counts[0], strict=True))
    assert c["L1^1 R1-0^1"] == 2 and c["L1^2 R1-0^2"] == 1 and c["impacting (all)"] == 2
    assert c["non-impacting (sum)"] == 3 and c["unresolved"] == 1


def test_ranking_ties_go_to_the_larger_margin():
    n = 100
    target = np.array([90, 100, 99, 100])
    score = target / n
    margin = np.array([0.9, 0.1, 0.5, 0.2])
    order = ranking(score, target, n, margin)
    # 1.00, 0.99 and 1.00 are tied (Wilson half-width at 100/100 is ~0.018): margin
    # decides among them; 0.90 is clearly worse whatever its margin
    assert list(order) == [2, 3, 1, 0]
    lo, hi = wilson_interval(np.array([100]), n)
    assert 0.5 * (hi[0] - lo[0]) < 0.1


# ------------------------------------------------------------------ a small design run

SCENE = """
[system]
model = "duffing"
[analysis]
kind = "design"
target = "L1^1 R1-0^1"
bounds = {d = [3.0, 10.0], phi = ["pi/2", "3*pi/2"], k_c = [4.0, 12.0], c_c = [2.0, 12.0]}
candidates = 6
screen_n = 16
refine = 2
robust_n = 16
phi_points = 24
reference = {d = 5.0, phi = "pi", k_c = 8.0, c_c = 10.0}
seed = 2
[initial_conditions]
kind = "random"
box = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}
n = 48
seed = 15
[catalogue]
grid = 6
random = 20
"""


@pytest.fixture(scope="module")
def small_design():
    from softimpact_cli.sweep.design import run_design

    scene = parse_scene(SCENE, "design.toml")
    return scene, run_design(scene, workers=2)


def test_pick_lies_in_the_region(small_design):
    scene, ds = small_design
    best = design_summary(ds)["best"]
    # independent check: every critical distance at the pick's phase, recomputed
    left = []
    from softimpact_cli.analysis.catalogue import catalogue_from_dataset

    left = list(catalogue_from_dataset(ds).attractors)
    dc = critical_distances(scene.system, dict(scene.values), left, np.array([best["phi"]]))
    names = [str(n) for n in dc["combination_label"].values]
    column = dc["d_crit"].values[:, 0]
    t = names.index("L1^1 R1-0^1")
    assert column[t] < best["d"] < np.delete(column, t).min()
    assert best["margin"]["d_to_target"] == pytest.approx(best["d"] - column[t], abs=1e-8)
    assert 3.0 <= best["d"] <= 10.0 and np.pi / 2 <= best["phi"] <= 3 * np.pi / 2
    assert best["target_exists"] is True


def test_pick_at_least_as_good_as_figure_6f(small_design):
    _, ds = small_design
    s = design_summary(ds)
    best, ref = s["best"], s["reference"]
    assert best["n"] == ref["n"] == 48  # the same samples
    assert (ref["d"], ref["phi"], ref["k_c"], ref["c_c"]) == pytest.approx((5, np.pi, 8, 10))
    half = 0.5 * (ref["ci95"][1] - ref["ci95"][0])
    assert best["share"] >= ref["share"] - half
    assert best["score"] >= max(p["score"] for p in s["runners_up"]) - 0.2
    # the screened points: every one was ranked no better than the pick on its samples
    assert s["screened"] == 6 and len(s["runners_up"]) == 1
    assert len(s["robustness"]) == 8 and all(p["n"] == 16 for p in s["robustness"])


def test_shares_add_up(small_design):
    _, ds = small_design
    groups = [str(g) for g in ds["group"].values]
    single = [j for j, g in enumerate(groups) if "(" not in g]
    total = ds["count"].values[:, single].sum(axis=1)
    assert (total == ds["n_samples"].values).all()
    assert (ds["ci_low"].values <= ds["share"].values + 1e-12).all()
    assert (ds["share"].values <= ds["ci_high"].values + 1e-12).all()


def test_multipliers_are_the_union_of_the_bodies(small_design):
    """At the pick, a finite-difference monodromy of the coupled flow has the eigenvalues
    reported (the union of the two bodies' multipliers)."""
    scene, ds = small_design
    from softimpact_cli.analysis.catalogue import (
        SHOOTING,
        body_problem,
        catalogue_from_dataset,
        combinations,
        right_attractors,
    )

    best = design_summary(ds)["best"]
    point = {k: best[k] for k in ("d", "phi", "k_c", "c_c")}
    values = {**scene.values, **point}
    left = list(catalogue_from_dataset(ds).attractors)
    extra = scene.system.extra
    right = right_attractors(body_problem(scene.system, values, SHOOTING), left, point["phi"],
                             extra["right_sign"], extra["right_phase"])
    combo = next(c for c in combinations(left, right) if c.name == "L1^1 R1-0^1")
    pair = Problem(scene.system, values, SHOOTING)
    x0, T, h = combo.orbit[0], pair.period, 1e-6
    jac = np.column_stack([(flow(pair, x0 + h * e, 0.0, T)[1] - flow(pair, x0 - h * e, 0.0,
                                                                       T)[1]) / (2 * h)
                           for e in np.eye(4)])
    fd = np.linalg.eigvals(jac)
    reported = np.array([complex(*z) for z in best["multipliers"]])
    # each reported multiplier matches a finite-difference one, and vice versa
    assert np.abs(fd[:, None] - reported[None, :]).min(axis=0).max() < 1e-5
    assert np.abs(fd[:, None] - reported[None, :]).min(axis=1).max() < 1e-5
    assert np.all(np.abs(reported) < 1)  # a stable attractor


def test_same_seed_same_design_whatever_the_workers(small_design):
    from softimpact_cli.sweep.design import run_design

    scene, ds = small_design
    again = run_design(scene, workers=1)
    for key in ("point_d", "point_phi", "point_k_c", "point_c_c", "count", "role"):
        assert (again[key].values == ds[key].values).all(), key


def test_unresolved_samples_count_against_the_target():
    """A point where most samples never settle is no better than one where they impact."""
    from softimpact_cli.analysis.design import scores

    groups = ["L1^1 R1-0^1", "impacting (all)", "unresolved"]
    counts = np.array([[10, 0, 90],    # 10% target, the rest unresolved
                       [18, 82, 0],    # 18% target, the rest impacting
                       [10, 90, 0]])
    s = scores(groups, counts, "L1^1 R1-0^1", 100)
    assert s == pytest.approx([-0.8, -0.64, -0.8])
    assert ranking(s, counts[:, 0], 100, np.zeros(3))[0] == 1
