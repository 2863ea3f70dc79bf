"""From parameter values to kernel calls: the one place that packs arrays for the kernels.

Analyses build a :class:`Problem` (a system at one parameter point with integrator
settings) and call :func:`classify_state` or :func:`record_trajectory`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from functools import cache, cached_property
from typing import Any

import numpy as np

from ..config import IntegratorSettings
from ..kernels import IMPACT_ADVANCE, METHODS, cells, layout, orbit
from ..kernels.codes import CONVERGED, MIXED_CELL, NO_ORBIT, outcome
from ..systems import Surfaces, System
from ..systems.piecewise_linear import with_exact_block

# istate[:layout.N_COUNTERS]; "stiff_steps" are the Rodas4 steps (the others explicit),
# "method_switches" the changes of method within `auto`
COUNTER_NAMES = ("mode", "steps", "rejected_steps", "rhs_evaluations", "switches", "contacts",
                 "samples", "stiff_steps", "method_switches")


# the impact loop's counters (kernels/impacts.py), in results of systems with rigid stops
IMPACT_COUNTERS = {"impacts": layout.N_IMPACTS, "chatter_sequences": layout.N_CHATTERS,
                   "sticking_phases": layout.N_STICKS}


def impact_counters(counters: np.ndarray) -> dict[str, int]:
    """The impact loop's counters of the kernels' istate as {name: value}."""
    return {name: int(counters[i]) for name, i in IMPACT_COUNTERS.items()}


def counter_dict(counters: np.ndarray) -> dict[str, int]:
    """The kernels' istate as {name: value} (its tail is auto's running state, not counted)."""
    return dict(zip(COUNTER_NAMES, map(int, counters[: layout.N_COUNTERS]), strict=True))


@dataclass(frozen=True)
class Problem:
    """A system at one parameter point, with the settings to integrate it."""

    system: System
    values: Mapping[str, Any]
    integrator: IntegratorSettings = field(default_factory=IntegratorSettings)

    def __post_init__(self):
        params = self.system.pack(self.values)
        if self.integrator.traits.closed_form:
            if self.system.variational:  # its fundamental matrix: an explicit method
                object.__setattr__(self, "integrator", replace(self.integrator, method="dopri5"))
            else:  # the modes' flows travel behind the parameters (kernels/exact.py)
                params = with_exact_block(self.system, params)
        object.__setattr__(self, "params", params)
        object.__setattr__(self, "surfaces", self.system.surfaces(self.params))

    params: np.ndarray = field(init=False, repr=False, compare=False)
    surfaces: Surfaces = field(init=False, repr=False, compare=False)

    @property
    def period(self) -> float:
        """Forcing period T = 2 pi / w."""
        return self.system.period(self.params)

    def with_values(self, **changes) -> Problem:
        return replace(self, values={**self.values, **changes})

    def with_integrator(self, **changes) -> Problem:
        return replace(self, integrator=replace(self.integrator, **changes))

    def options(self, sample_dt: float = 0.0, sample_t0: float = 0.0) -> np.ndarray:
        """The kernels' ``opts`` array (see ``kernels.layout``)."""
        s = self.integrator
        opts = np.zeros(layout.N_OPTS)
        opts[layout.RTOL] = s.rtol
        opts[layout.ATOL] = s.atol
        opts[layout.H_FIXED] = self.period / s.steps_per_period
        opts[layout.LOCATE] = 1.0 if s.locate_switches else 0.0
        opts[layout.H_MAX] = self.period / 8.0  # keeps dense-output sampling of g fine enough
        opts[layout.MAX_STEPS] = s.max_steps_per_period
        opts[layout.BOUND] = s.divergence_bound
        opts[layout.SAMPLE_DT] = sample_dt
        opts[layout.SAMPLE_T0] = sample_t0
        opts[layout.MAX_SWITCHES] = s.max_switches_per_period
        return opts

    @property
    def advance(self):
        """The integration method's kernel (see ``kernels.driver``); with rigid stops, its
        impact loop (``kernels.impacts``)."""
        if self.system.extra.get("rigid"):
            return IMPACT_ADVANCE[self.integrator.resolved_method]
        return METHODS[self.integrator.resolved_method].advance

    def kernel_args(self):
        sf = self.surfaces
        return sf.A, sf.b, sf.relevance, sf.contacts


