"""The fatal shocks of a solution against the phase of its orbit."""

from __future__ import annotations

import numpy as np

from .common import place_panels


def draw_fatal_shock(ds, ax=None):
    """One panel: per phase t/T, the smallest fatal shock over the directions, their
    median and quartiles; the minimum marked with where it leads. Returns the Figure."""
    container, (panel,) = place_panels(ax, (1, 1), [(0, 0)], (6.0, 4.0))
    T = float(ds.attrs.get("forcing_period", 1.0))
    phase = ds["shock_time"].values / T
    mag = ds["shock_magnitude"].values
    finite = np.where(np.isfinite(mag), mag, np.nan)
    has = np.isfinite(mag).any(axis=1)
    if has.any():
        low = np.full(phase.size, np.nan)
        q1, med, q3 = (np.full(phase.size, np.nan) for _ in range(3))
        low[has] = np.nanmin(finite[has], axis=1)
        q1[has], med[has], q3[has] = np.nanpercentile(finite[has], [25, 50, 75], axis=1)
        panel.fill_between(phase, q1, q3, alpha=0.25, label="quartiles over directions")
        panel.plot(phase, med, "-", label="median over directions")
        panel.plot(phase, low, "o-", label="smallest (per phase)")
    else:  # every kick survives: the scan's reach at each phase scanned is the result
        max_shock = float(ds.attrs["max_shock"])
        panel.plot(phase, np.full(phase.size, max_shock), "k^--",
                   label=f"no fatal shock up to {max_shock:g} (every kick survives)")
        panel.set_xlim(0.0, 1.0)
        panel.set_ylim(top=1.15 * max_shock)
    if np.isfinite(ds.attrs.get("mfs", np.inf)):
        t = float(ds.attrs["mfs_time"]) / T
        panel.plot([t], [float(ds.attrs["mfs"])], "r*", ms=14,
                   label=f"minimal fatal shock {float(ds.attrs['mfs']):.3g} -> "
                         f"{ds.attrs['mfs_destination']}")
    panel.set_xlabel("phase of the orbit t / T")
    panel.set_ylabel("fatal shock magnitude |dy|")
    panel.set_ylim(bottom=0)
    panel.set_title(f"fatal shocks of {ds.attrs['target']}: {ds.attrs['n_directions']} "
                    f"directions, bisection to {ds.attrs['tol']:g}", fontsize=9)
    panel.legend(fontsize=7)
    return container if not hasattr(ax, "get_figure") or ax is None else ax.get_figure()
