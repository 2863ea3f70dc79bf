"""Provenance attributes every result file carries."""

from __future__ import annotations

import datetime as _dt
import platform
import socket

import numba
import numpy as np

from .. import __version__


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
        "started": _dt.datetime.fromtimestamp(started, _dt.UTC).isoformat(),
        "finished": _dt.datetime.fromtimestamp(finished, _dt.UTC).isoformat(),
        "wall_s": float(wall_s),
        "machine": f"{socket.gethostname()} {platform.machine()} {platform.system()} "
                   f"python {platform.python_version()}",
        "complete": 1,
    }
