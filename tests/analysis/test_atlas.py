"""The atlas's two-parameter curves checked independently of how they are computed:
the augmented system's algebra, a Duffing body's fold curve and its cusp against harmonic
balance, figure 14(c)'s Neimark-Sacker points and their criticality (known by brute force,
tests/analysis/test_neimark_sacker.py) on one NS curve in (c_c, d), with the Chenciner
point between the sub- and supercritical parts."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.atlas import AtlasSettings, Seed, find_seeds, trace_curves
from softimpact_cli.analysis.atlas_augmented import AugmentedMap, bordered_test, borders, compound
from softimpact_cli.analysis.atlas_curves import codimension_two, follow_curve, on_curve, seed
from softimpact_cli.analysis.atlas_normal_form import criticality, supercritical
from softimpact_cli.analysis.continuation import Settings, correct
from softimpact_cli.analysis.continuation_branches import continue_starts
from softimpact_cli.analysis.shooting import OrbitMap
from softimpact_cli.systems import get_system

BODY = get_system("duffing", 1)
VALUES = BODY.defaults()  # c = 0.05, k1 = 1, k2 = 0.01, F = 1, w = 1.3
SMALL = np.array([-0.14175511, -1.90995831])  # the small period-1 orbit at F = 1 (t = 0)
PAIR = get_system("duffing", 2)
FIG14C = {**PAIR.defaults(), "d": 10.5, "phi": 5.28, "k_c": 8.0, "c_c": 4.3}
ORBIT_AT_4_3 = np.array([-9.55833715, -0.23131117, 1.73677921, -1.83088462])  # t = 0


def test_the_compound_matrix_has_the_pairwise_products_as_eigenvalues():
    rng = np.random.default_rng(1)
    M = rng.normal(size=(4, 4))
    mu = np.linalg.eigvals(M)
    products = np.sort_complex(np.array([mu[i] * mu[j] for i in range(4)
                                         for j in range(i + 1, 4)]))
    assert np.sort_complex(np.linalg.eigvals(compound(M))) == pytest.approx(products, abs=1e-10)


def test_the_bordered_test_vanishes_exactly_where_the_matrix_is_singular():
    rng = np.random.default_rng(2)
    Q = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    B, C = borders(Q @ np.diag([2.0, 1.0, 0.3]) @ Q.T)
    values = [bordered_test(Q @ np.diag([2.0, 1.0, s]) @ Q.T, B, C) for s in (0.1, 0.0, -0.1)]
    assert values[1] == pytest.approx(0.0, abs=1e-14)
    assert values[0] * values[2] < 0  # changes sign through the singularity
    assert abs(values[0]) == pytest.approx(0.1, rel=1e-9)  # g = smallest singular value here


def test_criticality_signs():
    assert supercritical("period doubling", 0.3) and not supercritical("period doubling", -0.3)
    assert supercritical("Neimark-Sacker", -0.3) and not supercritical("Neimark-Sacker", 0.3)
    assert supercritical("fold", 1.0) is None and supercritical("Neimark-Sacker", np.nan) is None


@pytest.mark.slow
def test_the_fold_curve_of_a_duffing_body_has_its_cusp_where_harmonic_balance_puts_it():
    """The small and large orbits at w = 1.3 fold twice in F; both folds, and those found
    continuing in w at F = 1, lie on one fold curve in (w, F), whose two arms meet at a
    cusp. One-harmonic balance (F^2 = u [(a + b u)^2 + (c w)^2], u = A^2, a = k1 - w^2,
    b = 3/4 k2): the folds' roots in u merge where a^2 = 3 (c w)^2, at
    w = (sqrt(3) c + sqrt(3 c^2 + 4 k1)) / 2 = 1.04419, F = 0.17078."""
    s = AtlasSettings(("w", "F"), ((0.9, 2.0), (0.05, 3.0)), step=0.05, max_step=0.3,
                      max_points=200, max_period=1, slices=0, switch_depth=0)
    seeds = find_seeds(BODY, VALUES, s, [("small", SMALL, 1)])
    assert sorted(x.kind for x in seeds) == ["fold"] * 4
    (curve,) = trace_curves(BODY, VALUES, s, seeds)  # the four seeds on one curve
    for p in curve.points:  # each point a fold: a multiplier +1, the other e^(-c T)
        mu = np.sort(np.abs(p.multipliers))
        assert mu[1] == pytest.approx(1.0, abs=1e-7)
        assert mu[0] == pytest.approx(np.exp(-0.05 * 2 * np.pi / p.u[-2]), abs=1e-7)
    (cusp,) = curve.codim2
    assert cusp.kind == "cusp"
    c, k1, k2 = 0.05, 1.0, 0.01
    w = (np.sqrt(3) * c + np.sqrt(3 * c ** 2 + 4 * k1)) / 2
    a, b = k1 - w ** 2, 0.75 * k2
    u = -2 * a / (3 * b)
    F = np.sqrt(u * ((a + b * u) ** 2 + (c * w) ** 2))
    assert cusp.point.u[-2] == pytest.approx(w, rel=0.002)
    assert cusp.point.u[-1] == pytest.approx(F, rel=0.01)
    # the fold found continuing in F at w = 1.3 and the curve agree there
    (branch,), _ = continue_starts(OrbitMap(BODY, VALUES, "F", 1), [("small", SMALL, 1)], 1.0,
                                   Settings((0.2, 3.0), step=0.05, max_step=0.3))
    aug = AugmentedMap(BODY, VALUES, ("w", "F"), 1, "fold")
    for event in branch.events:
        found = correct(aug, np.concatenate([event.point.state, [1.3, event.point.parameter]]),
                        np.array([0.0, 0.0, 1.0, 0.0]), 1e-10)
        assert found is not None and found[0][-1] == pytest.approx(event.point.parameter,
                                                                    abs=1e-7)


def test_a_seed_beyond_where_a_curve_stopped_extends_that_curve_instead_of_a_second_copy():
    """Issue 34's fold curve traced twice: the first copy stopped at max_points before
    reaching the second seed. Here the small orbit's fold at w = 1.3 seeds a curve cut
    at 6 points per direction, and a point 10 steps on along that curve seeds again."""
    (branch,), _ = continue_starts(OrbitMap(BODY, VALUES, "F", 1), [("small", SMALL, 1)], 1.0,
                                   Settings((0.2, 3.0), step=0.05, max_step=0.3),
                                   switch_depth=0)
    fold = next(e.point for e in branch.events if e.kind == "fold")
    u = np.concatenate([fold.state, [1.3, fold.parameter]])
    s = AtlasSettings(("w", "F"), ((0.9, 2.0), (0.05, 3.0)), step=0.02, max_step=0.02,
                      max_points=6, max_period=1, slices=0, switch_depth=0)
    aug = AugmentedMap(BODY, VALUES, ("w", "F"), 1, "fold")
    longer = Settings(s.ranges[1], 0.02, 1e-6, 0.02, 12, 1e-9, resolve_turns=False)
    reference = follow_curve(aug, seed(aug, u, 1e-9, 2), longer, s.ranges[0], "small")
    beyond = reference.points[-2].u  # 10 steps on; a 6-point direction stops at 5
    fixed = 2 if abs(beyond[2] - u[2]) > abs(beyond[3] - u[3]) else 3
    seeds = [Seed("fold", "small", 1, u, 2), Seed("fold", "small", 1, beyond, fixed)]
    (curve,) = trace_curves(BODY, VALUES, s, seeds)  # before the fix: two curves
    assert on_curve(aug, curve, beyond, fixed, 1e-9) and on_curve(aug, curve, u, 2, 1e-9)
    assert len(curve.points) > 11 and curve.ends == ("max points", "max points")
    steps = np.array([np.linalg.norm(q.u - p.u)
                      for p, q in zip(curve.points[:-1], curve.points[1:], strict=True)])
    assert np.all(steps > 0.01)  # one curve in order, no point twice at the join
    assert np.linalg.norm(curve.points[-1].u - curve.points[0].u) == pytest.approx(
        steps.sum(), rel=0.05)  # a short piece of curve: nearly straight, no fold back


@pytest.fixture(scope="module")
def ns_curve():
    """Figure 14(c)'s NS point at c_c = 4.0662267 (d = 10.5), followed in (c_c, d)."""
    (branch,), _ = continue_starts(OrbitMap(PAIR, FIG14C, "c_c", 1),
                                   [("impacting P1", ORBIT_AT_4_3, 1)], 4.3,
                                   Settings((3.9, 4.3), step=0.05, max_step=0.2),
                                   switch_depth=0)
    (ns,) = [e.point for e in branch.events if e.kind == "Neimark-Sacker"]
    aug = AugmentedMap(PAIR, FIG14C, ("c_c", "d"), 1, "Neimark-Sacker")
    first = seed(aug, np.concatenate([ns.state, [ns.parameter, 10.5]]), 1e-9)
    settings = Settings((8.5, 11.5), step=0.05, max_step=0.2, max_points=80, tol=1e-9,
                        resolve_turns=False)
    curve = follow_curve(aug, first, settings, (2.5, 6.0), "impacting P1")
    codimension_two(aug, curve, 1e-9)
    return aug, curve


