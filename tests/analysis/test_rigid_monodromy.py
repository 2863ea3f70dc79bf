"""The saltation matrix of a rigid impact's reset (kernels/impacts.py, saltation.py):
tangent vectors carried across impacts, into sticking and out of it.

The impact oscillator ``x'' + 2 zeta x' + x = cos(w t)`` with a wall at ``sigma`` and
restitution ``r`` (``test_rigid_impacts.oscillator``): the monodromy of its period-1
single-impact orbit against central differences of scipy's event integration and against
the closed form ``exp(A (T - t*)) S exp(A t*)``; two bodies chattering, sticking and
released against central differences of the flow.
"""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit
from scipy.linalg import expm

from softimpact_cli.analysis.engine import Problem, flow, record_trajectory
from softimpact_cli.analysis.lyapunov import finite_difference_monodromy
from softimpact_cli.analysis.shooting import OrbitMap, salted_monodromy
from softimpact_cli.kernels.saltation import reset_saltation, saltation
from softimpact_cli.systems.chain import ChainModel, Stop, chain_system, chain_values
from softimpact_cli.systems.variational import initial_variational_state, variational_system

from .rigid_reference import amplitude, period_one, scipy_sections
from .test_rigid_impacts import TIGHT, ZETA, oscillator


def variational_flow(problem: Problem, y, t0: float, t1: float):
    """(status, y(t1), Phi(t1)) of the variational system from (y, I) at t0."""
    var = Problem(variational_system(problem.system), problem.values, problem.integrator)
    y = np.asarray(y, dtype=float)
    status, z, _ = flow(var, initial_variational_state(y), t0, t1)
    n = y.size
    return status, z[:n], z[n:].reshape(n, n)


def scipy_monodromy(w, sigma, r, state, step=1e-5):
    """Central differences of scipy's stroboscopic map (impacts as events)."""
    M = np.empty((2, 2))
    for j in range(2):
        e = np.zeros(2)
        e[j] = step
        plus = scipy_sections(ZETA, w, sigma, r, state + e, 1)[0][-1]
        minus = scipy_sections(ZETA, w, sigma, r, state - e, 1)[0][-1]
        M[:, j] = (plus - minus) / (2.0 * step)
    return M


def closed_form_monodromy(w, sigma, r, t_impact, v_impact):
    """exp(A (T - t*)) S exp(A t*): free flights of x'' + 2 zeta x' + x = 0 around the
    impact's S = [[-r, 0], [(a+ + r a-) / v-, -r]], a+ + r a- = (1 + r)(cos(w t*) - sigma)."""
    T = 2.0 * np.pi / w
    A = np.array([[0.0, 1.0], [-1.0, -2.0 * ZETA]])
    S = np.array([[-r, 0.0],
                  [(1.0 + r) * (np.cos(w * t_impact) - sigma) / v_impact, -r]])
    return expm(A * (T - t_impact)) @ S @ expm(A * t_impact)


@njit
def two_constant_fields(t, z, p, mode, out):
    """f = p[:n] in mode 0, p[n:] in mode 1 (n = z's size)."""
    n = z.shape[0]
    for i in range(n):
        out[i] = p[mode * n + i]


def test_the_reset_saltation_maps_the_surface_by_DR_and_the_flow_onto_the_flow():
    """S is fixed by two properties (n conditions): a tangent vector along the surface
    (grad h . u = 0) jumps as the reset's Jacobian says, S u = DR u, and the flow's
    direction before goes to the flow's direction after, S f- = f+ (a shift along the
    orbit stays one). Its determinant is det DR (grad h . DR^-1 f+) / (grad h . f-); with
    DR = I it is the field jump's saltation matrix."""
    rng = np.random.default_rng(3)
    n = 4
    DR = np.eye(n) + 0.3 * rng.standard_normal((n, n))
    fb, fa, a = rng.standard_normal(n), rng.standard_normal(n), rng.standard_normal(n)
    S = np.empty((n, n))
    rate = reset_saltation(DR, fb, fa, a, n, S)
    assert rate == pytest.approx(a @ fb)
    u = rng.standard_normal(n)
    u -= (a @ u) / (a @ a) * a
    np.testing.assert_allclose(S @ u, DR @ u, atol=1e-12)
    np.testing.assert_allclose(S @ fb, fa, atol=1e-12)
    expected = np.linalg.det(DR) * (a @ np.linalg.solve(DR, fa)) / (a @ fb)
    assert np.linalg.det(S) == pytest.approx(expected, rel=1e-10)

    jump = np.empty((n, n))
    saltation(two_constant_fields, np.concatenate([fb, fa]), 0.0, np.zeros(n), n, 0, 1, a,
              jump)
    reset_saltation(np.eye(n), fb, fa, a, n, S)
    np.testing.assert_allclose(S, jump, atol=1e-14)