@dataclass(frozen=True)
class KnownOrbits:
    """Stable orbits known before integrating (see ``kernels.orbit.classify_near``).

    points : (K, Q, dim) section points in time order, rows beyond each period unused;
    periods : (K,) int periods; max_g : (K,) max of x1 - x2 - d along each orbit (< 0:
    no contact); capture_tol, capture_hits : the capture rule.
    """

    points: np.ndarray
    periods: np.ndarray
    max_g: np.ndarray
    capture_tol: float
    capture_hits: int

    @classmethod
    def from_orbits(cls, orbits: list[np.ndarray], max_g, capture_tol: float,
                    capture_hits: int, dim: int) -> KnownOrbits:
        """Pack orbits, each (q, dim) in time order, into the kernel's arrays."""
        q_max = max((len(o) for o in orbits), default=1)
        points = np.zeros((len(orbits), q_max, dim))
        for k, o in enumerate(orbits):
            points[k, : len(o)] = o
        return cls(points, np.array([len(o) for o in orbits], dtype=np.int64),
                   np.asarray(max_g, dtype=np.float64).reshape(len(orbits)),
                   float(capture_tol), int(capture_hits))

    @cached_property
    def bundle(self) -> orbit.Known:
        """The kernel's ``Known`` bundle (built once: every trajectory passes it)."""
        return orbit.Known(self.points, self.periods, self.max_g, self.capture_tol,
                           self.capture_hits)


def no_known_orbits(dim: int) -> KnownOrbits:
    return KnownOrbits.from_orbits([], [], 0.0, 1, dim)


class RecurrenceCells:
    """The section cells earlier trajectories of one parameter point labelled
    (``kernels.cells``): boxes of side ``size``; a trajectory takes a label after ``hits``
    consecutive periods in cells of that label. Start a new one per parameter point."""

    def __init__(self, size: float, hits: int, max_periods: int):
        self.size = float(size)
        self.hits = int(hits)
        self.table = cells.new_cells()
        self.visited = np.empty(max_periods + 1, dtype=np.int64)  # filled by each classify
        self.bundle = orbit.Cells(self.size, self.hits, self.visited)  # the kernel's bundle

    def remember(self, classification: Classification, code: int) -> None:
        """Mark the cells the last classified trajectory visited with its label code."""
        n = min(classification.periods_used + 1, self.visited.size)
        cells.remember_cells(self.table, self.visited, n, code)


@dataclass(frozen=True)
class Classification:
    """Outcome of one trajectory on the stroboscopic section.

    orbit : (period, dim) section points of the final orbit in time order (empty unless
    converged). max_penetration : max of x1 - x2 - d over the final orbit (> 0: the stop
    is compressed; -inf when the system has no contact).
    """

    status: int
    period: int
    periods_used: int
    orbit: np.ndarray
    contacts: int
    max_penetration: float
    counters: dict[str, int]
    captured: int = NO_ORBIT  # index of the known orbit that captured it
    cell_code: int = MIXED_CELL  # label code taken from recurrence cells (orbit unknown)
    # the impact loop's counters over the whole integration (``impact_counters``); empty
    # for a system without rigid stops
    impacts: dict[str, int] = field(default_factory=dict)

    @property
    def outcome(self) -> str:
        return outcome(self.status)

    @property
    def impacting(self) -> bool:
        return self.status == CONVERGED and self.max_penetration >= 0.0


@cache
def _no_cells() -> RecurrenceCells:
    """An empty, disabled table: the kernel keeps one signature with or without cells."""
    return RecurrenceCells(0.0, 1, 0)


def classify_state(problem: Problem, state, t0: float = 0.0,
                   known: KnownOrbits | None = None,
                   recurrence: RecurrenceCells | None = None) -> Classification:
    """Integrate from ``state`` imposed at time ``t0`` until classified (or captured by
    one of the ``known`` stable orbits of this parameter point, or by the ``recurrence``
    cells earlier trajectories of this point labelled)."""
    y0 = np.array(state, dtype=np.float64)  # a writable copy: one kernel signature
    s = problem.integrator
    if known is None:
        known = no_known_orbits(y0.shape[0])
    if recurrence is None:
        recurrence = _no_cells()
    out = orbit.classified(orbit.classify_near(
        problem.advance, problem.system.rhs, problem.params, (y0, float(t0), problem.period),
        problem.kernel_args(), problem.options(),
        (s.max_periods, s.max_orbit_period, s.convergence_tol),
        known.bundle, recurrence.bundle, recurrence.table,
    ))
    q = int(out.period)
    return Classification(
        status=int(out.status), period=q, periods_used=int(out.periods_used),
        orbit=out.orbit[:q].copy(), contacts=int(out.contacts),
        max_penetration=float(out.max_g), counters=counter_dict(out.counters),
        captured=int(out.captured), cell_code=int(out.cell_code),
        impacts=impact_counters(out.counters) if problem.system.extra.get("rigid") else {},
    )


