"""What a result file holds, as a dict (``softimpact info``)."""

from __future__ import annotations

import numpy as np

SUMMARY_KEYS = (
    "analysis", "model", "bodies", "parameters", "outcome", "status_message", "period",
    "periods_used", "contacts_on_orbit", "max_penetration", "impacting", "t0",
    "integrator_resolved_method", "integrator_rtol", "integrator_atol",
    "integrator_steps_per_period", "integrator_locate_switches", "wall_s", "complete",
    "scene_source", "scene_sha256", "softimpact_version", "started", "finished", "machine",
)


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, float) and not np.isfinite(value):
        return None
    return value


def describe(ds) -> dict:
    """Summary of a result dataset: analysis, outcome, timings, provenance."""
    out = {k: _plain(ds.attrs[k]) for k in SUMMARY_KEYS if k in ds.attrs}
    if "orbit" in ds:
        out["orbit"] = _plain(ds["orbit"].values)
        out["variables"] = [str(v) for v in ds["variable"].values]
    out["scene"] = ds.attrs.get("scene_text", "")
    return {k: _plain(v) for k, v in out.items()}
