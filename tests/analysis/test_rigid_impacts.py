"""Rigid stops (law "rigid", kernels/impacts.py) on the impact oscillator

    x'' + 2 zeta x' + x = cos(w t),   a wall at x = sigma, restitution r,

a chain of one body (m = 1, c = 2 zeta, k1 = 1, F = 1, phi = pi/2: F sin(w t + phi) =
cos(w t)) with a wall stop on its right; against scipy with impact events and Shaw and
Holmes's closed form (``rigid_reference.py``, no softimpact code), and two bodies.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from softimpact_cli.analysis.engine import Problem, classify_state, record_trajectory
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems.chain import ChainModel, Stop, chain_system, chain_values

from .rigid_reference import amplitude, period_one, scipy_sections

ZETA = 0.05
TIGHT = IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13)
WALL = ChainModel(1, (), (), (Stop(1, 0, "right", "rigid"),))


def oscillator(w: float, sigma: float, r: float, zeta: float = ZETA,
               settings: IntegratorSettings = TIGHT) -> Problem:
    values = chain_values(WALL, w, {"m": 1.0, "c": 2.0 * zeta, "k1": 1.0, "k2": 0.0,
                                    "F": 1.0, "phi": np.pi / 2}, (),
                          ({"wall": sigma, "r": r},))
    return Problem(chain_system(WALL), values, settings)


def test_the_period_one_impacting_orbit_matches_scipy_and_the_closed_form():
    w, r = 0.8, 0.8
    sigma = 0.5 * amplitude(ZETA, w)
    traj = record_trajectory(oscillator(w, sigma, r), [0.0, 0.0], 0.0, 60, 4)
    reference, impacts = scipy_sections(ZETA, w, sigma, r, [0.0, 0.0], 60)
    assert traj.status == 0
    assert np.max(np.abs(traj.section_y - reference)) < 1e-8  # the whole transient
    assert traj.impacts["impacts"] == impacts == int(traj.contacts.sum())
    assert list(traj.contacts[-10:]) == [1] * 10  # one impact per period
    orbits = [o for o in period_one(ZETA, w, sigma, r) if o[1] > 0.0]  # v- > 0: physical
    assert len(orbits) == 1
    assert np.max(np.abs(traj.section_y[-1] - orbits[0][2])) < 1e-8
    # and the classification finds it: period 1, impacting, the same point (to its
    # convergence test, which stops once the section points repeat to convergence_tol)
    cls = classify_state(oscillator(w, sigma, r), [0.0, 0.0])
    assert cls.period == 1 and cls.contacts == 1 and cls.max_penetration >= 0.0
    assert np.max(np.abs(cls.orbit[0] - orbits[0][2])) < 100 * TIGHT.convergence_tol


@pytest.mark.parametrize("r", [0.0, 0.5, 1.0])
def test_restitution_reverses_the_impact_velocity(r):
    """Each impact leaves at -r times the arrival velocity: the scipy reference agrees
    for r = 0 (plastic: the body rests, then sticks or leaves), 1/2 and 1 (elastic)."""
    w = 0.8
    sigma = 0.5 * amplitude(ZETA, w)
    traj = record_trajectory(oscillator(w, sigma, r), [0.0, 0.0], 0.0, 12, 4)
    if r == 0.0:  # sticking: scipy's events cannot stick; see the sticking test
        assert traj.impacts["sticking_phases"] == traj.impacts["impacts"] > 0
        return
    reference, impacts = scipy_sections(ZETA, w, sigma, r, [0.0, 0.0], 12)
    assert np.max(np.abs(traj.section_y - reference)) < 1e-8
    assert traj.impacts["impacts"] == impacts


def test_grazing_of_the_non_impacting_orbit_at_sigma_equal_to_its_amplitude():
    w = 0.8
    A = amplitude(ZETA, w)
    psi = np.arctan2(2.0 * ZETA * w, 1.0 - w * w)
    on_orbit = [A * np.cos(-psi), -A * w * np.sin(-psi)]  # x = A cos(w t - psi) at t = 0
    above = record_trajectory(oscillator(w, A * (1.0 + 1e-7), 0.8), on_orbit, 0.0, 10, 64)
    assert above.impacts["impacts"] == 0
    assert np.max(np.abs(above.section_y - on_orbit)) < 1e-9
    assert abs(np.max(above.y[:, 0]) - A) < 1e-3 * A  # its top is A: it grazes sigma = A
    below = record_trajectory(oscillator(w, A * (1.0 - 1e-4), 0.8), on_orbit, 0.0, 10, 4)
    assert below.impacts["impacts"] >= 1


def test_a_plastic_sticking_orbit_releases_where_the_force_would_pull():
    """r = 0: the body sticks on the wall at its first impact of each period and leaves
    when cos(w t) - sigma turns negative (the wall would pull): the section point is then
    the free flight from (sigma, 0) at w t = arccos(sigma) (scipy, no softimpact code)."""
    w = 0.8
    sigma = 0.5 * amplitude(ZETA, w)
    T = 2.0 * np.pi / w
    traj = record_trajectory(oscillator(w, sigma, 0.0), [0.0, 0.0], 0.0, 40, 8)
    assert traj.status == 0
    counts = traj.impacts
    assert counts["sticking_phases"] >= 30 and counts["chatter_sequences"] == 0
    t_release = np.arccos(sigma) / w  # cos decreasing through sigma
    from scipy.integrate import solve_ivp  # (the test's own reference)
    sol = solve_ivp(lambda t, y: [y[1], np.cos(w * t) - 2 * ZETA * y[1] - y[0]],
                    (t_release, T), [sigma, 0.0], method="DOP853", rtol=1e-12, atol=1e-13,
                    dense_output=True)
    assert np.all(sol.sol(np.linspace(t_release, T, 200))[0] < sigma)  # no impact before T
    assert np.max(np.abs(traj.section_y[-1] - sol.y[:, -1])) < 1e-8
    # stuck from the impact to the release, once a period
    assert traj.sticking_time > 0.0


def test_the_chattering_case_ends_in_bounded_time_with_its_counts():
    """w = 2.5, sigma = 0.9 A, r = 0.8: impacts accumulate (Budd and Dux), the body
    sticks, the run finishes and counts its chatter sequences and sticking."""
    w, r = 2.5, 0.8
    sigma = 0.9 * amplitude(ZETA, w)
    started = time.process_time()
    traj = record_trajectory(oscillator(w, sigma, r), [0.0, 0.0], 0.0, 50, 8)
    spent = time.process_time() - started
    assert traj.status == 0 and spent < 10.0
    counts = traj.impacts
    assert counts["chatter_sequences"] >= 10 and counts["sticking_phases"] >= 10
    assert counts["impacts"] > 10 * counts["chatter_sequences"]
    assert traj.sticking_time > 0.0
    cls = classify_state(oscillator(w, sigma, r), [0.0, 0.0])
    assert cls.status == 0 and cls.period >= 1 and cls.contacts >= 1


def test_an_impact_between_two_bodies_keeps_momentum():
    """Two free bodies (no springs, no forcing), masses 1 and 3, meet once: Newton's law
    on the relative velocity, the total momentum kept to rounding."""
    model = ChainModel(2, (), (), (Stop(1, 2, law="rigid"),))
    r = 0.5
    values = chain_values(model, 1.0, {"m": [1.0, 3.0], "c": 0.0, "k1": 0.0, "F": 0.0},
                          (), ({"d": 0.5, "r": r},))
    problem = Problem(chain_system(model), values, TIGHT)
    traj = record_trajectory(problem, [0.0, 1.0, 0.0, -1.0], 0.0, 1, 4)
    x1, v1, x2, v2 = traj.section_y[-1]
    assert traj.impacts["impacts"] == 1
    assert v1 == pytest.approx(1.0 - (1.0 + r) * 2.0 * 0.75, abs=1e-14)
    assert v2 == pytest.approx(-1.0 + (1.0 + r) * 2.0 * 0.25, abs=1e-14)
    assert v1 + 3.0 * v2 == pytest.approx(-2.0, abs=1e-13)
    T = 2.0 * np.pi
    assert x1 - x2 == pytest.approx(0.5 - r * 2.0 * (T - 0.25), abs=1e-10)
