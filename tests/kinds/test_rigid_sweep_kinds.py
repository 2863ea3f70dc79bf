"""map, design and fatal_shock on a rigid stop (issue 33, item 3): the impact oscillator

    x'' + 2 zeta x' + x = cos(w t),   a wall at x = sigma, restitution r = 0.8,

as a chain of one body with a rigid wall stop. The expectations are independent of
softimpact's kernels: the non-impacting orbit is the linear response of amplitude A(w), so
it survives exactly while the wall stands above A (map, design); and a kick that sends it
to another solution must make the free motion reach the wall (the linear oscillator's
motion after a kick is known in closed form), a lower bound on every fatal shock.
"""

from __future__ import annotations

import numpy as np

from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep

from ..analysis.rigid_reference import amplitude
from .test_rigid_kinds import ZETA, oscillator

BOX = """[initial_conditions]
kind = "random"
n = {n}
seed = 3
box = {{ x1 = [-3.0, 2.0], v1 = [-4.0, 4.0] }}
"""


def test_a_map_keeps_the_free_orbit_exactly_where_the_wall_clears_its_amplitude(tmp_path):
    """Over (w, wall) the free orbit L1^1 survives iff wall > A(w) (closed form)."""
    walls, ws = [2.0, 2.6, 3.2], [1.1, 1.2]
    scene = parse_scene(oscillator(1.2, 3.0, f"""[analysis]
kind = "map"
[grid]
"stop.1.wall" = {walls}
w = {ws}
""" + BOX.format(n=8)))
    ds = run_sweep(scene, tmp_path / "m.h5", workers=1)
    survives = ds["combination_survives"].squeeze().transpose("w", "stop.1.wall").values
    expected = np.array([[wall > amplitude(ZETA, w) for wall in walls] for w in ws])
    assert expected.any() and not expected.all()  # the grid straddles grazing
    assert np.array_equal(survives == 1, expected)


def test_a_design_on_the_wall_puts_the_region_at_the_free_orbits_amplitude():
    """Keeping only L1^1 needs the wall above A: the region's critical value is A, the
    pick lies above it and keeps L1^1 from every sampled start."""
    w = 1.2
    A = amplitude(ZETA, w)
    ds = run_scene(parse_scene(oscillator(w, 3.0, """[analysis]
kind = "design"
target = "L1^1"
bounds = { "stop.1.wall" = [2.0, 6.0] }
candidates = 4
screen_n = 20
refine = 1
robust_n = 20
shock_directions = 4
seed = 0
""" + BOX.format(n=40))))
    assert abs(float(ds["region_critical"].values.squeeze()) - A) < 1e-6
    roles = ds["role"].values.tolist()
    best = roles.index("best")
    assert ds["point_stop.1.wall"].values[best] > A
    assert ds["share"].values[best, 0] == 1.0


def test_every_fatal_kick_of_the_free_orbit_makes_its_free_motion_reach_the_wall():
    """A kick that leaves the free orbit's motion below the wall never impacts and decays
    back to it (the only non-impacting solution of a linear oscillator): so each fatal
    magnitude is at least the smallest kick along its direction whose free motion reaches
    the wall. The fatal kicks end on the impacting orbit."""
    w = 1.2
    A = amplitude(ZETA, w)
    sigma = 1.2 * A
    psi = np.arctan2(2.0 * ZETA * w, 1.0 - w * w)
    ds = run_scene(parse_scene(oscillator(w, sigma, """[analysis]
kind = "fatal_shock"
solution = "L1^1"
phases = 4
directions = 16
max_shock = 8.0
scan = 8
tol = 1e-3
""")))
    times = ds["shock_time"].values
    states = ds["orbit_state"].values
    for i, ts in enumerate(times):  # the kicks start on the free orbit x = A cos(w t - psi)
        free = [A * np.cos(w * ts - psi), -A * w * np.sin(w * ts - psi)]
        assert np.allclose(states[i], free, atol=1e-6)
    wd = np.sqrt(1.0 - ZETA * ZETA)
    t = np.linspace(0.0, 60.0, 12001)
    decay = np.exp(-ZETA * t)

    def reaches(i, kick):
        ts = times[i]
        a, b = kick
        h = decay * (a * np.cos(wd * t) + (b + ZETA * a) / wd * np.sin(wd * t))
        return np.max(A * np.cos(w * (t + ts) - psi) + h) >= sigma

    magnitudes = ds["shock_magnitude"].values
    destinations = ds["shock_destination"].values
    directions = ds["direction"].values
    fatal = np.isfinite(magnitudes)
    assert fatal.any()
    assert set(destinations[fatal].tolist()) == {"impacting P1"}
    for i, j in zip(*np.nonzero(fatal), strict=True):
        low, high = 0.0, magnitudes[i, j]
        assert reaches(i, high * directions[j]), (i, j)
        for _ in range(24):  # the smallest kick along direction j that reaches the wall
            mid = 0.5 * (low + high)
            low, high = (low, mid) if reaches(i, mid * directions[j]) else (mid, high)
        assert magnitudes[i, j] >= high - 1e-3
