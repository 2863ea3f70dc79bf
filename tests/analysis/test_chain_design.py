"""The chain's design region (``analysis.chain_design``) against brute force: at points of
a three-body chain's parameters, each product is integrated on the coupled chain (its stops
at the point's values) from its own orbit; it survives when no stop is ever touched. The
region says "only the target" exactly where that integration does; its margins are the
distances to where the survivors change, found by scanning (``chain_catalogue.survival``)."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import sample_states
from softimpact_cli.analysis.chain_catalogue import build_chain_catalogue, survival
from softimpact_cli.analysis.chain_region import build_region
from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.kinds.design_settings import DesignAnalysis
from softimpact_cli.kinds.scene import parse_scene

TARGET = "B1:P1^1 B2:P1-0^1 B3:P1-0^1"
CHAIN = """\
[system]
model = "chain"
bodies = 3
k2 = 0.05
F = 1.5
w = 1.4
phi = [0.0, "5*pi/8", "5*pi/4"]

[[stop]]
between = [1, 2]
d = 2.0

[[stop]]
between = [2, 3]
d = 5.0

[analysis]
state = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
"""
STATES = sample_states({"x": (-4.0, 4.0), "v": (-4.0, 4.0)}, 4, 0, 0)


@pytest.fixture(scope="module")
def chain():
    return parse_scene(CHAIN, "chain.toml")


def catalogues(scene):
    """``catalogue_at`` as the design's runner gives it (computed here, cached)."""
    cache = {}

    def at(point: dict):
        key = tuple(sorted(point.items()))
        if key not in cache:
            cache[key] = build_chain_catalogue(scene.system, {**scene.values, **point},
                                               scene.integrator, STATES)
        return cache[key]
    return at


def settings(bounds: dict, grid_points: int = 3) -> DesignAnalysis:
    return DesignAnalysis("design", TARGET, bounds, grid_points=grid_points)


def brute_survivors(scene, cat, values: dict) -> set[str]:
    """The products that never touch a stop on the coupled chain at ``values``."""
    problem = Problem(scene.system, values, scene.integrator)
    out = set()
    for p in cat.products:
        y = record_trajectory(problem, p.orbit[0], 0.0, 2 * p.orbit.shape[0], 2048).y
        gap1 = y[:, 0] - y[:, 2] - values["stop.1.d"]
        gap2 = y[:, 2] - y[:, 4] - values["stop.2.d"]
        if gap1.max() < 0.0 and gap2.max() < 0.0:
            out.add(p.name)
    return out


def clear_of_edges(critical: np.ndarray, d1: float, d2: float, tol: float = 0.05) -> bool:
    """Whether (d1, d2) lies at least ``tol`` from every product's critical values."""
    c = critical[np.isfinite(critical[:, 0])]
    return bool(np.all(np.abs(c[:, 0] - d1) > tol) and np.all(np.abs(c[:, 1] - d2) > tol))


def test_the_stop_region_is_where_only_the_target_survives_by_integration(chain):
    at = catalogues(chain)
    region = build_region(chain.system, chain.values,
                          settings({"stop.1.d": (1.0, 10.0), "stop.2.d": (1.0, 10.0)}), at)
    assert region.body_axes == () and region.grid.shape == (1, 0)
    cat = at({})
    inside = outside = 0
    for d1 in (2.5, 3.4, 4.3, 5.2, 6.4):
        for d2 in (2.5, 3.6, 5.0, 6.4, 9.6):
            if not clear_of_edges(region.critical[0], d1, d2):
                continue
            point = {"stop.1.d": d1, "stop.2.d": d2}
            alone = region.alone(region.critical[0], region.stop_vector(point))
            survivors = brute_survivors(chain, cat, {**chain.values, **point})
            assert alone == (survivors == {TARGET}), (point, survivors)
            inside += alone
            outside += not alone and bool(survivors - {TARGET})  # another one survives
    assert inside >= 2 and outside >= 4


