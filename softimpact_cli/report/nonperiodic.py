"""The attractors that are not periodic in a sweep result, for ``softimpact info``."""

from __future__ import annotations

import numpy as np

from ..sweep.result import grid_dims, grid_point


def nonperiodic_summary(ds) -> list[dict]:
    """One row per attractor and grid point from the ``nonperiodic_*`` variables: name,
    kind, members and cells there, ``at`` (the grid point's values), exponents and stderr
    (1/time, largest first)."""
    out = []
    gridded = all(d in ds.sizes for d in grid_dims(ds))  # a trajectory has no grid
    shape = tuple(ds.sizes[d] for d in grid_dims(ds)) if gridded else ()
    for i, name in enumerate(ds["nonperiodic_name"].values):
        point = int(ds["nonperiodic_point"].values[i])
        index = np.unravel_index(point, shape) if shape else ()
        out.append({
            "name": str(name),
            "kind": str(ds["nonperiodic_kind"].values[i]),
            "members": int(ds["nonperiodic_members"].values[i]),
            "cells": int(ds["nonperiodic_cells"].values[i]),
            "at": _relevant(ds, grid_point(ds, tuple(int(k) for k in index))) if gridded
            else {},
            "exponents": [float(v) for v in ds["nonperiodic_exponents"].values[i]],
            "stderr": [float(v) for v in ds["nonperiodic_stderr"].values[i]],
        })
    return out


def _relevant(ds, point: dict) -> dict:
    """The grid point's values of the axes that are parameters of the system (a body
    without a stop has no d, phi, k_c, c_c) or swept (``grid_point`` gives every axis)."""
    names = {item.partition("=")[0] for item in str(ds.attrs.get("parameters", "")).split(", ")}
    return {k: v for k, v in point.items()
            if k in names or ds.sizes.get(k, 1) > 1 or not isinstance(v, float)}


def nonperiodic_lines(rows: list[dict]) -> list[str]:
    """The table ``info`` prints: one line per attractor and grid point."""
    if not rows:
        return []
    width = max(len(r["name"]) for r in rows)
    out = ["attractors that are not periodic (second stage), per grid point: trajectories, "
           "cells, Lyapunov exponents +- standard error (1/time)"]
    for r in rows:
        where = ", ".join(f"{k}={v:.6g}" for k, v in r["at"].items()
                          if k != "t0" and isinstance(v, float))  # the grid's axes
        spectrum = ", ".join(f"{v:+.4f}+-{e:.4f}" for v, e in zip(r["exponents"],
                                                                  r["stderr"], strict=True))
        where = f"  {where}:" if where else ":"
        out.append(f"  {r['name']:{width}s}{where} {r['members']} trajectories, "
                   f"{r['cells']} cells, [{spectrum}]")
    return out
