"""Provenance attributes every result file carries."""

from __future__ import annotations

import datetime as _dt
import os
import platform
import shlex
import socket
import sys

import numba
import numpy as np

from .. import __version__
from ..config import forcing_period


def command_line() -> str:
    """This process's command line as a user would type it (``softimpact sweep ...``)."""
    argv0 = sys.argv[0] if sys.argv and sys.argv[0] else "python"
    if argv0 == "-c":  # python -c '...' (also how pytest-xdist starts its workers)
        return shlex.join(["python", "-c", *sys.argv[1:]])
    program = os.path.basename(argv0)
    if program == "__main__.py":  # python -m PACKAGE
        program = os.path.basename(os.path.dirname(argv0))
    if program == "softimpact_cli":
        program = "softimpact"
    return shlex.join([program, *sys.argv[1:]])


def iso_time(epoch: float) -> str:
    """An epoch time (s) as an ISO 8601 UTC string."""
    return _dt.datetime.fromtimestamp(epoch, _dt.UTC).isoformat(timespec="seconds")


def history_line(started: float) -> str:
    """One line of the CF ``history`` attribute: when and by which command."""
    return f"{iso_time(started)} {command_line()}"


def provenance(scene, started: float, finished: float, wall_s: float) -> dict:
    """Attributes describing how a result was made (netCDF-safe: strings and numbers)."""
    s = scene.integrator
    return {
        "softimpact_version": __version__,
        "numpy_version": np.__version__,
        "numba_version": numba.__version__,
        "scene_source": str(scene.source),
        "scene_text": scene.text,
        "scene_sha256": scene.sha256,
        "model": scene.system.model,
        "bodies": scene.system.bodies,
        "parameters": ", ".join(f"{k}={v}" for k, v in scene.values.items()),
        "integrator_method": s.method,
        "integrator_resolved_method": s.resolved_method,
        "integrator_steps_per_period": s.steps_per_period,
        "integrator_locate_switches": int(s.locate_switches),
        "integrator_rtol": s.rtol,
        "integrator_atol": s.atol,
        "integrator_max_periods": s.max_periods,
        "integrator_max_orbit_period": s.max_orbit_period,
        "integrator_convergence_tol": s.convergence_tol,
        "integrator_divergence_bound": s.divergence_bound,
        "integrator_capture_tol": s.capture_tol,
        "integrator_capture_hits": s.capture_hits,
        "integrator_cell_size": s.cell_size,
        "integrator_cell_hits": s.cell_hits,
        "started": _dt.datetime.fromtimestamp(started, _dt.UTC).isoformat(),
        "finished": _dt.datetime.fromtimestamp(finished, _dt.UTC).isoformat(),
        "wall_s": float(wall_s),
        "machine": f"{socket.gethostname()} {platform.machine()} {platform.system()} "
                   f"python {platform.python_version()}",
        "history": history_line(started),
        "complete": 1,
        **_start_time(scene),
    }


def _start_time(scene) -> dict:
    """``t0`` (time units), ``t0_over_T`` and ``t0_mode`` of an analysis that starts at
    one given time ([analysis] t0: trajectory, catalogue); sweeps record their own."""
    t0 = getattr(scene.analysis, "t0", None)
    if t0 is None:
        return {}
    period = forcing_period(scene.values)
    return {"t0": float(t0), "t0_over_T": float(t0) / period, "t0_mode": "fixed"}
