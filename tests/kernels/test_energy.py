"""Energy balance of the unforced, undamped Duffing pair through contacts.

With F = 0 and c = 0 the only dissipation is the stop's damper, so

    E = sum_i (v_i^2/2 + k1 x_i^2/2 + k2 x_i^4/4) + (k_c/2) delta^2 [delta > 0]

(delta = x1 - x2 - d) obeys dE/dt = -c_c (v1 - v2)^2 in contact, 0 outside: the energy a
contact phase removes is the damper's work over it.

The work is integrated by the kernels themselves, the way the package is meant to be
extended: this module defines a *new system* (the pair plus a fifth state variable
W' = c_c (v1 - v2)^2 while the stop acts), builds a ``System`` from
``softimpact_cli.systems.base`` and runs it through ``Problem``/``record_trajectory``
without touching the kernels. E + W must then be constant along the whole trajectory.
"""

from __future__ import annotations

from math import cos, sin

import numpy as np
import pytest
from numba import njit

from softimpact_cli.analysis.engine import Problem, classify_state, record_trajectory
from softimpact_cli.kernels.codes import CONVERGED, OK
from softimpact_cli.systems.base import (
    COUPLING_PARAMETERS,
    Parameter,
    Surfaces,
    System,
    relevance_table,
)
from softimpact_cli.systems.duffing import (
    BODY_PARAMETERS,
    CC,
    COS_PHI,
    K1,
    K2,
    KC,
    LAW,
    SIN_PHI,
    STOP,
    C,
    D,
    F,
    W,
    pack_pair,
)
from softimpact_cli.systems.stops import COUPLING_SIZE
from tests import naive

from .helpers import DUFFING_PAIR, stable_identity

# packed after the pair's parameters: 1.0 = W integrates the whole stop force
STOP_WORK = STOP + COUPLING_SIZE


def pack_work_pair(values) -> np.ndarray:
    return np.append(pack_pair(values), float(values.get("stop_work", 0.0)))


@njit
def work_rhs(t, y, p, mode, out):
    """Duffing pair (same packed parameters and mode bits as the package's) + the work
    W' = c_c (v1 - v2)^2 of the stop's damper (or F_C (v1 - v2) of the whole stop)."""
    x1, v1, x2, v2 = y[0], y[1], y[2], y[3]
    fc = 0.0
    power = 0.0
    if mode & 1 and (p[LAW] == 0.0 or mode & 2):
        fc = p[KC] * (x1 - x2 - p[D]) + p[CC] * (v1 - v2)
        if p[STOP_WORK] != 0.0:
            power = fc * (v1 - v2)
        else:
            power = p[CC] * (v1 - v2) * (v1 - v2)
    s = sin(p[W] * t)
    co = cos(p[W] * t)
    out[0] = v1
    out[1] = p[F] * s - p[C] * v1 - p[K1] * x1 - p[K2] * x1 * x1 * x1 - fc
    out[2] = v2
    out[3] = (p[F] * (s * p[COS_PHI] + co * p[SIN_PHI]) - p[C] * v2 - p[K1] * x2
              - p[K2] * x2 * x2 * x2 + fc)
    out[4] = power


@njit
def work_jacobian(t, y, p, mode, jac, dfdt):  # not used by the explicit kernels
    jac[:, :] = np.nan
    dfdt[:] = np.nan


def work_surfaces(p: np.ndarray) -> Surfaces:
    """The pair's surfaces (x1 - x2 - d, and the stop force for no-tension), W ignored."""
    A = [[1.0, 0.0, -1.0, 0.0, 0.0]]
    b = [-p[D]]
    requires = {}
    if p[LAW] != 0.0:
        A.append([p[KC], p[CC], -p[KC], -p[CC], 0.0])
        b.append(-p[KC] * p[D])
        requires[1] = 0
    return Surfaces(np.array(A), np.array(b), relevance_table(len(A), requires), 1,
                    ("contact", "stop force")[: len(A)])


stable_identity(repr((C, K1, K2, F, W, D, KC, CC, COS_PHI, SIN_PHI, LAW, STOP_WORK)),
                work_rhs, work_jacobian)

WORK_PAIR = System(
    model="duffing-work",
    bodies=2,
    description="Duffing pair with the stop damper's work as a fifth state",
    state_names=("x1", "v1", "x2", "v2", "W"),
    parameters=BODY_PARAMETERS + COUPLING_PARAMETERS
    + (Parameter("stop_work", "1", 0.0, "1: W is the work of the whole stop force"),),
    rhs=work_rhs,
    jacobian=work_jacobian,
    pack=pack_work_pair,
    surfaces=work_surfaces,
)

FREE = dict(DUFFING_PAIR, F=0.0, c=0.0, phi=0.0)  # d = 1, k_c = 8, c_c = 10
RTOL = 1e-7


def run(values, y0, periods, samples=200, **integrator):
    settings = dict(method="dopri5", rtol=1e-11, atol=1e-13)
    settings.update(integrator)
    pr = Problem(WORK_PAIR, values).with_integrator(**settings)
    tr = record_trajectory(pr, np.concatenate([y0, [0.0]]), 0.0, periods, samples)
    assert tr.status == OK
    return pr, tr


@pytest.fixture(scope="module")
def contact_run():
    # bodies apart, rushing together: an onset, a long compression, then grazing touches
    return run(FREE, [0.0, 2.0, 0.0, -2.0], 6)


