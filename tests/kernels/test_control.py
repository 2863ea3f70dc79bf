"""Step-size control of the adaptive driver (kernels/control.py)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.kernels import control, layout
from softimpact_cli.kernels.control import Controller

DOPRI = Controller(5, 0.9, 0.2, 10.0, 0.5, False)
RODAS = Controller(4, 0.9, 0.2, 6.0, 0.5, True)


def test_first_step_carries_the_last_proposal_or_takes_a_percent_of_the_span():
    opts = np.zeros(layout.N_OPTS)
    opts[layout.H_MAX] = 0.5
    fstate = np.zeros(layout.N_FSTATE)
    floor, h = control.first_step(0.0, 10.0, opts, fstate)
    assert h == 0.1 and floor == control.H_FLOOR * 10.0
    floor, h = control.first_step(0.0, 100.0, opts, fstate)
    assert h == 0.5  # capped by the largest step
    fstate[layout.H] = 0.03
    assert control.first_step(0.0, 100.0, opts, fstate)[1] == 0.03


def test_landing_hits_the_end_time_exactly():
    assert control.landing(0.1, 0.5, 0.0, 1.0) == (0.1, 0.1, False)
    assert control.landing(0.7, 0.5, 0.0, 1.0) == (0.5, 0.5, False)  # capped
    h, step, truncated = control.landing(0.3, 0.5, 0.8, 1.0)
    assert h == 0.3 and truncated and 0.8 + step == 1.0
    # within 0.01 % of the end the step is stretched onto it instead of leaving a sliver
    h, step, truncated = control.landing(0.19999, 0.5, 0.8, 1.0)
    assert truncated and 0.8 + step == 1.0


def test_a_refused_step_shrinks_by_the_elementary_controller():
    assert control.rejects(False, 0.5) and control.rejects(True, np.inf)
    assert control.rejects(True, np.nan) and control.rejects(True, 1.01)
    assert not control.rejects(True, 1.0)
    assert control.reject_factor(False, 0.5, RODAS) == 0.5  # singular matrix
    assert control.reject_factor(True, np.inf, DOPRI) == 0.2
    assert control.reject_factor(True, 32.0, DOPRI) == 0.9 * 32.0 ** (-1 / 5)
    assert control.reject_factor(True, 1e9, DOPRI) == 0.2


@given(st.floats(0.0, 1.0), st.sampled_from([DOPRI, RODAS]))
def test_growth_stays_within_the_bounds(err, c):
    fac = control.accept_factor(err, c)
    assert c.fac_min <= fac <= c.fac_max
    if err > 0.0:
        assert fac == min(c.fac_max, max(c.fac_min, c.safety * err ** (-1.0 / c.order)))


def test_next_step_after_a_rejection_and_after_landing():
    h_step, h = 0.1, 0.2
    grow = h_step * control.accept_factor(1e-3, RODAS)
    assert control.next_step(1e-3, RODAS, h_step, h, False, False) == grow
    assert control.next_step(1e-3, RODAS, h_step, h, True, False) == h_step  # no growth
    assert control.next_step(1e-3, DOPRI, h_step, h, True, False) > h_step  # dopri5 may grow
    # a step cut short to land on the end time keeps the proposal it was cut from
    assert control.next_step(0.99, DOPRI, 0.01, 0.2, False, True) == 0.2
