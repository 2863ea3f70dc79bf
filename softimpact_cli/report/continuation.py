"""``info`` of a continuation result: branches, stability, bifurcations (dict and text)."""

from __future__ import annotations

import json

import numpy as np


def _runs(stable: np.ndarray, lam: np.ndarray) -> list[dict]:
    """Maximal runs of equal stability along a branch: [{stable, from, to}]."""
    out = []
    start = 0
    for k in range(1, stable.size + 1):
        if k == stable.size or stable[k] != stable[start]:
            out.append({"stable": bool(stable[start]), "from": float(lam[start]),
                        "to": float(lam[k - 1])})
            start = k
    return out


def continuation_summary(ds) -> dict:
    """Per branch its points, parameter range, stability runs and ends; every event with
    its parameter value and multipliers; what became of each start."""
    branches = []
    for b in range(ds.sizes["branch"]):
        first, size = int(ds["branch_first"].values[b]), int(ds["branch_size"].values[b])
        part = slice(first, first + size)
        lam = ds["parameter"].values[part]
        stable = ds["stable"].values[part].astype(bool)
        parent = int(ds["branch_parent"].values[b])
        branches.append({
            "name": str(ds["branch_name"].values[b]),
            "periods": int(ds["branch_periods"].values[b]),
            "points": size, "stable_points": int(stable.sum()),
            "impacting_points": int(ds["impacting"].values[part].sum()),
            "range": [float(np.min(lam)), float(np.max(lam))],
            "stability": _runs(stable, lam),
            "ends": [str(ds["branch_end_low"].values[b]), str(ds["branch_end_high"].values[b])],
            "switched_from": str(ds["branch_name"].values[parent]) if parent >= 0 else None,
            "max_residual": float(np.max(ds["residual"].values[part])),
        })
    events = []
    for e in range(ds.sizes["event"]):
        mu = ds["event_multiplier_re"].values[e] + 1j * ds["event_multiplier_im"].values[e]
        events.append({
            "kind": str(ds["event_kind"].values[e]),
            "branch": str(ds["branch_name"].values[int(ds["event_branch"].values[e])]),
            "parameter": float(ds["event_parameter"].values[e]),
            "state": [float(x) for x in ds["event_state"].values[e]],
            "multipliers": [[float(m.real), float(m.imag)] for m in mu],
        })
        if "event_stop" in ds:  # a chain's: the stop a grazing touches (0: none)
            events[-1]["stop"] = int(ds["event_stop"].values[e])
    return {"parameter": ds.attrs["parameter"], "start_value": float(ds.attrs["start_value"]),
            "bounds": [float(ds.attrs["low"]), float(ds.attrs["high"])],
            "starts": json.loads(ds.attrs.get("starts", "{}")),
            "branches": branches, "bifurcations": events,
            "brute_force_sweeps": int(ds.sizes.get("sweep", 0))}


def continuation_info(ds) -> dict:
    """The kind's part of ``info --json``: {"continuation": :func:`continuation_summary`}
    (nested: ``branches`` means the bifurcation kind's followed solutions at the top)."""
    return {"continuation": continuation_summary(ds)}


def _mu(pairs) -> str:
    return ", ".join(f"{re:+.6f}{im:+.6f}j" if abs(im) > 1e-12 else f"{re:+.6f}"
                     for re, im in pairs)


def format_continuation(ds) -> str:
    """Branches (range, stable runs, ends) and located bifurcations, one line each."""
    s = continuation_summary(ds)
    name = s["parameter"]
    lines = [f"continuation in {name} from {s['start_value']:.6g} within "
             f"[{s['bounds'][0]:.6g}, {s['bounds'][1]:.6g}]: {len(s['branches'])} branches, "
             f"{len(s['bifurcations'])} bifurcations"]
    for start, fate in s["starts"].items():
        if fate != "traced":
            lines.append(f"  start {start}: {fate}")
    for b in s["branches"]:
        runs = "; ".join(f"{'stable' if r['stable'] else 'unstable'} {r['from']:.6g}.."
                         f"{r['to']:.6g}" for r in b["stability"])
        origin = f", from {b['switched_from']}" if b["switched_from"] else ""
        lines.append(f"  {b['name']} (period {b['periods']}{origin}): {b['points']} points, "
                     f"{name} in [{b['range'][0]:.6g}, {b['range'][1]:.6g}]; {runs}; "
                     f"ends: {b['ends'][0]} / {b['ends'][1]}")
    for e in s["bifurcations"]:
        kind = f"{e['kind']} stop {e['stop']}" if e.get("stop") else e["kind"]
        lines.append(f"  {kind:16s} {name} = {e['parameter']:.10g} on {e['branch']}; "
                     f"multipliers {_mu(e['multipliers'])}")
    return "\n".join(lines)
