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
from scipy.integrate import solve_ivp

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
    if r == 0.0:  # the wall at 1.36 > F = 1 never holds the body: it leaves at once
        assert traj.impacts["sticking_phases"] == 0
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


def free_flight_after_release(w, sigma, t_release, times, zeta=ZETA):
    """scipy's flight from (sigma, 0) at ``t_release`` (where cos(w t) = sigma, the wall
    starting to pull), at ``times`` (the test's own reference, no softimpact code)."""
    sol = solve_ivp(lambda t, y: [y[1], np.cos(w * t) - 2 * zeta * y[1] - y[0]],
                    (t_release, times[-1]), [sigma, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-13, dense_output=True)
    return sol.sol(times).T


def test_a_plastic_sticking_orbit_releases_where_the_force_would_pull():
    """r = 0, wall at sigma = 0.5 < F: the body sticks at each impact and leaves when
    cos(w t) - sigma turns negative (the wall would pull), at w t = arccos(sigma) mod 2 pi;
    its flight from there is scipy's from (sigma, 0)."""
    w, sigma = 0.8, 0.5
    T = 2.0 * np.pi / w
    traj = record_trajectory(oscillator(w, sigma, 0.0), [0.0, 0.0], 0.0, 20, 400)
    assert traj.status == 0
    counts = traj.impacts
    assert counts["sticking_phases"] == counts["impacts"] >= 19
    assert counts["chatter_sequences"] == 0
    # stuck at n T, where its impact was located (to ~1e-13)
    assert np.max(np.abs(traj.section_y[-5:] - [sigma, 0.0])) < 1e-11
    t_release = 19 * T + np.arccos(sigma) / w  # in the last period
    window = (traj.t > t_release + 1e-3) & (traj.t < t_release + 1.5)
    reference = free_flight_after_release(w, sigma, t_release, traj.t[window])
    assert window.sum() > 50 and np.all(reference[:, 0] < sigma)
    assert np.max(np.abs(traj.y[window] - reference)) < 1e-7  # dense output's accuracy
    stuck_per_period = traj.sticking_time / counts["sticking_phases"]
    assert 0.0 < stuck_per_period < T


def test_the_chattering_case_accumulates_sticks_and_releases():
    """w = 2.5, sigma = 0.9 A, r = 0.8 from just below the wall moving into it while the
    forcing pushes: impacts accumulate (a geometric series, Budd and Dux), the body sticks
    and is released where cos(w t) = sigma; its flight is then scipy's from (sigma, 0)."""
    w, r = 2.5, 0.8
    sigma = 0.9 * amplitude(ZETA, w)
    T = 2.0 * np.pi / w
    started = time.process_time()
    traj = record_trajectory(oscillator(w, sigma, r), [sigma - 1e-6, 0.0], 0.0, 1, 2000)
    assert traj.status == 0 and time.process_time() - started < 5.0
    counts = traj.impacts
    assert counts["chatter_sequences"] == 1 and counts["sticking_phases"] == 1
    # from ~1e-3 to the resolution's ~1e-6 at ratio 0.8: some 30 impacts
    assert 15 <= counts["impacts"] <= 60
    t_release = np.arccos(sigma) / w
    assert 0.0 < traj.sticking_time < t_release
    window = (traj.t > t_release + 1e-3) & (traj.t < T)
    reference = free_flight_after_release(w, sigma, t_release, traj.t[window])
    flying = np.cumprod(reference[:, 0] < sigma).astype(bool)  # up to its next impact
    assert flying.sum() > 50
    assert np.max(np.abs(traj.y[window][flying] - reference[flying])) < 1e-7


def test_the_chattering_case_runs_to_completion_labelled_in_bounded_time():
    """The issue's chattering parameters over 60 periods from several starts, some of
    which chatter and stick on the way: each finishes (status 0) within a CPU budget, is
    classified, and counts its impacts, chatter sequences and sticking."""
    w, r = 2.5, 0.8
    sigma = 0.9 * amplitude(ZETA, w)
    started = time.process_time()
    chattered = 0
    for state in ([sigma - 1e-6, 0.0], [0.0, 0.0], [-0.5, 1.0]):
        traj = record_trajectory(oscillator(w, sigma, r), state, 0.0, 60, 4)
        assert traj.status == 0
        chattered += traj.impacts["chatter_sequences"]
        cls = classify_state(oscillator(w, sigma, r), state)
        assert cls.status == 0 and cls.period >= 1 and cls.contacts >= 1
    assert chattered >= 1
    assert time.process_time() - started < 10.0


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


def test_the_stiff_soft_stop_converges_to_the_rigid_law_at_rate_one_half():
    """A soft wall (law "paper", k_c, c_c = 2 zeta_c sqrt(k_c)) with the restitution of a
    linear spring-dashpot released at delta = 0, r = exp(-zeta_c pi / sqrt(1 - zeta_c^2)),
    tends to the rigid wall: the stroboscopic period-1 point moves as the contact's
    duration pi / sqrt(k_c), distance ~ k_c^(-1/2) (measured: 8.4e-2, 2.8e-2, 8.9e-3,
    2.8e-3 for k_c = 1e3 .. 1e6)."""
    w, r = 0.8, 0.8
    sigma = 0.5 * amplitude(ZETA, w)
    rigid = [o for o in period_one(ZETA, w, sigma, r) if o[1] > 0.0][0][2]
    soft = ChainModel(1, (), (), (Stop(1, 0, "right", "paper"),))
    zeta_c = -np.log(r) / np.sqrt(np.pi ** 2 + np.log(r) ** 2)
    stiffness = np.array([1e3, 1e4, 1e5, 1e6])
    distances = []
    for k_c in stiffness:
        values = chain_values(soft, w, {"m": 1.0, "c": 2.0 * ZETA, "k1": 1.0, "k2": 0.0,
                                        "F": 1.0, "phi": np.pi / 2}, (),
                              ({"wall": sigma, "k_c": k_c, "c_c": 2 * zeta_c * np.sqrt(k_c)},))
        problem = Problem(chain_system(soft), values,
                          IntegratorSettings(method="auto", rtol=1e-11, atol=1e-12))
        traj = record_trajectory(problem, rigid, 0.0, 60, 1)
        assert np.max(np.abs(traj.section_y[-1] - traj.section_y[-2])) < 1e-10  # converged
        distances.append(np.max(np.abs(traj.section_y[-1] - rigid)))
    slope = np.polyfit(np.log(stiffness), np.log(distances), 1)[0]
    assert np.all(np.diff(distances) < 0.0) and distances[-1] < 5e-3
    assert -0.55 < slope < -0.45


def test_two_bodies_stuck_move_together_until_the_force_would_pull():
    """Two bodies (m = 1, no springs, no damping) start touching at rest across a rigid
    stop (x1 - x2 = d: stuck from the start), body 1 forced by sin t: they move as one,
    v = (1 - cos t) / 2, until t = pi where the force on body 1 turns to pull it back;
    then body 2 flies on at v = 1 and body 1 at v = -cos t. At t = 2 pi:
    (x1, v1, x2, v2) = (d + pi/2, -1, 3 pi/2, 1), stuck for pi."""
    model = ChainModel(2, (), (), (Stop(1, 2, law="rigid"),))
    values = chain_values(model, 1.0, {"m": 1.0, "c": 0.0, "k1": 0.0, "F": [1.0, 0.0],
                                       "phi": 0.0}, (), ({"d": 0.5, "r": 0.5},))
    problem = Problem(chain_system(model), values, TIGHT)
    traj = record_trajectory(problem, [0.5, 0.0, 0.0, 0.0], 0.0, 1, 64)
    assert traj.status == 0 and traj.impacts["impacts"] == 0
    expected = [0.5 + np.pi / 2, -1.0, 1.5 * np.pi, 1.0]
    assert np.max(np.abs(traj.section_y[-1] - expected)) < 1e-9
    assert traj.sticking_time == pytest.approx(np.pi, abs=1e-9)
    stuck = traj.t < np.pi - 1e-6
    assert np.all(traj.y[stuck, 1] == traj.y[stuck, 3])  # one velocity, bit for bit
