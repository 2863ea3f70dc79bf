"""``info`` of an atlas result: its curves and codimension-two points (dict and text)."""

from __future__ import annotations

import json

import numpy as np


def atlas_summary(ds) -> dict:
    """Per curve its kind, orbit, period, points as [a, b] pairs, multipliers ([re, im]
    per point), stability beside the critical multipliers and criticality per point, and
    its ends; every codimension-two point with its curve and [a, b]."""
    curves = []
    kinds = [str(k) for k in ds["curve_kind"].values]
    for c in range(ds.sizes["curve"]):
        first, size = int(ds["curve_first"].values[c]), int(ds["curve_size"].values[c])
        part = slice(first, first + size)
        mu = ds["multiplier_re"].values[part] + 1j * ds["multiplier_im"].values[part]
        sup = ds["supercritical"].values[part]
        curves.append({
            "kind": kinds[c], "orbit": str(ds["curve_orbit"].values[c]),
            "periods": int(ds["curve_periods"].values[c]),
            "points": [[float(a), float(b)] for a, b in ds["pair"].values[part]],
            "multipliers": [[[float(m.real), float(m.imag)] for m in row] for row in mu],
            "stable": [bool(s) for s in ds["stable_beside"].values[part]],
            "supercritical": [None if s < 0 else bool(s) for s in sup],
            "ends": [str(ds["curve_end_first"].values[c]), str(ds["curve_end_last"].values[c])],
        })
    codim2 = [{"kind": str(ds["codim2_kind"].values[k]),
               "curve": int(ds["codim2_curve"].values[k]),
               "orbit": str(ds["curve_orbit"].values[int(ds["codim2_curve"].values[k])]),
               "point": [float(x) for x in ds["codim2_pair"].values[k]]}
              for k in range(ds.sizes["codim2"])]
    return {"parameters": json.loads(ds.attrs["atlas_parameters"]),
            "ranges": json.loads(ds.attrs["atlas_ranges"]), "curves": curves, "codim2": codim2}


def atlas_info(ds) -> dict:
    """The kind's part of ``info --json``: {"atlas": :func:`atlas_summary`}."""
    return {"atlas": atlas_summary(ds)}


def format_atlas(ds) -> str:
    """One line per curve (kind, orbit, points, range, ends) and per codimension-two point."""
    s = atlas_summary(ds)
    a, b = s["parameters"]
    lines = [f"atlas in ({a}, {b}) over [{s['ranges'][0][0]:.6g}, {s['ranges'][0][1]:.6g}] x "
             f"[{s['ranges'][1][0]:.6g}, {s['ranges'][1][1]:.6g}]: {len(s['curves'])} curves, "
             f"{len(s['codim2'])} codimension-two points"]
    for c in s["curves"]:
        pts = np.array(c["points"])
        lines.append(f"  {c['kind']:15s} {c['orbit']:20s} p={c['periods']} {len(pts):4d} points, "
                     f"{a} {pts[:, 0].min():.6g}..{pts[:, 0].max():.6g}, "
                     f"{b} {pts[:, 1].min():.6g}..{pts[:, 1].max():.6g}; ends: "
                     f"{c['ends'][0]} / {c['ends'][1]}")
    for k in s["codim2"]:
        lines.append(f"  {k['kind']:15s} on {k['orbit']} ({k['curve']}): {a} = "
                     f"{k['point'][0]:.8g}, {b} = {k['point'][1]:.8g}")
    return "\n".join(lines)
