"""kind = "continuation" with a rigid stop: the impact oscillator's period-1 impacting orbit
followed in the wall's position up to grazing (issue 33, item 3).

    x'' + 2 zeta x' + x = -cos(w t),   a wall at x = sigma, r = 0.8, w = 0.8

(``phi = 3 pi / 2``: the section half a period away from the impacts, which otherwise cross
t = 0 mod T on the way, where the stroboscopic map's fixed point jumps from before to
after its impact.) Its multipliers are the section-independent ones of the closed form
(``tests/analysis/test_rigid_monodromy.closed_form_monodromy``, Shaw and Holmes's orbit).

Near grazing (sigma -> A) the impact velocity v- vanishes and the saltation matrix's
``(1 + r)(cos(w t*) - sigma) / v-`` blows up: Nordmark's (1991) square-root singularity,
``|mu_large| ~ c / v-`` with ``v- = sqrt(2 |x''| depth)``, depth the penetration of the
orbit continued without its impact. Along the wall the fixed point's depth grows as
``(A - sigma)^2`` (the Nordmark map ``x -> mu - gamma sqrt(x)``: its impacting fixed point
has ``sqrt(x*) ~ mu / gamma``, and ``v- ~ (A - sigma)``, 0.032 .. 3.2e-5 for A - sigma =
1e-2 A .. 1e-5 A), so the multipliers scale as ``(A - sigma)^(-1)`` and ``(A - sigma)^(+1)``
(their product is det M = r^2 exp(-2 zeta T)), ``depth^(-1/2)`` and ``depth^(+1/2)``.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.engine import Problem
from softimpact_cli.analysis.lyapunov import finite_difference_monodromy
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene

from ..analysis.rigid_reference import amplitude, period_one
from ..analysis.test_rigid_monodromy import closed_form_monodromy

ZETA, R, W = 0.05, 0.8, 0.8
A = amplitude(ZETA, W)

SCENE = f"""\
[system]
model = "chain"
bodies = 1
c = {2 * ZETA}
k1 = 1.0
F = 1.0
phi = "3*pi/2"
w = {W}

[[stop]]
body = 1
wall = 1.35
side = "right"
law = "rigid"
r = {R}

[analysis]
kind = "continuation"
parameter = "stop.1.wall"
low = 1.0
high = 2.8
start = "state"
state = [-0.835, -0.339]
step = 0.05
max_step = 0.1
min_step = 1e-4
max_points = 80
switch_depth = 0
"""


def closed_form_multipliers(sigma: float) -> np.ndarray:
    """|mu| of Shaw and Holmes's period-1 impacting orbit at wall sigma, ascending."""
    t_impact, v_impact, _ = next(o for o in period_one(ZETA, W, sigma, R) if o[1] > 0)
    return np.sort(np.abs(np.linalg.eigvals(
        closed_form_monodromy(W, sigma, R, t_impact, v_impact))))


@pytest.fixture(scope="module")
def branch():
    ds = run_scene(parse_scene(SCENE))
    order = np.argsort(ds["parameter"].values)
    walls = ds["parameter"].values[order]
    mu = np.abs(ds["multiplier_re"].values[order] + 1j * ds["multiplier_im"].values[order])
    return ds, walls, np.sort(mu, axis=1), ds["state"].values[order]


def test_the_impacting_orbit_is_followed_up_to_grazing_with_its_period_doubling(branch):
    """From sigma = 1.35 (A = 2.7116) the branch is impacting all along, loses stability in
    a period doubling (at 1.9297: the bifurcation kind's period-2 orbit past it) and
    reaches the wall within 1e-2 A of grazing (1e-3 A: 80 points, its steps shrinking
    as the multipliers blow up), its multipliers the closed form's all along."""
    ds, walls, mu, _ = branch
    assert np.all(ds["impacting"].values == 1)
    assert list(ds["event_kind"].values) == ["period doubling"]
    assert float(ds["event_parameter"].values[0]) == pytest.approx(1.92972, abs=1e-4)
    assert walls[-1] > 0.99 * A and walls[-1] < A
    for k in np.linspace(0, walls.size - 1, 12).astype(int):
        np.testing.assert_allclose(mu[k], closed_form_multipliers(walls[k]), rtol=1e-5)


def test_the_multipliers_near_grazing_scale_as_the_nordmark_map_says(branch):
    """On the branch's points within 10 % of grazing, log |mu| against log (A - sigma):
    slopes -1 and +1 (module docstring: the square root is in the penetration depth, which
    goes as (A - sigma)^2); brute force, central differences of the stroboscopic map
    with impacts at three of these points (10 % to 1 % from grazing), gives the same
    multipliers."""
    _, walls, mu, states = branch
    near = (A - walls < 0.1 * A) & (A - walls > 0.0)
    assert near.sum() >= 8 and (A - walls[near]).min() < 0.01 * A
    distance = np.log(A - walls[near])
    large = np.polyfit(distance, np.log(mu[near, 1]), 1)[0]
    small = np.polyfit(distance, np.log(mu[near, 0]), 1)[0]
    assert large == pytest.approx(-1.0, abs=0.05) and small == pytest.approx(1.0, abs=0.05)
    scene = parse_scene(SCENE)
    # (closer, the penetration depth ~ 1e-6 at A - sigma = 1e-3 A is too near the step)
    far = np.flatnonzero(near & (A - walls > 0.01 * A))
    for k in far[[0, far.size // 2, -1]]:
        problem = Problem(scene.system, {**scene.values, "stop.1.wall": walls[k]},
                          IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13))
        brute = np.sort(np.abs(np.linalg.eigvals(
            finite_difference_monodromy(problem, states[k], 0.0, 1, step=1e-7))))
        np.testing.assert_allclose(brute, mu[k], rtol=1e-4)


def test_the_free_orbit_is_followed_down_to_grazing_at_its_amplitude():
    """The non-impacting orbit x = -A cos(w t - psi) from sigma = 2.9 down: it lives while
    the wall is beyond its amplitude, its stop's gap (max of x - sigma) closing to 0, and
    its branch ends at sigma = A, to 1e-5 (the impacting orbit's multipliers blow up on
    the other side: the branch does not pass through grazing)."""
    psi = np.arctan2(2.0 * ZETA * W, 1.0 - W * W)
    state = [float(-A * np.cos(psi)), float(-A * W * np.sin(psi))]
    text = (SCENE.replace("wall = 1.35", "wall = 2.9").replace("low = 1.0", "low = 2.0")
            .replace("high = 2.8", "high = 3.0").replace("min_step = 1e-4", "min_step = 1e-7")
            .replace("state = [-0.835, -0.339]", f"state = [{state[0]!r}, {state[1]!r}]"))
    ds = run_scene(parse_scene(text))
    walls = ds["parameter"].values
    assert np.all(ds["impacting"].values == 0) and np.all(ds["stable"].values == 1)
    assert walls.min() == pytest.approx(A, abs=1e-5) and walls.max() == pytest.approx(3.0)
    gaps = ds["stop_gap"].values[:, 0]
    np.testing.assert_allclose(gaps, A - walls, atol=1e-8)  # its top is A
