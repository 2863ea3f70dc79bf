"""The chain family (systems/chain.py) against independent references.

The references are written here from the equations (the chain module's docstring), not
from the package: scipy's DOP853 with every switch located and the integration restarted
there (``tests.naive.solve_with_events``).
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.engine import Problem, flow, record_trajectory
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kernels import orbit
from softimpact_cli.systems import get_system
from softimpact_cli.systems.chain import (
    ChainModel,
    Kink,
    Stop,
    chain_jacobian,
    chain_rhs,
    chain_system,
    chain_values,
)
from tests.naive import solve_with_events

TIGHT = IntegratorSettings(method="dopri5", rtol=1e-11, atol=1e-12)


def sections(system, values, y0, periods, settings=TIGHT):
    problem = Problem(system, values, settings)
    traj = record_trajectory(problem, y0, 0.0, periods, 4)
    assert traj.status == 0
    return problem, traj


# ---------------------------------------------------------------- an independent referee


def reference_chain(masses, c, k1, k2, F, phi, w, stops, kinks=()):
    """(rhs per mode, switching functions) of a chain, written from the equations.

    stops: (i, j, d, k_c, c_c, law) with j = None for a wall, then d is (X, side);
    kinks: (i, position, side, k). Surfaces: stops' contacts, kinks, no-tension surfaces.
    """
    n = len(masses)

    def delta_of(stop, y):
        i, j, d = stop[:3]
        if j is None:
            wall, side = d
            s = 1.0 if side == "right" else -1.0
            return s * (y[2 * i] - wall), s * y[2 * i + 1], s
        return y[2 * i] - y[2 * j] - d, y[2 * i + 1] - y[2 * j + 1], 1.0

    tension = [k for k, stop in enumerate(stops) if stop[5] == "no-tension"]

    def rhs(t, y, mode):
        out = np.empty(2 * n)
        force = np.zeros(n)
        for i in range(n):
            x, v = y[2 * i], y[2 * i + 1]
            force[i] = (F[i] * np.sin(w * t + phi[i]) - c[i] * v - k1[i] * x - k2[i] * x**3)
        for k, (i, position, _side, stiffness) in enumerate(kinks):
            if (mode >> (len(stops) + k)) & 1:
                force[i] -= stiffness * (y[2 * i] - position)
        for s, stop in enumerate(stops):
            if not (mode >> s) & 1:
                continue
            delta, rate, sign = delta_of(stop, y)
            fc = stop[3] * delta + stop[4] * rate
            if stop[5] == "no-tension":
                bit = len(stops) + len(kinks) + tension.index(s)
                if not (mode >> bit) & 1:
                    fc = 0.0
            force[stop[0]] -= sign * fc
            if stop[1] is not None:
                force[stop[1]] += fc
        for i in range(n):
            out[2 * i] = y[2 * i + 1]
            out[2 * i + 1] = force[i] / masses[i]
        return out

    switches = [lambda t, y, stop=stop: delta_of(stop, y)[0] for stop in stops]
    switches += [lambda t, y, kink=kink: (y[2 * kink[0]] - kink[1]) * (1 if kink[2] == "right"
                                                                        else -1)
                 for kink in kinks]
    switches += [lambda t, y, stop=stops[s]: stop[3] * delta_of(stop, y)[0]
                 + stop[4] * delta_of(stop, y)[1] for s in tension]
    return rhs, switches


def onsets(solution, stops: int) -> int:
    """Contact onsets in the referee's events: a stop's surface crossed into contact."""
    return sum(1 for s, mode in zip(solution.event_surface, solution.event_mode, strict=True)
               if s < stops and (mode >> s) & 1)


def scipy_sections(rhs, switches, y0, period, periods):
    times = period * np.arange(periods + 1)
    sol = solve_with_events(rhs, y0, (0.0, times[-1]), switches, t_eval=times,
                            rtol=1e-12, atol=1e-13)
    return sol


THREE = ChainModel(3, stops=(Stop(1, 2), Stop(2, 3)))
PHASES = [0.0, 5 * np.pi / 8, 5 * np.pi / 4]


def three_body_values(d=2.0):
    return chain_values(THREE, 1.3, {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0,
                                     "phi": PHASES},
                        stop_values=[{"d": d, "k_c": 8.0, "c_c": 10.0}] * 2)


def test_three_body_chain_matches_scipy_with_located_switches():
    """Three Duffing bodies, stops between neighbours: 20 stroboscopic points to 1e-6."""
    system = chain_system(THREE)
    y0 = np.array([1.5, 0.0, -0.5, 1.0, -2.0, 0.0])
    problem, traj = sections(system, three_body_values(), y0, 20)
    assert traj.contacts.sum() > 5  # the stops engage
    rhs, switches = reference_chain(
        [1.0] * 3, [0.05] * 3, [1.0] * 3, [0.01] * 3, [1.0] * 3, PHASES, 1.3,
        [(0, 1, 2.0, 8.0, 10.0, "paper"), (1, 2, 2.0, 8.0, 10.0, "paper")])
    ref = scipy_sections(rhs, switches, y0, problem.period, 20)
    assert np.max(np.abs(traj.section_y - ref.y_eval)) < 1e-6
    assert traj.contacts.sum() == onsets(ref, 2)  # onsets counted on both stops


def test_two_sided_stop_matches_scipy():
    """One body between two walls (clearance), each a paper stop, with a mass != 1."""
    model = ChainModel(1, stops=(Stop(1, side="right"), Stop(1, side="left")))
    values = chain_values(model, 0.9, {"m": 1.5, "c": 0.1, "k1": 1.0, "k2": 0.0, "F": 2.0},
                          stop_values=[{"wall": 1.0, "k_c": 20.0, "c_c": 1.0},
                                       {"wall": -0.8, "k_c": 30.0, "c_c": 0.5}])
    y0 = np.array([0.2, 0.0])
    problem, traj = sections(chain_system(model), values, y0, 15)
    assert traj.contacts.sum() > 10
    rhs, switches = reference_chain(
        [1.5], [0.1], [1.0], [0.0], [2.0], [0.0], 0.9,
        [(0, None, (1.0, "right"), 20.0, 1.0, "paper"),
         (0, None, (-0.8, "left"), 30.0, 0.5, "paper")])
    ref = scipy_sections(rhs, switches, y0, problem.period, 15)
    assert np.max(np.abs(traj.section_y - ref.y_eval)) < 1e-6
    assert traj.contacts.sum() == onsets(ref, 2)  # both walls' onsets counted
    # the running maximum over both contact functions, per period, against the
    # referee's dense samples (x - 1 on the right wall, -0.8 - x on the left)
    times = np.linspace(0.0, 15 * problem.period, 15 * 400 + 1)
    dense = solve_with_events(rhs, y0, (0.0, times[-1]), switches, t_eval=times,
                              rtol=1e-12, atol=1e-13).y_eval[:, 0]
    g = np.maximum(dense - 1.0, -0.8 - dense).reshape(-1)[1:].reshape(15, 400).max(axis=1)
    assert np.all(np.abs(traj.max_g[1:] - g) < 1e-3)
    assert np.all(traj.max_g[1:] >= g - 1e-9)


def test_wall_stop_with_kink_and_no_tension_matches_scipy():
    """A softening Duffing body with a kink on its left and a no-tension wall stop on its
    right (the law's force surface watched in contact only)."""
    model = ChainModel(1, kinks=(Kink(1, "left"),), stops=(Stop(1, side="right",
                                                               law="no-tension"),))
    values = chain_values(model, 1.1, {"c": 0.05, "k1": 1.0, "k2": -0.02, "F": 1.2},
                          kinks=[{"x": -0.7, "k": 5.0}],
                          stop_values=[{"wall": 0.9, "k_c": 15.0, "c_c": 4.0}])
    y0 = np.array([0.0, 0.3])
    problem, traj = sections(chain_system(model), values, y0, 15)
    assert traj.contacts.sum() > 5
    assert traj.counters["switches"] > 2 * traj.contacts.sum()  # kink and force surface too
    rhs, switches = reference_chain(
        [1.0], [0.05], [1.0], [-0.02], [1.2], [0.0], 1.1,
        [(0, None, (0.9, "right"), 15.0, 4.0, "no-tension")], [(0, -0.7, "left", 5.0)])
    ref = scipy_sections(rhs, switches, y0, problem.period, 15)
    assert np.max(np.abs(traj.section_y - ref.y_eval)) < 1e-6


def test_stops_that_never_engage_leave_independent_duffing_bodies():
    """Gaps far beyond the motion: each body is the Duffing preset's body, its phase a
    shift of the start time (F sin(w t + phi) = F sin(w (t + phi / w)))."""
    system = chain_system(THREE)
    values = three_body_values(d=100.0)
    y0 = np.array([1.5, 0.0, -0.5, 1.0, -2.0, 0.0])
    problem = Problem(system, values, TIGHT)
    t1 = 7 * problem.period
    status, y, max_g = flow(problem, y0, 0.0, t1)
    assert status == 0 and max_g < -90.0
    body = Problem(get_system("duffing", 1),
                   {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0, "w": 1.3}, TIGHT)
    for i, phi in enumerate(PHASES):
        shift = phi / 1.3
        status, yi, _ = flow(body, y0[2 * i: 2 * i + 2], shift, t1 + shift)
        assert status == 0
        assert np.max(np.abs(yi - y[2 * i: 2 * i + 2])) < 1e-8


# ---------------------------------------------------------------- the presets as members

PAIR = ChainModel(2, stops=(Stop(1, 2),))
BILINEAR_PAIR = ChainModel(2, kinks=(Kink(1, "left"), Kink(2, "right")), stops=(Stop(1, 2),))


def duffing_pair_as_chain(v):
    return chain_values(PAIR, v["w"], {"c": v["c"], "k1": v["k1"], "k2": v["k2"],
                                       "F": v["F"], "phi": [0.0, v["phi"]]},
                        stop_values=[{"d": v["d"], "k_c": v["k_c"], "c_c": v["c_c"]}])


def bilinear_pair_as_chain(v):
    return chain_values(BILINEAR_PAIR, v["w"], {"c": v["c"], "k1": v["k1"], "k2": 0.0,
                                                "F": v["F"], "phi": [0.0, v["phi"]]},
                        kinks=[{"x": -v["d1"], "k": v["k2"]}, {"x": v["d1"], "k": v["k2"]}],
                        stop_values=[{"d": v["d"], "k_c": v["k_c"], "c_c": v["c_c"]}])


DUFFING = {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0, "w": 1.3, "d": 2.0, "phi": 1.9,
           "k_c": 8.0, "c_c": 10.0, "law": "paper"}
BILINEAR = {"c": 0.02, "k1": 1.0, "k2": 29.0, "F": 0.518, "w": 0.86, "d1": 1.26, "d": 0.5,
            "phi": 1.9, "k_c": 8.0, "c_c": 10.0, "law": "paper"}


@pytest.mark.parametrize("law", ["paper", "no-tension", "hunt-crossley"])
@pytest.mark.parametrize("model, values, chain, as_chain", [
    ("duffing", DUFFING, PAIR, duffing_pair_as_chain),
    ("bilinear", BILINEAR, BILINEAR_PAIR, bilinear_pair_as_chain),
])
def test_preset_pair_equals_its_chain_form(model, values, chain, as_chain, law):
    """Same surfaces, and rhs and Jacobian to 1e-12 in every mode at random states, for
    every stop law (Hunt-Crossley with exponent 1.7)."""
    preset = get_system(model, 2)
    chain = ChainModel(2, kinks=chain.kinks, stops=(Stop(1, 2, law=law),))
    member = chain_system(chain)
    values = dict(values, law=law, exponent=1.7)
    in_chain = dict(as_chain(values), **{"stop.1.exponent": 1.7})
    p_preset, p_chain = preset.pack(values), member.pack(in_chain)
    s_preset, s_chain = preset.surfaces(p_preset), member.surfaces(p_chain)
    assert np.array_equal(s_preset.A, s_chain.A) and np.array_equal(s_preset.b, s_chain.b)
    assert np.array_equal(s_preset.relevance, s_chain.relevance)
    assert s_preset.contacts == s_chain.contacts == 1
    rng = np.random.default_rng(3)
    for mode in range(1 << s_preset.A.shape[0]):
        for _ in range(5):
            t, y = rng.uniform(0, 10), rng.uniform(-3, 3, 4)
            y[0] = y[2] + values["d"] + rng.uniform(-0.5, 1.0)  # near and in contact
            a, b = np.empty(4), np.empty(4)
            preset.rhs(t, y, p_preset, mode, a)
            chain_rhs(t, y, p_chain, mode, b)
            assert np.allclose(a, b, rtol=0, atol=1e-12)
            ja, jb, da, db = np.empty((4, 4)), np.empty((4, 4)), np.empty(4), np.empty(4)
            preset.jacobian(t, y, p_preset, mode, ja, da)
            chain_jacobian(t, y, p_chain, mode, jb, db)
            assert np.allclose(ja, jb, rtol=0, atol=1e-12)
            assert np.allclose(da, db, rtol=0, atol=1e-12)


def test_duffing_pair_trajectory_equals_its_chain_form():
    """The same trajectory, impacts included, to 1e-9 over 10 periods (the arithmetic
    order differs: rounding, amplified by the adaptive steps)."""
    y0 = np.array([1.0, 0.0, -1.0, 0.5])
    _, preset = sections(get_system("duffing", 2), DUFFING, y0, 10)
    _, member = sections(chain_system(PAIR), duffing_pair_as_chain(DUFFING), y0, 10)
    assert preset.contacts.sum() > 0
    assert np.array_equal(preset.contacts, member.contacts)
    assert np.max(np.abs(preset.section_y - member.section_y)) < 1e-9


# ---------------------------------------------------------------- one compilation


def test_a_new_chain_compiles_nothing():
    """Two different chains in one process: the second adds no kernel signature."""
    first = ChainModel(2, stops=(Stop(1, 2),))
    second = ChainModel(4, powers=(5,), kinks=(Kink(3, "left"),),
                        stops=(Stop(1, 2, law="no-tension"), Stop(4, side="right"),
                               Stop(2, 3, law="hunt-crossley")))
    settings = IntegratorSettings()

    def run(model, values, dim):
        problem = Problem(chain_system(model), values, settings)
        flow(problem, np.linspace(-1, 1, dim), 0.0, problem.period)

    run(first, duffing_pair_as_chain(DUFFING), 4)
    dispatchers = [orbit.flow, chain_rhs, chain_jacobian]
    before = [len(d.signatures) for d in dispatchers]
    values = chain_values(second, 1.1, {"k_x5": [0.0, 0.001, 0.0, 0.0], "phi": [0, 1, 2, 3]},
                          kinks=[{"x": -1.0, "k": 4.0}],
                          stop_values=[{"d": 1.0}, {"wall": 1.5}, {"d": 0.5}])
    run(second, values, 8)
    assert [len(d.signatures) for d in dispatchers] == before


# ---------------------------------------------------------------- structure problems


@pytest.mark.parametrize("model, message", [
    (ChainModel(0), "bodies must be in 1..8, got 0"),
    (ChainModel(1000), "bodies must be in 1..8, got 1000"),
    (ChainModel(2, stops=(Stop(1, 3),)), "stop 1: body 3 does not exist (bodies 1..2)"),
    (ChainModel(2, stops=(Stop(2),)), "stop 1: a wall needs side = \"left\" or \"right\""),
    (ChainModel(2, kinks=(Kink(5, "left"),)), "kink 1: body 5 does not exist"),
    (ChainModel(8, stops=tuple(Stop(1, side="right", law="no-tension") for _ in range(9))),
     "18 switching surfaces (stops, kinks, no-tension force surfaces): at most 16"),
])
def test_structure_problems_are_named(model, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        chain_system(model)


def test_overlapping_kinks_and_wrong_list_lengths_are_named():
    model = ChainModel(2, kinks=(Kink(1, "left"), Kink(1, "left")))
    values = chain_values(model, 1.0, {}, kinks=[{"x": -1.0, "k": 2.0}, {"x": -1.0, "k": 3.0}])
    assert model.value_problems(values) == [
        "kinks 1 and 2 overlap: body 1, side 'left', position -1"]
    with pytest.raises(ValueError, match="phi: 3 values for 2 bodies"):
        chain_values(model, 1.0, {"phi": [0, 1, 2]})


# ---------------------------------------------------------------- the exact flow


def test_a_linear_chain_runs_on_the_exact_flow():
    """Three linear bodies, a kink, stops between bodies and against a wall: method
    "exact" (each mode's flow in closed form) agrees with tight dopri5; a cubic term is
    refused with the mode named."""
    model = ChainModel(3, kinks=(Kink(1, "left"),),
                       stops=(Stop(1, 2), Stop(2, 3, law="no-tension"),
                              Stop(3, side="left")))
    values = chain_values(model, 1.1, {"c": 0.1, "k1": [1.0, 1.5, 0.8], "F": 1.0,
                                       "phi": [0.0, 1.0, 2.0], "m": [1.0, 2.0, 0.5]},
                          kinks=[{"x": -1.0, "k": 3.0}],
                          stop_values=[{"d": 0.5, "k_c": 5.0, "c_c": 1.0},
                                       {"d": 0.5, "k_c": 5.0, "c_c": 1.0},
                                       {"wall": -1.5, "k_c": 10.0, "c_c": 0.5}])
    system = chain_system(model)
    assert system.piecewise_linear
    y0 = np.array([0.5, 0.0, -0.3, 0.2, 0.1, 0.0])
    _, exact = sections(system, values, y0, 10, IntegratorSettings(method="exact"))
    _, tight = sections(system, values, y0, 10)
    assert exact.contacts.sum() > 5
    assert np.max(np.abs(exact.section_y - tight.section_y)) < 1e-7
    cubic = dict(values, **{"k2.2": 0.01})
    with pytest.raises(ValueError, match="chain of 3: mode 0's right-hand side is not linear"):
        Problem(system, cubic, IntegratorSettings(method="exact"))
