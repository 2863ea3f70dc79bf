"""Branches, events and brute-force sweeps as one xarray Dataset.

Dimensions: ``point`` (every point of every branch, branch after branch, each in order of
arclength), ``branch``, ``event``, ``variable`` (the state), ``multiplier`` (n), ``section``
(a point's p section points), ``body`` (x of each body), and for the brute-force sweeps
``sweep``, ``sweep_step``, ``sweep_point``. A chain's adds ``stop``: each stop's gap along
the branches (``stop_gap``) and the stop each grazing touches (``event_stop``).
"""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

from .catalogue import orbit_points
from .continuation_branches import Branch
from .continuation_grazing import is_chain, kernel_gaps
from .shooting import OrbitMap


def _strings(values) -> np.ndarray:
    return np.array(list(values), dtype=object)


def branch_variables(base: OrbitMap, branches: list[Branch]) -> tuple[dict, dict]:
    """(data variables, coordinates) of the branches' points and events."""
    system = base.system
    n = system.dim
    bodies = system.bodies
    points = [(i, p) for i, b in enumerate(branches) for p in b.points]
    max_p = max((b.periods for b in branches), default=1)
    first = np.cumsum([0] + [len(b.points) for b in branches])[:-1]
    N = len(points)
    section_x = np.full((N, max_p, bodies), np.nan)
    mult = np.full((N, n), np.nan + 0j)
    for k, (i, p) in enumerate(points):
        orbit = orbit_points(base.problem(p.parameter), p.state, branches[i].periods)
        section_x[k, : orbit.shape[0]] = orbit[:, 0::2]
        mult[k] = p.multipliers
    events = [(i, e) for i, b in enumerate(branches) for e in b.events]
    E = len(events)
    ev_mult = np.full((E, n), np.nan + 0j)
    for k, (_, e) in enumerate(events):
        ev_mult[k] = e.point.multipliers
    name = base.parameter
    data = {
        "parameter": (("point",), [p.parameter for _, p in points],
                      {"long_name": f"continued parameter {name}", "units": "1"}),
        "state": (("point", "variable"), np.array([p.state for _, p in points]).reshape(N, n),
                  {"long_name": "fixed point of P^p at t = 0 (mod T)", "units": "1"}),
        "section_x": (("point", "section", "body"), section_x,
                      {"long_name": "displacement of each body at the orbit's section "
                                    "points t = kT, k < p", "units": "1"}),
        "point_branch": (("point",), np.array([i for i, _ in points], dtype=np.int64)),
        "stable": (("point",), np.array([p.stable for _, p in points], dtype=np.int8),
                   {"long_name": "1: every |multiplier| < 1"}),
        "impacting": (("point",), np.array([p.impacting for _, p in points], dtype=np.int8),
                      {"long_name": "1: the orbit touches the stop"}),
        "gap": (("point",), [p.value.max_g for _, p in points],
                {"long_name": "max over the orbit of x1 - x2 - d (-inf: one body)",
                 "units": "1"}),
        "residual": (("point",), [float(np.max(np.abs(p.value.residual))) for _, p in points],
                     {"long_name": "|P^p(y) - y|_inf", "units": "1"}),
        "multiplier_re": (("point", "multiplier"), mult.real,
                          {"long_name": "Floquet multiplier, real part (largest |mu| first)",
                           "units": "1"}),
        "multiplier_im": (("point", "multiplier"), mult.imag,
                          {"long_name": "Floquet multiplier, imaginary part", "units": "1"}),
        "branch_name": (("branch",), _strings(b.name for b in branches)),
        "branch_periods": (("branch",), np.array([b.periods for b in branches], dtype=np.int64),
                           {"units": "forcing periods"}),
        "branch_parent": (("branch",), np.array([b.parent for b in branches], dtype=np.int64),
                          {"long_name": "branch switched from at a period doubling "
                                        "or branch point (-1: a start)"}),
        "branch_first": (("branch",), first.astype(np.int64),
                         {"long_name": "index of the branch's first point"}),
        "branch_size": (("branch",), np.array([len(b.points) for b in branches],
                                              dtype=np.int64)),
        "branch_start": (("branch",), np.array([f + b.start for f, b in zip(first, branches,
                                                                             strict=True)],
                                               dtype=np.int64),
                         {"long_name": "index of the point the branch was started from"}),
        "branch_end_low": (("branch",), _strings(b.ends[0] for b in branches),
                           {"long_name": "why the branch ends at its first point"}),
        "branch_end_high": (("branch",), _strings(b.ends[1] for b in branches),
                            {"long_name": "why the branch ends at its last point"}),
        "event_kind": (("event",), _strings(e.kind for _, e in events)),
        "event_branch": (("event",), np.array([i for i, _ in events], dtype=np.int64)),
        "event_parameter": (("event",), [e.point.parameter for _, e in events],
                            {"long_name": f"{name} at the event", "units": "1"}),
        "event_state": (("event", "variable"),
                        np.array([e.point.state for _, e in events]).reshape(E, n),
                        {"units": "1"}),
        "event_after": (("event",), np.array([first[i] + max(e.after, 0) for i, e in events],
                                             dtype=np.int64),
                        {"long_name": "index of the branch point before the event"}),
        "event_multiplier_re": (("event", "multiplier"), ev_mult.real, {"units": "1"}),
        "event_multiplier_im": (("event", "multiplier"), ev_mult.imag, {"units": "1"}),
    }
    coords = {"point": np.arange(N), "branch": np.arange(len(branches)),
              "event": np.arange(E), "variable": list(system.state_names),
              "multiplier": np.arange(n), "section": np.arange(max_p),
              "body": [f"x{i}" for i in range(1, bodies + 1)] if bodies > 1 else ["x"]}
    if is_chain(system):
        chain_data, chain_coords = stop_variables(base, branches, points, events)
        data.update(chain_data)
        coords.update(chain_coords)
    return data, coords


