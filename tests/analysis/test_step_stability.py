"""The fixed-step RK4 stability check run before a scene starts."""

import math
import re

import numpy as np

from softimpact_cli.analysis.engine import Problem, classify_state
from softimpact_cli.analysis.step_stability import largest_stable_step, rk4_step_warning
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems import get_system

STIFF = dict(c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3, d=1.0, phi=math.pi, k_c=1e6, c_c=1e3,
             law="paper")


def test_real_axis_limit_of_rk4():
    # RK4's stability interval on the negative real axis ends at about -2.785
    assert largest_stable_step(np.array([-1.0])) == np.float64(
        largest_stable_step(np.array([-1.0]))) and abs(
        largest_stable_step(np.array([-1.0])) - 2.7852935) < 1e-6


def test_stiff_stop_warns_and_the_suggested_step_is_stable():
    problem = Problem(get_system("duffing", 2), STIFF, IntegratorSettings(method="rk4"))
    message = rk4_step_warning(problem)
    assert message is not None and "method 'stiff'" in message
    need = int(re.search(r"stable from steps_per_period >= (\d+)", message).group(1))
    assert 1440 < need < 10_000
    assert classify_state(problem, [2.0, 0.0, -2.0, 0.0]).outcome == "diverged"
    # the promise is stability: bounded, integrated to the end of its budget (near the
    # limit the contact phase is too coarse for the section points to settle to 1e-6)
    fixed = problem.with_integrator(steps_per_period=int(need * 1.05), max_periods=60)
    assert rk4_step_warning(fixed) is None
    result = classify_state(fixed, [2.0, 0.0, -2.0, 0.0])
    assert result.outcome != "diverged" and result.periods_used == 60
    # and well above the limit RK4 converges to the impacting period-1 orbit
    fine = problem.with_integrator(steps_per_period=14400, max_periods=60)
    converged = classify_state(fine, [2.0, 0.0, -2.0, 0.0])
    assert converged.outcome == "converged" and converged.period == 1 and converged.impacting


def test_no_warning_for_soft_stops_or_adaptive_methods():
    soft = {**STIFF, "k_c": 8.0, "c_c": 10.0}
    assert rk4_step_warning(Problem(get_system("duffing", 2), soft,
                                    IntegratorSettings(method="rk4"))) is None
    assert rk4_step_warning(Problem(get_system("duffing", 2), STIFF,
                                    IntegratorSettings(method="dopri5"))) is None
