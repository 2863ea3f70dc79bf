"""A result's verification report (``verify_*`` attributes, see ``sweep.verification``)
as a dict for ``info --json`` and as the one line ``sweep``, ``info`` and plots print."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from ..sweep.pilot import pilot_trial_text

NUMBERS = ("sample", "total", "disagreements", "share", "ci95_low", "ci95_high",
           "threshold", "rungs", "check_wall_s", "wall_s", "seed")


def verification_summary(attrs: Mapping[str, Any]) -> dict | None:
    """{status, message, sample, disagreements, share, ci95 [low, high], threshold,
    settings, run_settings, changes, history, ...} from a result's attributes; None for a
    result written before verification existed."""
    if "verify_status" not in attrs:
        return None
    out: dict[str, Any] = {"status": str(attrs["verify_status"])}
    for key in ("message", "settings", "run_settings", "changes"):
        if f"verify_{key}" in attrs:
            out[key] = str(attrs[f"verify_{key}"])
    for key in NUMBERS:
        if f"verify_{key}" in attrs:
            value = attrs[f"verify_{key}"]
            out[key] = float(value) if isinstance(value, float) else int(value)
    if "verify_history" in attrs:
        out["history"] = json.loads(str(attrs["verify_history"]))
    if "pilot_status" in attrs:
        out["pilot"] = pilot_summary(attrs)
    return out


def pilot_summary(attrs: Mapping[str, Any]) -> dict:
    """The tolerance pilot's record (``pilot_*`` attributes, see ``sweep.pilot``)."""
    out: dict[str, Any] = {"status": str(attrs["pilot_status"])}
    for key in ("sample", "reference_rtol", "rtol", "atol", "wall_s", "reference_wall_s"):
        if f"pilot_{key}" in attrs:
            value = attrs[f"pilot_{key}"]
            out[key] = int(value) if key == "sample" else float(value)
    if "pilot_trials" in attrs:
        out["trials"] = json.loads(str(attrs["pilot_trials"]))
    return out


def pilot_line(attrs: Mapping[str, Any]) -> str | None:
    """One line: what the tolerance pilot chose and on what evidence (None: the result
    has no pilot record)."""
    if "pilot_status" not in attrs:
        return None
    s = pilot_summary(attrs)
    if "trials" not in s:
        return f"tolerance pilot: {s['status']}"
    tried = "; ".join(f"rtol {t['rtol']:g}: {pilot_trial_text(t, s['sample'])}"
                      for t in s["trials"])
    return (f"tolerance pilot: {s['status']} ({s['sample']} trajectories against rtol "
            f"{s['reference_rtol']:g}; {tried})")


def _percent(share: float) -> str:
    return f"{100 * share:.2f}%"


def verification_line(attrs: Mapping[str, Any]) -> str | None:
    """One line, e.g. ``label error (verified, 800 of 250000 rerun at dopri5, rtol 1e-10,
    ...): 0 / 800 disagree, 95% interval [0.00%, 0.48%] <= 0.50%``, or for a sample in
    which none disagreed that is too small to reach the threshold, the bound it gives
    (``label error <= 3.70% (95%), measured on 100 of 10000 trajectories rerun at ...:
    none disagreed``); None when the result carries no verification."""
    s = verification_summary(attrs)
    if s is None:
        return None
    if "sample" not in s:
        return f"label error: {s['status']}"
    if s["status"] == "bounded":  # none disagreed: the bound is the result
        return (f"label error <= {_percent(s['ci95_high'])} (95%), measured on "
                f"{s['sample']} of {s['total']} trajectories rerun at {s['settings']}: none "
                "disagreed")
    within = "<=" if s["ci95_high"] <= s["threshold"] else ">"
    redone = (f"; redone {s['rungs']}x, now at {s['run_settings']}" if s.get("rungs")
              else "")
    return (f"label error ({s['status']}, {s['sample']} of {s['total']} rerun at "
            f"{s['settings']}{redone}): {s['disagreements']} / {s['sample']} disagree, "
            f"95% interval [{_percent(s['ci95_low'])}, {_percent(s['ci95_high'])}] "
            f"{within} {_percent(s['threshold'])}")


def verification_lines(attrs: Mapping[str, Any]) -> list[str]:
    """The line, the status's meaning and, after a redo, each attempt: what ``info``
    prints."""
    line = verification_line(attrs)
    if line is None:
        return []
    s = verification_summary(attrs)
    out = [line]
    if "message" in s:
        out.append(f"  {s['message']}")
    for k, a in enumerate(s.get("history", [])[:-1] if s.get("rungs") else []):
        out.append(f"  attempt {k + 1} ({a['settings']}): {a['disagreements']} / "
                   f"{a['sample']} disagree, [{_percent(a['ci_low'])}, "
                   f"{_percent(a['ci_high'])}], {a['outcome']}, run {a['run_wall_s']:.1f} s")
    if s.get("changes") not in (None, "none"):
        out.append(f"  changes: {s['changes']}")
    pilot = pilot_line(attrs)
    return out + ([pilot] if pilot else [])