def flow(problem: Problem, state, t0: float, t1: float, contacts: int | None = None
         ) -> tuple[int, np.ndarray, float]:
    """(status, state at t1, max of the contact function on [t0, t1]) from ``state`` at t0.

    contacts : the bit mask of the surfaces whose running maximum is returned (default the
        system's contact surfaces, all of a chain's stops at once; ``1 << s``: surface s
        alone). It changes nothing else: the integration watches every surface.
    """
    y0 = np.array(state, dtype=np.float64)  # a writable copy: one kernel signature
    A, b, relevance, mask = problem.kernel_args()
    surfaces = (A, b, relevance, mask if contacts is None else int(contacts))
    status, y, max_g, _ = orbit.flow(problem.advance, problem.system.rhs, problem.params, y0,
                                     float(t0), float(t1), surfaces, problem.options())
    return int(status), y, float(max_g)


def contact_maxima(problem: Problem, state, t0: float, t1: float) -> np.ndarray:
    """Max of each contact function on [t0, t1] from ``state`` at t0: (n_contacts,), one
    per contact surface in order (a chain's stops), -inf for none. One flow per surface,
    each counting that surface alone (the contact mask is bookkeeping only: the flows are
    the same arithmetic as ``flow``'s, so no new kernel and no new compilation)."""
    y0 = np.array(state, dtype=np.float64)
    sf = problem.surfaces
    out = np.full(len(sf.contact_indices), -np.inf)
    for k, i in enumerate(sf.contact_indices):
        _, _, max_g, _ = orbit.flow(problem.advance, problem.system.rhs, problem.params,
                                    y0.copy(), float(t0), float(t1),
                                    (sf.A, sf.b, sf.relevance, 1 << i), problem.options())
        out[k] = max_g
    return out


@dataclass(frozen=True)
class Trajectory:
    """A recorded trajectory.

    t : (n_samples,) sample times; y : (n_samples, dim) dense samples;
    section_t : (periods + 1,) stroboscopic times; section_y : (periods + 1, dim);
    contacts : (periods + 1,) contact onsets per period (entry 0: before the first section);
    max_g : (periods + 1,) max of x1 - x2 - d per period; impacts : the impact loop's
    counters (``impact_counters``) and sticking_time, the time spent stuck on rigid stops.
    """

    status: int
    t: np.ndarray
    y: np.ndarray
    section_t: np.ndarray
    section_y: np.ndarray
    contacts: np.ndarray
    max_g: np.ndarray
    counters: dict[str, int]
    impacts: dict[str, int] = field(default_factory=dict)
    sticking_time: float = 0.0


def record_trajectory(problem: Problem, state, t0: float, periods: int,
                      samples_per_period: int) -> Trajectory:
    """Integrate ``periods`` forcing periods from the first section at or after ``t0``,
    sampling the dense output ``samples_per_period`` times per period from ``t0`` on."""
    y0 = np.array(state, dtype=np.float64)  # a writable copy: one kernel signature
    T = problem.period
    dt = T / samples_per_period
    n0 = int(orbit.first_section(float(t0), T))
    t_end = (n0 + periods) * T
    capacity = int(np.floor((t_end - t0) / dt + 1e-9)) + 1
    out = orbit.recorded(orbit.record(
        problem.advance, problem.system.rhs, problem.params, (y0, float(t0), T), int(periods),
        problem.kernel_args(), problem.options(dt, float(t0)), capacity))
    n = out.n_samples
    return Trajectory(int(out.status), out.sample_t[:n], out.sample_y[:n], out.section_t,
                      out.section_y, out.contacts, out.max_g, counter_dict(out.counters),
                      impact_counters(out.counters), float(out.sticking_time))
