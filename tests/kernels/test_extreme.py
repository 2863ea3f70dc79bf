"""A fast subset of the extreme corpus (benchmarks/bench_extreme.py) with the default method.

Every case must end in a status that is true: converged to an orbit that really is
periodic under a tight reference flow (and, where auto used Rodas4, the orbit plain dopri5
finds), or unresolved / diverged for the reason the status table gives. No crash, no
silent wrong orbit.
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.engine import classify_state, flow
from softimpact_cli.kernels.codes import CONVERGED, DIVERGED, UNRESOLVED, message

from .helpers import BILINEAR_PAIR, DUFFING_PAIR, problem

STIFF = dict(k_c=1e6, c_c=1e3)
TIGHT = dict(method="dopri5", rtol=1e-12, atol=1e-14)
DUFFING_STATES = [[2.0, 0.0, -2.0, 0.0], [-6.0, 0.0, 6.0, 0.0], [8.0, 0.0, -4.0, 0.0]]
BILINEAR_STATES = [[1.5, 0.0, -1.5, 0.0], [-2.0, 0.0, 2.0, 0.0], [2.5, 0.0, 0.5, 0.0]]

CONVERGING = {  # name -> (model, values); all from the bench's corners
    "stiff no-tension": ("duffing", dict(DUFFING_PAIR, **STIFF, law="no-tension")),
    "overdamped sticky no-tension": ("duffing", dict(DUFFING_PAIR, c_c=1e3, law="no-tension")),
    "stiff F=100": ("duffing", dict(DUFFING_PAIR, **STIFF, F=100.0)),
    "stiff d=0.01": ("duffing", dict(DUFFING_PAIR, **STIFF, d=0.01)),
    "undamped hard stop": ("duffing", dict(DUFFING_PAIR, k_c=1e6, c_c=0.0)),
    "bilinear k2=1e4 stiff no-tension": ("bilinear",
                                         dict(BILINEAR_PAIR, **STIFF, k2=1e4, law="no-tension")),
}


def orbit_residual(pr, cls) -> float:
    """|Phi^q(y*) - y*| / max(1, |y*|) under the tight flow (forcing is T-periodic)."""
    status, y, _ = flow(pr.with_integrator(**TIGHT), cls.orbit[0], 0.0, cls.period * pr.period)
    assert status == 0
    return float(np.max(np.abs(y - cls.orbit[0])) / max(1.0, np.max(np.abs(cls.orbit[0]))))


@pytest.mark.parametrize("name", list(CONVERGING))
def test_extreme_cases_converge_to_real_orbits(name):
    model, values = CONVERGING[name]
    pr = problem(model, 2, values)
    states = BILINEAR_STATES if model == "bilinear" else DUFFING_STATES
    for y0 in states:
        a = classify_state(pr, y0)
        assert a.status == CONVERGED, (name, y0, message(a.status))
        res = orbit_residual(pr, a)
        print(f"{name} {y0}: period {a.period}, residual {res:.1e}, "
              f"stiff {a.counters['stiff_steps']}/{a.counters['steps']}")
        assert res < 2e-5, (name, y0, res)
        if a.counters["stiff_steps"] > 0:  # the method mix changed nothing
            d = classify_state(pr.with_integrator(method="dopri5"), y0)
            assert d.status == CONVERGED and d.period == a.period
            shifts = [np.max(np.abs(np.roll(a.orbit, s, axis=0) - d.orbit))
                      for s in range(a.period)]
            assert min(shifts) < 1e-5


def test_a_far_stop_never_engages_and_nothing_switches():
    pr = problem("duffing", 2, dict(DUFFING_PAIR, **STIFF, d=100.0))
    a = classify_state(pr, DUFFING_STATES[1])
    assert a.status == CONVERGED and a.contacts == 0 and not a.impacting
    assert a.counters["stiff_steps"] == 0 and a.counters["switches"] == 0


def test_a_long_transient_says_unresolved_and_why():
    """c = 1e-3 and a stop out of reach (no impact damping): the transient decays like
    exp(-c t / 2), over thousands of periods."""
    pr = problem("duffing", 2, dict(DUFFING_PAIR, c=1e-3, d=100.0), max_periods=200)
    a = classify_state(pr, DUFFING_STATES[1])
    assert a.status == UNRESOLVED and a.periods_used == 200 and a.outcome == "unresolved"
    assert "max_periods" in message(a.status)


def test_an_escaping_softening_spring_says_diverged_and_why():
    """k2 < 0 (softening Duffing) driven hard: the bodies escape over the potential's top."""
    pr = problem("duffing", 2, dict(DUFFING_PAIR, **STIFF, k2=-1.0, F=10.0))
    a = classify_state(pr, DUFFING_STATES[0])
    assert a.status == DIVERGED and a.outcome == "diverged"
    assert "divergence_bound" in message(a.status)
