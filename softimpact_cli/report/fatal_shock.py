"""A fatal_shock result as a dict (``info --json``) and as text."""

from __future__ import annotations

import numpy as np


def fatal_shock_summary(ds) -> dict:
    """{solution, mfs, time, direction, destination, per phase: min and median over the
    directions, destinations with counts}."""
    mag = ds["shock_magnitude"].values
    finite = np.where(np.isfinite(mag), mag, np.nan)
    dest, counts = np.unique(ds["shock_destination"].values[np.isfinite(mag)],
                             return_counts=True)
    out = {"solution": str(ds.attrs["target"]), "mfs": float(ds.attrs["mfs"]),
           "searched": f"{ds.attrs['n_phases']} phases x {ds.attrs['n_directions']} "
                       f"directions, {ds.attrs['scan']} magnitudes up to "
                       f"{ds.attrs['max_shock']:g}, bisection to {ds.attrs['tol']:g}",
           "destinations": {str(d): int(c) for d, c in zip(dest, counts, strict=True)},
           "per_phase": [{"t": float(t),
                          "min": float(np.nanmin(row)) if np.isfinite(row).any() else None,
                          "median": float(np.nanmedian(row)) if np.isfinite(row).any()
                          else None}
                         for t, row in zip(ds["shock_time"].values, finite, strict=True)]}
    if np.isfinite(out["mfs"]):
        out.update(time=float(ds.attrs["mfs_time"]),
                   direction=[float(x) for x in np.atleast_1d(ds.attrs["mfs_direction"])],
                   destination=str(ds.attrs["mfs_destination"]))
    return out


def fatal_shock_lines(ds) -> list[str]:
    s = fatal_shock_summary(ds)
    names = [str(v) for v in ds["variable"].values]
    if not np.isfinite(s["mfs"]):
        return [f"minimal fatal shock of {s['solution']}: none found ({s['searched']})"]
    T = float(ds.attrs.get("forcing_period", np.nan))
    direction = ", ".join(f"{n} {x:+.3f}" for n, x in zip(names, s["direction"],
                                                          strict=True))
    lines = [f"minimal fatal shock of {s['solution']}: {s['mfs']:.4g} (an upper bound; "
             f"{s['searched']})",
             f"  at t = {s['time']:.4g} ({s['time'] / T:.3f} T), direction ({direction}), "
             f"leads to {s['destination']}",
             "  fatal shocks found lead to: " + ", ".join(
                 f"{d} ({c})" for d, c in s["destinations"].items())]
    return lines
