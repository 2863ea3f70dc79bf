"""Contestant 2 of the basin benchmark: the study's method on softimpact's kernels.

RK4 at T/1440 without switch location, a fixed transient of 1000 forcing periods (no
early stop), then classification of the final state (at most 100 more periods), named
with the catalogue as a sweep names an outcome.
"""

from __future__ import annotations

from dataclasses import dataclass

from softimpact_cli.analysis.catalogue import label_orbit
from softimpact_cli.analysis.engine import Problem, classify_state, flow
from softimpact_cli.analysis.labels import DIVERGED, UNRESOLVED
from softimpact_cli.kernels.codes import outcome

TRANSIENT_PERIODS = 1000  # the study's fixed transient (forcing periods)
CLASSIFY_PERIODS = 100  # after it: periods allowed to find the repeat
MAX_ORBIT_PERIOD = 30


@dataclass(frozen=True)
class StudyMethod:
    """The two problems of the study's method at a scene's parameter point, and the
    catalogue that names the outcomes."""

    transient: Problem  # RK4 T/1440, no switch location
    classify: Problem  # the same, classifying within CLASSIFY_PERIODS
    catalogue: object
    label_tol: float

    @classmethod
    def of(cls, scene, catalogue) -> StudyMethod:
        transient = Problem(scene.system, dict(scene.values), scene.integrator) \
            .with_integrator(method="rk4", steps_per_period=1440, locate_switches=False)
        classify = transient.with_integrator(max_periods=CLASSIFY_PERIODS,
                                             max_orbit_period=MAX_ORBIT_PERIOD)
        return cls(transient, classify, catalogue, scene.analysis.label_tol)

    def label(self, state) -> str:
        """The label of one initial state (x1, v1, x2, v2 at t = 0)."""
        t_end = TRANSIENT_PERIODS * self.transient.period
        status, y, _ = flow(self.transient, state, 0.0, t_end)
        if status != 0:
            return UNRESOLVED if outcome(status) == "unresolved" else DIVERGED
        cls = classify_state(self.classify, y, t_end)
        if cls.status != 0:
            return UNRESOLVED if outcome(cls.status) == "unresolved" else DIVERGED
        return label_orbit(self.catalogue, cls.orbit, cls.impacting, self.label_tol).name
