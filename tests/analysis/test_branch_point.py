"""Branch points of a continuation, located, switched onto and checked by brute force.

The Duffing pair at phi = pi (the bodies forced in antiphase), d = 6: the system is
symmetric under S(x1, v1, x2, v2) = (-x2, -v2, -x1, -v1), and its impacting period-1
orbit L1^1 R1-0^1 is symmetric (x2 = -x1). Followed in w, a real multiplier crosses +1 at
w = 1.0642063 and back at 1.1251762 while the branch goes on in w (no fold): two
symmetry-breaking pitchforks. At each, a pair of asymmetric orbits (mirror images under S)
branches off; the continuation must report both branch points and trace those orbits.

The brute-force check uses neither Newton nor multipliers: plain iteration of the
stroboscopic map from points near the symmetric orbit. Between the branch points (where
the symmetric orbit is unstable) it ends on the switched branches' orbits; below them it
returns to the symmetric orbit, and the switched branches have no orbit there.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.continuation import Settings, correct
from softimpact_cli.analysis.continuation_branches import continue_starts, crossings
from softimpact_cli.analysis.engine import Problem, flow
from softimpact_cli.analysis.shooting import SHOOTING, OrbitMap
from softimpact_cli.systems import get_system

PAIR = get_system("duffing", 2)
VALUES = {**PAIR.defaults(), "phi": np.pi, "d": 6.0}
BASE = OrbitMap(PAIR, VALUES, "w", 1)
# the symmetric orbit L1^1 R1-0^1 at w = 1.09 (t = 0), between the branch points
SYMMETRIC = np.array([-3.83958891166, -1.36292365732, 3.83958891166, 1.36292365732])
BRANCH_POINTS = (1.0642063, 1.1251762)


def mirror(y: np.ndarray) -> np.ndarray:
    """S(x1, v1, x2, v2) = (-x2, -v2, -x1, -v1): the pair's symmetry at phi = pi."""
    return -np.asarray(y)[[2, 3, 0, 1]]


@pytest.fixture(scope="module")
def traced():
    settings = Settings((1.05, 1.13), step=0.02, max_step=0.1)
    branches, _ = continue_starts(BASE, [("symmetric", SYMMETRIC, 1)], 1.09, settings,
                                  switch_depth=1)
    return branches


def test_both_pitchforks_are_located_as_branch_points(traced):
    symmetric = traced[0]
    events = [e for e in symmetric.events if e.kind in ("branch point", "fold")]
    assert [e.kind for e in events] == ["branch point", "branch point"]
    for e, w in zip(events, BRANCH_POINTS, strict=True):
        assert e.point.parameter == pytest.approx(w, abs=1e-6)
        mu = e.point.multipliers
        assert np.min(np.abs(mu - 1.0)) < 1e-8  # located as tightly as folds and doublings
        assert np.max(np.abs(e.point.value.residual)) < 1e-10
        # symmetric (to the corrector's resolution along the singular direction)
        assert np.max(np.abs(e.point.state - mirror(e.point.state))) < 1e-6
    # the symmetric orbit is unstable between them, stable outside
    for p in symmetric.points:
        inside = BRANCH_POINTS[0] + 1e-4 < p.parameter < BRANCH_POINTS[1] - 1e-4
        outside = not BRANCH_POINTS[0] - 1e-4 < p.parameter < BRANCH_POINTS[1] + 1e-4
        assert not (inside and p.stable) and not (outside and not p.stable)


def test_the_switched_branches_are_the_asymmetric_mirror_pairs(traced):
    switched = [b for b in traced if b.parent == 0]
    assert [b.name for b in switched] == ["symmetric BP1+", "symmetric BP1-",
                                          "symmetric BP2+", "symmetric BP2-"]
    located = [e.point for e in traced[0].events if e.kind == "branch point"]
    for b in switched:
        start = located[int(b.name[-2]) - 1]
        assert np.array_equal(b.points[0].u, start.u)  # each starts at its branch point
        for p in b.points[1:]:
            assert np.max(np.abs(p.value.residual)) < 1e-10
            assert np.max(np.abs(p.state - mirror(p.state))) > 1e-3  # off the symmetric
        assert all(p.parameter >= start.parameter - 1e-9 for p in b.points)
    for plus, minus in (switched[:2], switched[2:]):  # the two sides: mirror images
        assert len(plus.points) == len(minus.points)
        for p, q in zip(plus.points[1:], minus.points[1:], strict=True):
            assert np.max(np.abs(p.state - mirror(q.state))) < 1e-6
    first = switched[0].points
    assert first[1].stable  # born stable (a supercritical pitchfork) ...
    ns = [e for e in switched[0].events if e.kind == "Neimark-Sacker"]
    assert len(ns) == 1 and ns[0].point.parameter == pytest.approx(1.0997471, abs=1e-6)
    assert not any(p.stable for p in switched[2].points[1:])  # ... and, at the second, not


def settle(w: float, y: np.ndarray, tol: float = 1e-12, periods: int = 3000) -> np.ndarray:
    """Plain iteration of the stroboscopic map at w from y until it moves less than tol."""
    problem = Problem(PAIR, {**VALUES, "w": w}, SHOOTING)
    for _ in range(periods):
        image = flow(problem, y, 0.0, problem.period)[1]
        if np.max(np.abs(image - y)) < tol:
            return image
        y = image
    raise AssertionError(f"no fixed point reached at w = {w} in {periods} periods")


def starts_near(w: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """The symmetric orbit at w (Newton) and a few starts 1e-3 from it: along the
    eigenvector of its largest multiplier, both ways, and two random directions."""
    u, value, _ = correct(BASE, np.append(SYMMETRIC, w), None, 1e-11)
    mu, vectors = np.linalg.eig(value.monodromy)
    v = np.real(vectors[:, np.argmax(np.abs(mu))])
    v /= np.linalg.norm(v)
    rng = np.random.default_rng(3)
    return u[:-1], [u[:-1] + 1e-3 * v, u[:-1] - 1e-3 * v] + \
        [u[:-1] + 1e-3 * rng.standard_normal(4) for _ in range(2)]


def test_integration_between_the_branch_points_lands_on_the_switched_orbits(traced):
    w = 1.08
    orbits = {b.name: crossings(BASE, b, w, 1e-11) for b in traced if b.parent == 0}
    asymmetric = {name: c[0][0] for name, c in orbits.items() if c}
    assert sorted(asymmetric) == ["symmetric BP1+", "symmetric BP1-"]
    symmetric, starts = starts_near(w)
    reached = set()
    for y in starts:
        end = settle(w, y)
        assert np.max(np.abs(end - symmetric)) > 1.0  # the symmetric orbit is left
        name, distance = min(((n, float(np.max(np.abs(end - a)))) for n, a in
                              asymmetric.items()), key=lambda x: x[1])
        assert distance < 1e-6
        reached.add(name)
    assert reached == set(asymmetric)  # both mirror images, from either side


def test_below_the_first_branch_point_integration_stays_symmetric(traced):
    w = 1.055
    assert all(not crossings(BASE, b, w, 1e-11) for b in traced if b.parent == 0)
    symmetric, starts = starts_near(w)
    for y in starts:
        assert np.max(np.abs(settle(w, y) - symmetric)) < 1e-6
