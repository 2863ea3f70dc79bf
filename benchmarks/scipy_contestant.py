"""Contestant 3 of the basin benchmark: what a Python user would write with scipy.

``solve_ivp`` with a terminal event on every switching surface, restarted with the mode
flipped (the event-driven referee of ``tests/naive.py``, at benchmark tolerances), a fixed
transient, then stroboscopic points; the period is the smallest q whose last q points
repeat. The model is the referee's transcription of the equations, independent of the
package's numba systems.
"""

from __future__ import annotations

import numpy as np
from _common import ROOT  # noqa: F401  (puts the repository root on sys.path)

from softimpact_cli.analysis.catalogue import label_orbit
from softimpact_cli.analysis.labels import DIVERGED, UNRESOLVED
from tests.naive import (
    bilinear_body_model,
    bilinear_pair_model,
    duffing_pair_model,
    solve_with_events,
)

TRANSIENT = 300  # forcing periods integrated before recording
RECORD = 60  # recorded stroboscopic points after the transient
REPEAT_TOL = 1e-5  # section points repeating to this (scaled), rtol 1e-8 integration
MAX_ORBIT_PERIOD = 30
RTOL, ATOL = 1e-8, 1e-10


MODELS = {("duffing", 2): duffing_pair_model, ("bilinear", 2): bilinear_pair_model,
          ("bilinear", 1): bilinear_body_model}


def scipy_label(state, values: dict, method: str = "RK45", catalogue=None, tol: float = 1e-3,
                transient: int = TRANSIENT, record: int = RECORD, model: str = "duffing",
                bodies: int = 2) -> str:
    """The label of one initial state (x1, v1, x2, v2, or x, v for one body, at t = 0) of
    ``model`` at ``values``: a catalogue name, ``P{q}`` / ``P{q} impacting`` without a
    catalogue, or unresolved / diverged."""
    T = 2 * np.pi / float(values["w"])
    switched = MODELS[model, bodies]({k: v if isinstance(v, str) else float(v)  # law: a name
                                      for k, v in values.items()})
    strobe_t = (transient + np.arange(record + 1)) * T
    try:
        sol = solve_with_events(switched.rhs, state, (0.0, strobe_t[-1]), switched.switches,
                                strobe_t, rtol=RTOL, atol=ATOL, method=method,
                                max_events=200 * (transient + record))
    except RuntimeError as exc:  # chattering gives up; a failed step is a blow-up
        return UNRESOLVED if "too many events" in str(exc) else DIVERGED
    pts = sol.y_eval
    if not np.all(np.isfinite(pts)) or np.max(np.abs(pts)) > 1e6:
        return DIVERGED
    # in contact at any time of the recorded window: at its start, or a crossing in it
    impacting = bodies == 2 and bool(pts[0, 0] - pts[0, 2] >= float(values["d"]) or any(
        t > strobe_t[0] and s == 0 for t, s in zip(sol.event_t, sol.event_surface,
                                                   strict=True)))
    n = len(pts) - 1
    scale = max(1.0, float(np.max(np.abs(pts[n]))))
    period = next((q for q in range(1, MAX_ORBIT_PERIOD + 1) if n >= 2 * q and np.max(
        np.abs(pts[n - q + 1:n + 1] - pts[n - 2 * q + 1:n - q + 1])) <= REPEAT_TOL * scale),
        0)
    if period == 0:
        return UNRESOLVED
    if catalogue is None:
        return f"P{period}{' impacting' if impacting else ''}"
    return label_orbit(catalogue, pts[n - period + 1:n + 1], impacting, tol).name
