"""One trajectory: dense time series, stroboscopic points and its classification."""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from ..kernels.codes import message, outcome
from .engine import Problem, classify_state, record_trajectory


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
    cls = classify_state(problem, state, t0)
    done = time.perf_counter()
    T = problem.period
    has_contact = problem.surfaces.contact >= 0
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
            "status_message": message(cls.status),
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
            **{f"classify_{k}": v for k, v in cls.counters.items() if k != "mode"},
        },
    )
    return ds
