"""One trajectory: dense time series, stroboscopic points and its classification.

The classification is a sweep's, for one start: the first pass (``classify_state``) and,
when it finds no period (``unresolved``) and ``section_periods > 0``, the same second
stage (``section_follow.follow_section``, then ``nonperiodic.identify`` with the same
Lyapunov spectrum ``nonperiodic.section_spectrum``): a long-period orbit, a chaotic or
quasi-periodic attractor named ``chaotic A1`` etc. with its exponents (the result's
``nonperiodic_*`` variables, as a sweep stores them), or a long transient.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..kernels.codes import (
    BY_KNOWN_ORBIT,
    BY_OWN_REPEAT,
    BY_SECTION,
    CLASSIFIED_BY,
    CONVERGED,
    UNRESOLVED,
    message,
    outcome,
)
from .engine import (
    Classification,
    Problem,
    classify_state,
    contact_maxima,
    record_trajectory,
)
from .nonperiodic import SETTLING, Recurrent, attractor_table, identify, section_spectrum
from .section_follow import FAILED, PERIODIC, RECURRENT, follow_section

NOT_RUN = "not run"  # second_stage attribute: the first pass classified it (or stage off)


@dataclass(frozen=True)
class TwoStageClassification:
    """What both stages say about one start.

    outcome : converged, unresolved, diverged, or the attractor kind (chaotic,
    quasi-periodic, impacting chaotic, impacting quasi-periodic); label : the
    attractor's name for a recurrent set ("chaotic A1"), else ""; status : kernel status
    (CONVERGED after a long-period orbit; a recurrent set keeps the first pass's
    UNRESOLVED, as in sweeps); orbit : (period, dim) section points of the periodic
    orbit; periods_used : both stages; second_stage : the follow's outcome or NOT_RUN;
    table : the attractor table (``nonperiodic.attractor_table``; empty without one);
    settled_from (dim,), settled_periods : where the final orbit or attractor can be
    followed again, and for how many periods (its first section point and its period, or
    a recurrent set's first located point and its point count; 0: nothing settled).
    """

    outcome: str
    label: str
    status: int
    message: str
    period: int
    orbit: np.ndarray
    periods_used: int
    contacts: int
    max_penetration: float
    impacting: bool
    classified_by: int
    second_stage: str
    first: Classification
    table: xr.Dataset = field(default_factory=xr.Dataset)
    settled_from: np.ndarray = field(default_factory=lambda: np.zeros(0))
    settled_periods: int = 0


def classify_both_stages(problem: Problem, state, t0: float) -> TwoStageClassification:
    """The first pass from ``state`` at ``t0`` and, when it ends ``unresolved``, the
    sweeps' second stage (see the module docstring)."""
    cls = classify_state(problem, state, t0)
    how = BY_KNOWN_ORBIT if cls.captured >= 0 else BY_OWN_REPEAT
    first = dict(first=cls, label="", status=cls.status, orbit=cls.orbit, period=0,
                 contacts=0, max_penetration=-np.inf, impacting=False,
                 classified_by=BY_SECTION)
    s = problem.integrator
    if cls.status != UNRESOLVED or s.section_periods <= 0:
        return TwoStageClassification(
            **{**first, "period": cls.period, "contacts": cls.contacts,
               "max_penetration": cls.max_penetration, "impacting": cls.impacting,
               "classified_by": how, **_settled(cls.orbit, cls.period)},
            outcome=cls.outcome, message=message(cls.status),
            periods_used=cls.periods_used, second_stage=NOT_RUN)
    follow = follow_section(problem, state, t0, cls.periods_used)
    first.update(periods_used=cls.periods_used + follow.periods, second_stage=follow.outcome)
    if follow.outcome == FAILED:
        return TwoStageClassification(**{**first, "status": follow.status},
                                      outcome=outcome(follow.status),
                                      message=message(follow.status))
    if follow.outcome == PERIODIC:
        q = len(follow.orbit)
        return TwoStageClassification(
                **{**first, "status": CONVERGED, "orbit": follow.orbit, "period": q,
               "contacts": follow.contacts, "max_penetration": follow.max_g,
               "impacting": follow.impacting, **_settled(follow.orbit, q)},
            outcome="converged",
            message=f"converged to a period-{q} orbit of the stroboscopic map after "
                    f"max_periods (followed on the section)")
    if follow.outcome != RECURRENT:  # a long transient: still moving after both budgets
        return TwoStageClassification(
            **first, outcome="unresolved",
            message=f"no period <= section_max_period and no recurrent set within "
                    f"max_periods + section_periods = {first['periods_used']} periods "
                    f"(a long transient: raise `section_periods`)")
    rec = Recurrent(0, 0, follow.cells, follow.cloud, follow.impacting, follow.end_state,
                    follow.end_time)
    _, (attractor,) = identify([rec], lambda _point, y, t: section_spectrum(problem, y, t),
                               s.section_zero_exponent)
    lam = float(attractor.at[0].exponents[0])
    cells = len(follow.cells)
    if attractor.kind == SETTLING:
        kind = "unresolved"
        why = (f"recurrent on {cells} section cells but contracting (largest Lyapunov "
               f"exponent {lam:+.4g} /time < -section_zero_exponent): a periodic orbit not "
               f"converged yet")
    else:
        kind = attractor.kind
        why = (f"{kind} attractor on {cells} section cells, largest Lyapunov exponent "
               f"{lam:+.4g} /time (section_zero_exponent {s.section_zero_exponent:g})")
    return TwoStageClassification(
        **{**first, "label": attractor.name, "orbit": follow.cloud[:0],
           "contacts": follow.contacts, "max_penetration": follow.max_g,
           "impacting": follow.impacting, **_settled(follow.cloud, len(follow.cloud))},
        outcome=kind, message=why,
        table=attractor_table([attractor], tuple(problem.system.state_names)))


def _settled(points: np.ndarray, periods: int) -> dict:
    """The ``settled_*`` fields: from the first of ``points`` (section points), for
    ``periods`` periods (none without points)."""
    if len(points) == 0 or periods <= 0:
        return {}
    return {"settled_from": np.array(points[0], dtype=np.float64),
            "settled_periods": int(periods)}


def stop_penetrations(problem: Problem, cls: TwoStageClassification) -> np.ndarray:
    """(n_stops,) max of each stop's compression over the final orbit (or the located
    points of a recurrent set), followed again from its first section point (a section
    time, where the forcing's phase is 0 mod 2 pi); NaN when nothing settled. Their max
    is the trajectory's ``max_penetration`` (to the convergence tolerance)."""
    n = len(problem.surfaces.contact_indices)
    if cls.settled_periods == 0:
        return np.full(n, np.nan)
    return contact_maxima(problem, cls.settled_from, 0.0,
                          cls.settled_periods * problem.period)


def stop_descriptions(problem: Problem) -> list[str]:
    """One short name per stop of a chain: "bodies 1-2", "body 3 / right wall"."""
    model = problem.system.extra["chain"]
    return [f"body {s.body} / {s.side} wall" if s.wall else f"bodies {s.body}-{s.other}"
            for s in model.stops]


def per_stop_dataset(problem: Problem, cls: TwoStageClassification) -> xr.Dataset:
    """A chain's per-stop part of its trajectory result: ``stop_max_penetration`` (stop),
    and what each stop is: its compression is ``stop_sign * (x_i - x_j) - stop_offset``
    with i = ``stop_body``, j = ``stop_other`` (0: a wall, x_0 = 0)."""
    model = problem.system.extra["chain"]
    names = stop_descriptions(problem)
    sf = problem.surfaces
    rows = [sf.A[i] for i in sf.contact_indices]  # d delta / d y of each stop
    sign = np.array([row[2 * (stop.body - 1)] for row, stop in zip(rows, model.stops,
                                                                    strict=True)])
    offset = np.array([-sf.b[i] for i in sf.contact_indices])
    return xr.Dataset(
        {"stop_max_penetration": (
            ("stop",), stop_penetrations(problem, cls),
            {"long_name": "max of each stop's compression over the final orbit (>= 0: in "
                          "contact; < 0: the smallest clearance)", "units": "1"})},
        coords={"stop": ("stop", np.arange(1, len(names) + 1)),
                "stop_between": ("stop", names, {"long_name": "what the stop is between"}),
                "stop_body": ("stop", np.array([s.body for s in model.stops])),
                "stop_other": ("stop", np.array([s.other for s in model.stops]),
                               {"long_name": "the other body (0: a wall)"}),
                "stop_sign": ("stop", sign),
                "stop_offset": ("stop", offset, {
                    "long_name": "compression = stop_sign * (x_body - x_other) - "
                                 "stop_offset (x_0 = 0: a wall)", "units": "1"})})


def trajectory_dataset(problem: Problem, state, t0: float, periods: int,
                       samples_per_period: int) -> xr.Dataset:
    """Record ``periods`` forcing periods from ``state`` at ``t0`` and classify the start.

    Dims: ``time`` (dense samples), ``section`` (stroboscopic index n, time n T),
    ``variable`` (state names), ``orbit_point`` (points of the classified orbit).
    """
    names = list(problem.system.state_names)
    started = time.perf_counter()
    traj = record_trajectory(problem, state, t0, periods, samples_per_period)
    recorded = time.perf_counter()
    cls = classify_both_stages(problem, state, t0)
    done = time.perf_counter()
    T = problem.period
    has_contact = problem.surfaces.contacts != 0
    ds = xr.Dataset(
        {
            "state": (("time", "variable"), traj.y,
                      {"long_name": "state (dense output)", "units": "1"}),
            "section_state": (("section", "variable"), traj.section_y,
                              {"long_name": "state at the stroboscopic times n T", "units": "1"}),
            "section_time": (("section",), traj.section_t,
                             {"long_name": "stroboscopic time n T", "units": "1"}),
            "section_contacts": (("section",), traj.contacts,
                                 {"long_name": "contact onsets during the period ending here",
                                  "units": "1"}),
            "section_max_contact_function": (
                ("section",), np.where(np.isfinite(traj.max_g), traj.max_g, np.nan),
                {"long_name": "max of x1 - x2 - d over the period ending here "
                              "(> 0: stop compressed)", "units": "1"}),
            "orbit": (("orbit_point", "variable"), cls.orbit,
                      {"long_name": "stroboscopic points of the classified orbit, time order",
                       "units": "1"}),
        },
        coords={
            "time": ("time", traj.t, {"long_name": "time", "units": "1"}),
            "section": ("section", np.arange(traj.section_t.size)),
            "variable": ("variable", names),
            "orbit_point": ("orbit_point", np.arange(cls.period)),
        },
        attrs={
            "analysis": "trajectory",
            "record_status": int(traj.status),
            "record_outcome": outcome(traj.status),
            "status": int(cls.status),
            "outcome": cls.outcome,
            "status_message": cls.message,
            **({"label": cls.label} if cls.label else {}),
            "classified_by": CLASSIFIED_BY[cls.classified_by],
            "second_stage": cls.second_stage,
            "period": int(cls.period),
            "periods_used": int(cls.periods_used),
            "contacts_on_orbit": int(cls.contacts),
            "max_penetration": float(cls.max_penetration) if has_contact else np.nan,
            "impacting": int(cls.impacting),
            "forcing_period": T,
            "t0": float(t0),
            "initial_state": np.asarray(state, dtype=float),
            "record_wall_s": recorded - started,
            "classify_wall_s": done - recorded,
            **{f"record_{k}": v for k, v in traj.counters.items() if k != "mode"},
            **{f"classify_{k}": v for k, v in cls.first.counters.items() if k != "mode"},
            **(_rigid_attrs(traj) if problem.system.extra.get("rigid") else {}),
        },
    )
    if cls.table.data_vars:  # the attractor with its exponents, as sweeps store it
        ds = xr.merge([ds, cls.table], combine_attrs="override", compat="override")
    if "chain" in problem.system.extra:  # several stops: one maximum each
        ds = xr.merge([ds, per_stop_dataset(problem, cls)], combine_attrs="override",
                      compat="override")
        ds["section_max_contact_function"].attrs["long_name"] = (
            "max over the stops' compressions during the period ending here (> 0: a stop "
            "compressed)")
    return ds


def _rigid_attrs(traj) -> dict:
    """The recorded trajectory's rigid impacts (``kernels.impacts``): impacts, chatter
    sequences ended by their accumulation, sticking phases and the time stuck."""
    return {**{f"rigid_{k}": v for k, v in traj.impacts.items()},
            "rigid_sticking_time": float(traj.sticking_time)}