def stop_variables(base: OrbitMap, branches: list[Branch], points: list, events: list
                   ) -> tuple[dict, dict]:
    """(data variables, coordinates) a chain adds: each stop's gap at every point of the
    branches (``points``: (branch index, point)) and the stop of each grazing event."""
    gaps = np.array([kernel_gaps(base.with_periods(branches[i].periods), p)
                     for i, p in points])
    stops = len(base.system.extra["chain"].stops)
    data = {
        "stop_gap": (("point", "stop"), gaps.reshape(len(points), stops),
                     {"long_name": "max over the orbit of each stop's compression (its "
                                   "gap's grazing test: >= 0 in contact)", "units": "1"}),
        "event_stop": (("event",), np.array([e.stop for _, e in events], dtype=np.int64),
                       {"long_name": "the stop a grazing touches (0: another event)"}),
    }
    return data, {"stop": np.arange(1, stops + 1)}


def sweep_variables(sweeps: list[tuple[str, str, list[dict]]], bodies: int) -> tuple[dict, dict]:
    """(data variables, coordinates) of the brute-force sweeps."""
    S = len(sweeps)
    steps = max((len(r) for _, _, r in sweeps), default=0)
    q = max((rec["points"].shape[0] for _, _, r in sweeps for rec in r), default=1)
    lam = np.full((S, steps), np.nan)
    x = np.full((S, steps, q, bodies), np.nan)
    period = np.zeros((S, steps), dtype=np.int64)
    impacting = np.zeros((S, steps), dtype=np.int8)
    for i, (_, _, records) in enumerate(sweeps):
        for j, rec in enumerate(records):
            lam[i, j] = rec["parameter"]
            pts = rec["points"]
            x[i, j, : pts.shape[0]] = pts[:, 0::2]
            period[i, j] = rec["period"]
            impacting[i, j] = rec["impacting"]
    data = {
        "sweep_parameter": (("sweep", "sweep_step"), lam, {"units": "1"}),
        "sweep_x": (("sweep", "sweep_step", "sweep_point", "body"), x,
                    {"long_name": "brute force: section displacements, each step from the "
                                  "previous end state", "units": "1"}),
        "sweep_period": (("sweep", "sweep_step"), period,
                         {"long_name": "period found (0: unresolved or diverged)"}),
        "sweep_impacting": (("sweep", "sweep_step"), impacting),
        "sweep_start": (("sweep",), _strings(name for name, _, _ in sweeps)),
        "sweep_direction": (("sweep",), _strings(d for _, d, _ in sweeps)),
    }
    coords = {"sweep": np.arange(S), "sweep_step": np.arange(steps),
              "sweep_point": np.arange(q)}
    return data, coords


def continuation_dataset(base: OrbitMap, branches: list[Branch], fates: dict[str, str],
                         sweeps: list, lam0: float, bounds: tuple[float, float]
                         ) -> xr.Dataset:
    """The result of a continuation run (see the module docstring for its layout)."""
    data, coords = branch_variables(base, branches)
    s_data, s_coords = sweep_variables(sweeps, base.system.bodies)
    data.update(s_data)
    coords.update(s_coords)
    attrs = {"analysis": "continuation", "parameter": base.parameter,
             "start_value": float(lam0), "low": float(bounds[0]), "high": float(bounds[1]),
             "forcing_period": base.problem(lam0).period, "bodies": base.system.bodies,
             "model": base.system.model, "starts": json.dumps(fates)}
    return xr.Dataset(data, coords=coords, attrs=attrs)
