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
        spans = ", ".join(f"{name} {column.min():.6g}..{column.max():.6g}"
                          for name, column in zip((a, b), pts.T, strict=True))
        lines.append(f"  {c['kind']:15s} {c['orbit']:20s} p={c['periods']} {len(pts):4d} points, "
                     f"{spans}; ends: {c['ends'][0]} / {c['ends'][1]}")
    for k in s["codim2"]:
        lines.append(f"  {k['kind']:15s} on {k['orbit']} ({k['curve']}): {a} = "
                     f"{k['point'][0]:.8g}, {b} = {k['point'][1]:.8g}")
    return "\n".join(lines)


def curve_polylines(ds) -> list[np.ndarray]:
    """(m, 2) [a, b] points of each curve of an atlas result, in order."""
    out = []
    for c in range(ds.sizes["curve"]):
        first, size = int(ds["curve_first"].values[c]), int(ds["curve_size"].values[c])
        out.append(np.asarray(ds["pair"].values[first:first + size], dtype=float))
    return out


def changed_cells(counts: np.ndarray) -> np.ndarray:
    """(rows, cols) bool: cells whose count differs from a 4-neighbour's."""
    out = np.zeros(counts.shape, dtype=bool)
    for axis in (0, 1):
        differ = np.diff(counts, axis=axis) != 0
        lo = [slice(None)] * 2
        hi = [slice(None)] * 2
        lo[axis], hi[axis] = slice(None, -1), slice(1, None)
        out[tuple(lo)] |= differ
        out[tuple(hi)] |= differ
    return out


def near_curves(polylines: list[np.ndarray], x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(len(y), len(x)) bool: cells (centred on the grid x, y) within one cell of a curve:
    a curve passes through the cell or one of its eight neighbours (each polyline sampled
    at a quarter of the smaller cell size)."""
    dx = (x[-1] - x[0]) / max(1, len(x) - 1)
    dy = (y[-1] - y[0]) / max(1, len(y) - 1)
    hit = np.zeros((len(y), len(x)), dtype=bool)
    for line in polylines:
        if len(line) == 0:
            continue
        steps = np.abs(np.diff(line, axis=0)) / np.array([dx, dy])
        pieces = [line[:1]]
        for k, n in enumerate(np.ceil(4 * steps.max(axis=1)).astype(int)):
            t = np.linspace(0.0, 1.0, max(n, 1) + 1)[1:, None]
            pieces.append(line[k] + t * (line[k + 1] - line[k]))
        pts = np.concatenate(pieces)
        i = np.rint((pts[:, 0] - x[0]) / dx).astype(int)
        j = np.rint((pts[:, 1] - y[0]) / dy).astype(int)
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                ii, jj = i + di, j + dj
                ok = (ii >= 0) & (ii < len(x)) & (jj >= 0) & (jj < len(y))
                hit[jj[ok], ii[ok]] = True
    return hit


def map_agreement(atlas, map_ds, variable: str = "found_count") -> dict:
    """How the atlas's curves bound a map's regions: of the cells whose count of
    coexisting solutions differs from a neighbour's, the share within one cell of a curve,
    and the others ([a, b] of each with its count and its neighbours' counts)."""
    a, b = json.loads(atlas.attrs["atlas_parameters"])
    counts = map_ds[variable].squeeze(drop=True).transpose(b, a).values
    x, y = map_ds[a].values.astype(float), map_ds[b].values.astype(float)
    changed = changed_cells(counts)
    near = near_curves(curve_polylines(atlas), x, y)
    missed = []
    for j, i in zip(*np.nonzero(changed & ~near), strict=True):
        around = {f"{a}={x[ii]:.6g}, {b}={y[jj]:.6g}": int(counts[jj, ii])
                  for ii, jj in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1))
                  if 0 <= ii < len(x) and 0 <= jj < len(y) and counts[jj, ii] != counts[j, i]}
        missed.append({"point": [float(x[i]), float(y[j])], "count": int(counts[j, i]),
                       "differing_neighbours": around})
    total = int(changed.sum())
    return {"changed_cells": total, "near_a_curve": int((changed & near).sum()),
            "share": float((changed & near).sum() / total) if total else 1.0,
            "missed": missed}