def test_the_period_one_orbits_monodromy_against_scipy_and_the_closed_form():
    """w = 0.8, sigma = A/2, r = 0.8 (Shaw and Holmes's period-1 single-impact orbit):
    the monodromy with the impact's saltation matrix (the shooting's, and the
    variational flow's) equals central differences of scipy's event integration to 1e-6
    and the closed form to 1e-9; det M = r^2 exp(-2 zeta T) (det S = r^2)."""
    w, r = 0.8, 0.8
    sigma = 0.5 * amplitude(ZETA, w)
    t_impact, v_impact, state = next(o for o in period_one(ZETA, w, sigma, r) if o[1] > 0)
    problem = oscillator(w, sigma, r)
    T = problem.period
    M = salted_monodromy(problem, state, 1)
    status, end, Phi = variational_flow(problem, state, 0.0, T)
    assert status == 0 and np.max(np.abs(end - state)) < 1e-9
    np.testing.assert_allclose(Phi, M, atol=1e-10)
    np.testing.assert_allclose(M, scipy_monodromy(w, sigma, r, state), atol=1e-6)
    np.testing.assert_allclose(M, closed_form_monodromy(w, sigma, r, t_impact, v_impact),
                               atol=1e-9)
    assert np.linalg.det(M) == pytest.approx(r * r * np.exp(-2.0 * ZETA * T), rel=1e-9)
    assert np.all(np.abs(np.linalg.eigvals(M)) < 1.0)  # stable, as the sweeps find it
    # the continuation's shooting map returns the same monodromy on this impacting orbit
    value = OrbitMap(problem.system, problem.values, "stop.1.wall", 1).evaluate(
        state, sigma, parameter_derivative=False)
    assert value.max_g >= 0.0
    np.testing.assert_allclose(value.monodromy, M, atol=1e-10)


def test_sticking_on_a_wall_forgets_every_perturbation():
    """The chattering case (w = 2.5, sigma = 0.9 A, r = 0.8) from 1e-4 below the wall: the
    impacts accumulate, the body sticks at (sigma, 0) and is released where cos(w t) =
    sigma whatever its start: the period's monodromy is 0 (S = 0 entering sticking on a
    wall), and central differences of the flow agree."""
    w, r = 2.5, 0.8
    sigma = 0.9 * amplitude(ZETA, w)
    problem = oscillator(w, sigma, r)
    start = [sigma - 1e-4, 0.0]
    traj = record_trajectory(problem, start, 0.0, 1, 4)
    assert traj.impacts["chatter_sequences"] == 1 and traj.impacts["sticking_phases"] == 1
    status, _, Phi = variational_flow(problem, start, 0.0, problem.period)
    assert status == 0 and np.all(Phi == 0.0)
    assert np.max(np.abs(finite_difference_monodromy(problem, start, 0.0, 1))) < 1e-6


@pytest.mark.parametrize("r", [0.0, 0.5])
@pytest.mark.parametrize("damping", [(0.3, 0.05), (0.1, 0.2)])
def test_two_bodies_impacting_sticking_and_released_against_central_differences(r, damping):
    """Body 1 (m = 1, forced) hits body 2 (m = 2) across a rigid stop: with r = 0 it sticks
    at once, with r = 1/2 after a chatter; stuck they move as one until the force would
    pull them apart. The fundamental matrix over 2 pi (the reset's S, the projection on the
    constraint with its time correction, the stuck flow's variational equations, the
    release) equals central differences of the flow. With damping per mass 0.3 and 0.025
    the time correction entering sticking is not 0 (the common velocity's drift, kappa =
    (c1 m2 - c2 m1) / (m1 + m2)^2); with 0.1 and 0.1 it is."""
    model = ChainModel(2, (), (), (Stop(1, 2, law="rigid"),))
    values = chain_values(model, 1.0, {"m": [1.0, 2.0], "c": list(damping),
                                       "k1": [1.0, 0.5], "F": [2.0, 0.0], "phi": 0.0},
                          (), ({"d": 0.5, "r": r},))
    problem = Problem(chain_system(model), values, TIGHT)
    start = [0.0, 0.5, -0.2, 0.0]
    traj = record_trajectory(problem, start, 0.0, 1, 4)
    assert traj.impacts["sticking_phases"] == 1 and traj.impacts["impacts"] >= 1
    assert traj.impacts["chatter_sequences"] == (1 if r > 0 else 0)
    assert 0.5 < traj.sticking_time < 2.0  # released within the period
    status, end, Phi = variational_flow(problem, start, 0.0, 2.0 * np.pi)
    assert status == 0
    np.testing.assert_allclose(end, traj.section_y[-1], atol=1e-9)
    reference = finite_difference_monodromy(problem, start, 0.0, 1)
    assert np.max(np.abs(reference)) > 0.5
    np.testing.assert_allclose(Phi, reference, atol=1e-6)