def test_along_a_phase_the_region_follows_the_products_by_integration(chain):
    """phi.2 is a body axis: the region on its grid, each point against the coupled chain
    integrated at that phase."""
    at = catalogues(chain)
    s = settings({"phi.2": (0.5 * np.pi, np.pi), "stop.1.d": (1.0, 10.0)}, grid_points=3)
    region = build_region(chain.system, chain.values, s, at)
    assert region.shape == (3,) and np.allclose(region.grid[:, 0], [0.5 * np.pi,
                                                                    0.75 * np.pi, np.pi])
    checked = agree_alone = 0
    brute = {}  # (grid index, d1) -> only the target survives, by integration
    for g, (phi2,) in enumerate(region.grid):
        cat = at({"phi.2": float(phi2)})
        for d1 in (2.6, 3.5, 4.4, 5.5, 7.0):
            if not clear_of_edges(region.critical[g], d1, chain.values["stop.2.d"]):
                continue
            point = {"phi.2": float(phi2), "stop.1.d": d1}
            alone = region.alone(region.critical[g], region.stop_vector(point))
            survivors = brute_survivors(chain, cat, {**chain.values, **point})
            assert alone == (survivors == {TARGET}), (point, survivors)
            brute[g, d1] = survivors == {TARGET}
            checked += 1
            agree_alone += alone
    assert checked >= 10 and agree_alone >= 1
    # the phase margin of a point alone: to the nearest grid phase where integration saw
    # another survivor or the target destroyed, less half a step, over pi
    phis, step, compared = region.grid[:, 0], np.pi / 4, 0
    for (g, d1), alone in brute.items():
        line = [brute.get((k, d1)) for k in range(3)]
        if not alone or None in line:
            continue
        outside = [abs(phis[g] - phis[k]) for k in range(3) if not line[k]]
        expected = (min(outside) - step / 2) / np.pi if outside else (phis[-1] - phis[0]) / np.pi
        m = region.margins(region.critical[g], {"phi.2": float(phis[g]), "stop.1.d": d1})
        assert m["body_to_boundary"] == pytest.approx(expected, abs=1e-12), (g, d1)
        compared += 1
    assert compared >= 1


def test_margins_are_the_distances_to_where_the_survivors_change(chain):
    at = catalogues(chain)
    region = build_region(chain.system, chain.values,
                          settings({"stop.1.d": (1.0, 10.0), "stop.2.d": (1.0, 10.0)}), at)
    cat = at({})
    target = cat.names.index(TARGET)
    for d1, d2 in ((4.5, 4.0), (3.2, 5.5), (3.9, 3.3)):
        point = {"stop.1.d": d1, "stop.2.d": d2}
        m = region.margins(region.critical[0], point)
        # scan each stop axis both ways in steps of 1e-3 until the survivors change
        edges = []
        for axis in point:
            for direction in (-1.0, 1.0):
                step = 0
                while True:
                    step += 1
                    moved = {**chain.values, **point,
                             axis: point[axis] + direction * 1e-3 * step}
                    alive = survival(chain.system, moved, cat.critical)
                    if not (alive[target] and alive.sum() == 1):
                        break
                edges.append((step - 0.5) * 1e-3)
        assert m["d_to_boundary"] == pytest.approx(min(edges), abs=6e-4), point
        assert m["d_to_target"] == pytest.approx(
            min(d1 - cat.critical[target, 0], d2 - cat.critical[target, 1]), abs=1e-12)
        assert m["relative"] == pytest.approx(
            min(min(edges[0:2]) / d1, min(edges[2:4]) / d2), abs=6e-4)


WALL = CHAIN.replace("[[stop]]\nbetween = [2, 3]\nd = 5.0",
                     '[[stop]]\nbody = 3\nwall = -3.0\nside = "left"')


def test_a_left_wall_bounds_the_region_from_above_by_integration():
    """A left wall (contact while x3 <= wall) destroys a product when the wall rises above
    its min x3: the region in the wall's position is the mirror of a gap's, checked by
    integration of the coupled chain."""
    scene = parse_scene(WALL, "wall.toml")
    at = catalogues(scene)
    s = settings({"stop.1.d": (1.0, 10.0), "stop.2.wall": (-8.0, -0.5)})
    region = build_region(scene.system, scene.values, s, at)
    assert list(region.signs) == [1.0, -1.0]
    cat = at({})
    seen = {True: 0, False: 0}
    for d1 in (3.4, 4.3, 6.4):
        for wall in (-1.0, -2.0, -2.8, -4.0, -6.0):
            point = {"stop.1.d": d1, "stop.2.wall": wall}
            critical = region.critical[0]
            if np.any(np.abs(critical[:, 0] - d1) < 0.05) or \
                    np.any(np.abs(critical[:, 1] - wall) < 0.05):
                continue
            values = {**scene.values, **point}
            coupled = Problem(scene.system, values, scene.integrator)
            survivors, orbits = set(), {}
            for p in cat.products:
                y = orbits[p.name] = record_trajectory(coupled, p.orbit[0], 0.0, 2, 2048).y
                if (y[:, 0] - y[:, 2] < d1).all() and (y[:, 4] > wall).all():
                    survivors.add(p.name)
            alone = region.alone(critical, region.stop_vector(point))
            assert alone == (survivors == {TARGET}), (point, survivors)
            seen[alone] += 1
            m = region.margins(critical, point)
            if alone:  # the target's clearance: the wall below its min x3, d1 above
                lowest = orbits[TARGET][:, 4].min()
                assert m["d_to_target"] == pytest.approx(
                    min(lowest - wall, d1 - (orbits[TARGET][:, 0]
                                             - orbits[TARGET][:, 2]).max()), abs=2e-3)
    assert seen[True] >= 1 and seen[False] >= 3
