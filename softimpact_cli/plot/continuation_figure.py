"""Continuation: branches against the parameter, and their Floquet multipliers.

Top panel(s): the section displacement x of each body (one panel per body) at t = kT of
every point of every branch (a period-p branch draws p curves), stable runs solid,
unstable dashed, impacting runs thicker; bifurcations marked and named; the brute-force
sweeps' section points (up: small grey dots, down: small grey crosses) overlaid. Bottom
panel: the moduli |mu| of the multipliers along each branch, 1 marked.
"""

from __future__ import annotations

import numpy as np

from .common import PARAMETER_TEX, parameter_text, place_panels, root_figure

COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple", "tab:orange", "tab:brown")
MARKERS = {"fold": "o", "branch point": "D", "period doubling": "s",
           "Neimark-Sacker": "^", "grazing": "v", "doubling origin": "P"}
SHORT = {"fold": "LP", "branch point": "BP", "period doubling": "PD",
         "Neimark-Sacker": "NS", "grazing": "G", "doubling origin": "PD0"}


def _runs(mask: np.ndarray):
    """(start, stop) index pairs of maximal runs of equal ``mask`` values, overlapping by
    one point so that the curve stays connected."""
    start = 0
    for k in range(1, mask.size + 1):
        if k == mask.size or mask[k] != mask[start]:
            yield start, min(k + 1, mask.size), mask[start]
            start = k


def draw_continuation(ds, ax=None):
    """``len(body) + 1`` panels stacked (``ax``: that many Axes or a Figure)."""
    bodies = [str(b) for b in ds["body"].values]
    n = len(bodies) + 1
    fig, panels = place_panels(ax, (n, 1), [(i, 0) for i in range(n)],
                               figsize=(8, 3.2 * n), sharex=True)
    name = ds.attrs["parameter"]
    lam = ds["parameter"].values
    sx = ds["section_x"].values
    stable = ds["stable"].values.astype(bool)
    impacting = ds["impacting"].values.astype(bool)
    mod = np.hypot(ds["multiplier_re"].values, ds["multiplier_im"].values)
    if "sweep" in ds.dims:
        for i in range(ds.sizes["sweep"]):
            up = str(ds["sweep_direction"].values[i]) == "up"
            p = ds["sweep_parameter"].values[i]
            for j, ax_ in enumerate(panels[:-1]):
                xs = ds["sweep_x"].values[i, :, :, j]
                ax_.plot(np.repeat(p, xs.shape[1]), xs.ravel(), "." if up else "x",
                         color="0.55", ms=2.5 if up else 3, mew=0.6, zorder=1)
        panels[0].plot([], [], ".", color="0.55", label="brute force, up")
        panels[0].plot([], [], "x", color="0.55", label="brute force, down")
    for b in range(ds.sizes["branch"]):
        first, size = int(ds["branch_first"].values[b]), int(ds["branch_size"].values[b])
        part = slice(first, first + size)
        colour = COLOURS[b % len(COLOURS)]
        p = int(ds["branch_periods"].values[b])
        state = stable[part] + 2 * impacting[part]
        for a, z, code in _runs(state):
            style = "-" if code % 2 else "--"
            width = 2.2 if code >= 2 else 1.3
            for j, ax_ in enumerate(panels[:-1]):
                for k in range(p):
                    ax_.plot(lam[part][a:z], sx[part, k, j][a:z], style, color=colour,
                             lw=width, zorder=3)
            for m in range(mod.shape[1]):
                panels[-1].plot(lam[part][a:z], mod[part, m][a:z], style, color=colour,
                                lw=1.0, zorder=3)
        panels[0].plot([], [], "-", color=colour, label=str(ds["branch_name"].values[b]))
    for e in range(ds.sizes["event"]):
        kind = str(ds["event_kind"].values[e])
        x = float(ds["event_parameter"].values[e])
        state = ds["event_state"].values[e]
        for j, ax_ in enumerate(panels[:-1]):
            y = float(state[2 * j])
            ax_.plot(x, y, MARKERS.get(kind, "*"), mfc="white", mec="black", ms=7, zorder=5)
            ax_.annotate(SHORT.get(kind, kind), (x, y), textcoords="offset points",
                         xytext=(4, 4), fontsize=8, zorder=6)
    panels[0].plot([], [], "--", color="0.3", label="unstable")
    if impacting.any():
        panels[0].plot([], [], "-", color="0.3", lw=2.2, label="impacting")
    for j, ax_ in enumerate(panels[:-1]):
        label = bodies[j] if len(bodies) > 1 else "x"
        ax_.set_ylabel(f"${label}(kT)$")
    panels[0].legend(loc="best", fontsize=7, ncol=2)
    panels[-1].axhline(1.0, color="0.4", lw=0.8)
    panels[-1].set_ylabel(r"$|\mu|$ (Floquet)")
    panels[-1].set_yscale("log")
    panels[-1].set_xlabel(f"${PARAMETER_TEX.get(name, name)}$")
    marks = ", ".join(f"{SHORT[k]} {k}" for k in MARKERS)
    root_figure(fig).suptitle(f"Continuation in ${PARAMETER_TEX.get(name, name)}$: stable "
                              f"solid, unstable dashed, impacting thick\n{marks}\n"
                              f"{parameter_text(ds, exclude=(name,))}", fontsize=8)
    return root_figure(fig)