def _crossings(aug, curve, c_c: float) -> list[tuple[float, float]]:
    """(d, coefficient) where the curve crosses c_c, by Newton at fixed c_c."""
    n = aug.dim
    out = []
    for left, right in zip(curve.points[:-1], curve.points[1:], strict=True):
        x0, x1 = left.u[n] - c_c, right.u[n] - c_c
        if x0 * x1 > 0:
            continue
        w = x0 / (x0 - x1)
        normal = np.zeros(n + 2)
        normal[n] = 1.0
        u, value, _ = correct(aug, (1 - w) * left.u + w * right.u, normal, 1e-9)
        out.append((u[-1], criticality(aug.kind, aug.orbit_map(u[n], u[n + 1]), u[:n],
                                       value.monodromy)))
    return sorted(out)


@pytest.mark.slow
def test_figure_14c_neimark_sacker_points_lie_on_one_curve_with_their_criticality(ns_curve):
    """Subcritical at (c_c, d) = (4.0662267, 10.5) and (4.3, 10.2994), supercritical at
    (4.3, 9.040184) (brute force, test_neimark_sacker.py): all three on the NS curve through
    the first, with a pair on the unit circle along it; the first Lyapunov coefficient
    changes sign between them at a Chenciner point."""
    aug, curve = ns_curve
    for p in curve.points:
        mu = p.multipliers
        assert abs(mu[0]) == pytest.approx(1.0, abs=1e-7) and abs(mu[0].imag) > 0.1
    at_43 = _crossings(aug, curve, 4.3)
    (low, low_c), (high, high_c) = at_43
    assert low == pytest.approx(9.040184, abs=1e-5)
    assert high == pytest.approx(10.2994, abs=1e-4)
    assert supercritical("Neimark-Sacker", low_c)
    assert not supercritical("Neimark-Sacker", high_c)
    start = min(curve.points, key=lambda p: abs(p.u[-1] - 10.5) + abs(p.u[-2] - 4.0662267))
    assert start.u[-2] == pytest.approx(4.0662267, abs=1e-6)
    chenciner = [k.point.u[-2:] for k in curve.codim2 if k.kind == "Chenciner"]
    # between the supercritical (4.3, 9.04) and subcritical (4.3, 10.30) parts: one
    # Chenciner point, where the curve turns back in c_c beyond 5.3
    assert any(c_c > 4.3 and 9.04 < d < 10.3 for c_c, d in chenciner)