def test_the_new_system_is_the_pair_plus_one_state():
    """Sanity: its first four components are exactly the package's Duffing pair."""
    from softimpact_cli.systems import get_system

    pair = get_system("duffing", 2)
    rng = np.random.default_rng(7)
    for law in ("paper", "no-tension"):
        p = pack_work_pair(dict(DUFFING_PAIR, phi=0.7, law=law))
        for _ in range(50):
            y = np.append(rng.uniform(-3, 3, 4), 0.0)
            for mode in range(2 ** work_surfaces(p).A.shape[0]):
                a = np.empty(5)
                b = np.empty(4)
                work_rhs(1.3, y, p, mode, a)
                pair.rhs(1.3, y[:4], p[:STOP_WORK], mode, b)
                np.testing.assert_array_equal(a[:4], b)


def test_energy_lost_equals_damper_work(contact_run):
    pr, tr = contact_run
    E = naive.duffing_pair_energy(tr.y[:, :4], FREE)
    Wk = tr.y[:, 4]
    E0 = E[0]
    assert tr.contacts.sum() >= 2
    # the stop really dissipated: a sizeable share of the energy is gone
    assert Wk[-1] > 0.05 * E0, (Wk[-1], E0)
    drift = np.max(np.abs(E + Wk - E0)) / E0
    print(f"energy balance: E0 = {E0:.6f}, work = {Wk[-1]:.6f}, max |E + W - E0|/E0 = {drift:.2e}")
    assert drift < RTOL


def test_each_contact_phase_balances(contact_run):
    """Phase by phase: E before minus E after a contact = damper work in between."""
    pr, tr = contact_run
    delta = tr.y[:, 0] - tr.y[:, 2] - FREE["d"]
    E = naive.duffing_pair_energy(tr.y[:, :4], FREE)
    Wk = tr.y[:, 4]
    inside = delta > 0
    # samples just outside each contact phase
    edges = np.flatnonzero(np.diff(inside.astype(int)))
    starts = [i for i in edges if not inside[i]]  # last free sample before contact
    ends = [i + 1 for i in edges if inside[i]]  # first free sample after contact
    phases = [(s, next(e for e in ends if e > s)) for s in starts if any(e > s for e in ends)]
    assert len(phases) >= 3
    for k, (s, e) in enumerate(phases):
        lost = E[s] - E[e]
        work = Wk[e] - Wk[s]
        assert lost > (0.5 if k == 0 else 1e-6) * E[0], (k, lost)
        assert abs(lost - work) <= RTOL * E[0], (s, e, lost, work)
    # before the first contact nothing is dissipated
    assert np.all(Wk[: starts[0] + 1] == 0.0) or inside[0]


def test_energy_conserved_without_contact():
    values = dict(FREE, d=50.0)
    pr, tr = run(values, [3.0, 0.5, -2.0, 1.0], 6)
    assert tr.contacts.sum() == 0 and tr.counters["switches"] == 0
    E = naive.duffing_pair_energy(tr.y[:, :4], values)
    assert np.all(tr.y[:, 4] == 0.0)
    drift = np.max(np.abs(E - E[0])) / E[0]
    print(f"no contact: max |E - E0|/E0 = {drift:.2e}")
    assert drift < RTOL


@pytest.mark.parametrize("law", ["paper", "no-tension"])
def test_stop_work_balances_the_bodies_energy(law):
    """With W = integral of F_C (v1 - v2) dt, the bodies' own energy (no stop potential)
    plus W is constant, for either law. For the clipped law the stop potential is not an
    energy (it vanishes when the force is clipped), so this is the balance to check."""
    values = dict(FREE, law=law, stop_work=1.0)
    pr, tr = run(values, [0.0, 2.0, 0.0, -2.0], 6)
    E_bodies = naive.duffing_pair_energy(tr.y[:, :4], dict(values, k_c=0.0))
    Wk = tr.y[:, 4]
    drift = np.max(np.abs(E_bodies + Wk - E_bodies[0])) / E_bodies[0]
    print(f"{law}: stop work {Wk[-1]:.6f} of E0 = {E_bodies[0]:.6f}, drift {drift:.2e}")
    assert Wk[-1] > 0.05 * E_bodies[0]
    assert drift < RTOL, drift
    if law == "no-tension":
        assert tr.counters["switches"] > 2 * tr.contacts.sum()  # force surface crossed too


def test_new_system_classifies_through_the_engine():
    """classify_state runs the new system unchanged: far apart (no contact, W stays 0) it
    finds the same period-1 orbit as the package's own Duffing pair."""
    from softimpact_cli.systems import get_system

    values = dict(DUFFING_PAIR, d=50.0, phi=1.0)
    settings = dict(method="dopri5", rtol=1e-10, atol=1e-12, convergence_tol=1e-9)
    mine = classify_state(Problem(WORK_PAIR, values).with_integrator(**settings),
                          [3.0, 0.0, -3.0, 0.0, 0.0])
    theirs = classify_state(Problem(get_system("duffing", 2), values).with_integrator(**settings),
                            [3.0, 0.0, -3.0, 0.0])
    assert mine.status == theirs.status == CONVERGED
    assert mine.period == theirs.period
    assert mine.contacts == 0 and np.all(mine.orbit[:, 4] == 0.0)
    np.testing.assert_allclose(mine.orbit[:, :4], theirs.orbit, rtol=0, atol=1e-9)
