"""A tipping result's matrix and destinations as a dict (``info --json``) and as text."""

from __future__ import annotations

import numpy as np


def tipping_summary(ds) -> dict:
    """{before, after, from_share {i: share}, matrix {i: {j: {probability, ci95, count}}},
    destinations {solution: [labels after of its section points]}}."""
    rows = [str(n) for n in ds["tip_from"].values]
    cols = [str(n) for n in ds["tip_to"].values]
    p, count = ds["tip_probability"].values, ds["tip_count"].values
    low, high = ds["tip_ci95_low"].values, ds["tip_ci95_high"].values
    matrix = {r: {c: {"probability": float(p[i, j]), "ci95": [float(low[i, j]),
                                                              float(high[i, j])],
                      "count": int(count[i, j])}
                  for j, c in enumerate(cols) if count[i, j] > 0}
              for i, r in enumerate(rows)}
    destinations = {}
    if "tip_destination" in ds:
        for i, name in enumerate(ds["tip_solution"].values):
            destinations[str(name)] = [str(v) for v in ds["tip_destination"].values[i] if v]
    return {"before": str(ds.attrs.get("tip_before", "")),
            "after": str(ds.attrs.get("tip_after", "")),
            "from_share": {r: float(s) for r, s in zip(rows, ds["tip_from_share"].values,
                                                       strict=True)},
            "matrix": matrix, "destinations": destinations}


def tipping_lines(ds) -> list[str]:
    """The matrix, one line per basin before, and where each solution goes."""
    s = tipping_summary(ds)
    out = [f"tipping from ({s['before']}) to ({s['after']}): P(i -> j), 95% Wilson "
           "interval, starts"]
    for row, share in s["from_share"].items():
        cells = "; ".join(f"{col} {v['probability']:.3f} [{v['ci95'][0]:.3f}, "
                          f"{v['ci95'][1]:.3f}] ({v['count']})"
                          for col, v in sorted(s["matrix"][row].items(),
                                               key=lambda kv: -kv[1]["probability"]))
        out.append(f"  basin {row} ({100 * share:.1f}% of starts) -> {cells}")
    if s["destinations"]:
        out.append("solutions before, their section points (t = 0 mod T) labelled after:")
        for name, labels in s["destinations"].items():
            values, counts = np.unique(labels, return_counts=True)
            where = ", ".join(f"{v} ({c} of {len(labels)})" for v, c in zip(values, counts,
                                                                             strict=True))
            out.append(f"  {name} -> {where}")
    return out
