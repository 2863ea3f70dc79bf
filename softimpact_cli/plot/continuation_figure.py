"""Continuation: branches against the parameter, and their Floquet multipliers.

Top panel(s): the section displacement x of each body (one panel per body) at t = kT of
every point of every branch (a period-p branch draws p curves), stable runs solid,
unstable dashed, impacting runs thicker; bifurcations marked and named; the brute-force
sweeps' section points (up: small grey dots, down: small grey crosses) overlaid. Bottom
panel: the moduli |mu| of the multipliers along each branch, 1 marked.
"""

from __future__ import annotations

import numpy as np

from ..analysis.labels import latex_of
from .common import PARAMETER_TEX, parameter_text, place_panels, root_figure
from .palette import colour_of, solution_order

LABEL_FONT = 8  # points: the event labels (LP, NS, ...)
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


def _label_events(ax, points: list[tuple[float, float, str]]) -> None:
    """Name each event marker (LP, NS, ...) beside it, moving a label up, in steps of its
    height, while it would overlap one placed before (in display units: the axes' limits
    as autoscaled from the branches drawn so far)."""
    ax.autoscale_view()
    dpi_scale = ax.figure.dpi / 72.0
    height = 1.25 * LABEL_FONT * dpi_scale  # pixels of one label line
    placed: list[tuple[float, float, float]] = []  # (x, y, width) in pixels
    for x, y, kind in sorted(points, key=lambda p: (p[0], p[1])):
        text = SHORT.get(kind, kind)
        width = 0.65 * LABEL_FONT * dpi_scale * len(text)
        px, py = ax.transData.transform((x, y))
        px, py = px + 4 * dpi_scale, py + 3 * dpi_scale
        shift = 0.0
        while any(abs(px - qx) < max(width, qw) and abs(py + shift - qy) < height
                  for qx, qy, qw in placed):
            shift += height
        placed.append((px, py + shift, width))
        ax.annotate(text, (x, y), textcoords="offset points",
                    xytext=(4, 3 + shift / dpi_scale), fontsize=LABEL_FONT, zorder=6,
                    arrowprops=dict(arrowstyle="-", lw=0.4, color="0.4") if shift else None)


def draw_continuation(ds, ax=None):
    """``len(body) + 1`` panels stacked (``ax``: that many Axes or a Figure)."""
    bodies = [str(b) for b in ds["body"].values]
    order = solution_order(ds)
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
        branch = str(ds["branch_name"].values[b])
        colour = colour_of(branch, order)  # the solution's colour in the basin figures
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
        panels[0].plot([], [], "-", color=colour, label=latex_of(branch))
    events = [(float(ds["event_parameter"].values[e]), str(ds["event_kind"].values[e]),
               ds["event_state"].values[e]) for e in range(ds.sizes["event"])]
    for j, ax_ in enumerate(panels[:-1]):
        points = [(x, float(state[2 * j]), kind) for x, kind, state in events]
        for x, y, kind in points:
            ax_.plot(x, y, MARKERS.get(kind, "*"), mfc="white", mec="black", ms=7, zorder=5)
        _label_events(ax_, points)
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
