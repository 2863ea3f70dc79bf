"""The atlas in its parameter plane: fold, period-doubling, Neimark-Sacker and grazing
curves (solid where the orbit is stable beside its critical multipliers, dotted where
not; PD and NS marked with open circles where subcritical), codimension-two points, over
a map's counts of coexisting solutions or a dcrit result's d_crit(phi) curves."""

from __future__ import annotations

import json

import numpy as np

from .common import new_figure

STYLE = {"fold": "tab:blue", "period doubling": "tab:red", "Neimark-Sacker": "tab:green",
         "grazing": "black"}
MARKERS = {"cusp": "^", "fold-flip": "s", "degenerate flip": "D", "1:1 resonance": "P",
           "1:2 resonance": "X", "Chenciner": "*", "grazing-fold": "v"}


def _underlay(ax, over, a: str, b: str) -> None:
    """A map's found counts (cells) or a dcrit result's curves, in the atlas's axes (told
    apart by what they hold: a map has found_count, and also a d_crit table of its own)."""
    if "found_count" not in over:
        phi = over["phi"].values
        for k, d in enumerate(over["d_crit"].values):
            x, y = (phi, d) if a == "phi" else (d, phi)
            ax.plot(x, y, color="0.6", lw=3, alpha=0.6, zorder=1,
                    label="d_crit (dcrit)" if k == 0 else None)
        return
    counts = over["found_count"].squeeze(drop=True).transpose(b, a).values
    x, y = over[a].values, over[b].values
    hx = (x[-1] - x[0]) / max(1, len(x) - 1) / 2
    hy = (y[-1] - y[0]) / max(1, len(y) - 1) / 2
    im = ax.imshow(counts, origin="lower", aspect="auto", cmap="Greys", alpha=0.5,
                   extent=(x[0] - hx, x[-1] + hx, y[0] - hy, y[-1] + hy),
                   interpolation="nearest", zorder=0)
    ax.figure.colorbar(im, ax=ax, label="solutions found (map)")


def draw_atlas(ds, over=None, ax=None):
    """One panel: every curve of ``ds`` in (a, b), over ``over`` (a map or dcrit Dataset)
    when given; returns the matplotlib Figure."""
    a, b = json.loads(ds.attrs["atlas_parameters"])
    (a0, a1), (b0, b1) = json.loads(ds.attrs["atlas_ranges"])
    if ax is None:
        fig = new_figure(figsize=(8, 6))
        ax = fig.subplots()
    else:
        fig = ax.figure
    if over is not None:
        _underlay(ax, over, a, b)
    seen = set()
    for c in range(ds.sizes["curve"]):
        first, size = int(ds["curve_first"].values[c]), int(ds["curve_size"].values[c])
        pair = ds["pair"].values[first:first + size]
        stable = ds["stable_beside"].values[first:first + size].astype(bool)
        kind = str(ds["curve_kind"].values[c])
        colour = STYLE[kind]
        label = kind if kind not in seen else None
        seen.add(kind)
        for mask, style in ((stable, "-"), (~stable, ":")):
            segment = np.where(mask[:, None], pair, np.nan)
            ax.plot(segment[:, 0], segment[:, 1], style, color=colour, lw=1.4, label=label,
                    zorder=3)
            label = None
        sub = ds["supercritical"].values[first:first + size] == 0
        if np.any(sub):
            ax.plot(pair[sub, 0], pair[sub, 1], "o", mfc="none", mec=colour, ms=3, zorder=3)
    for k in range(ds.sizes["codim2"]):
        kind = str(ds["codim2_kind"].values[k])
        x, y = ds["codim2_pair"].values[k]
        ax.plot(x, y, MARKERS.get(kind, "o"), color="tab:orange", ms=9, mec="k", zorder=4,
                label=kind if kind not in seen else None)
        seen.add(kind)
    ax.set_xlim(a0, a1)
    ax.set_ylim(b0, b1)
    ax.set_xlabel(a)
    ax.set_ylabel(b)
    ax.set_title(f"atlas: {ds.sizes['curve']} curves, {ds.sizes['codim2']} codimension-two "
                 f"points (dotted: unstable beside the critical multipliers; open circles: "
                 f"subcritical)", fontsize=8)
    if seen:
        ax.legend(fontsize=7, loc="best")
    return fig
