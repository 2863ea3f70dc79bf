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


def branch_tex(name: str) -> str:
    """A branch's name typeset as the basin figures typeset solutions: the longest leading
    part that is a solution's name in LaTeX, the rest (``BP1+``, ``PD2``: where the branch
    was switched onto) as it is. ``"L1^1 R1-0^1 BP1+"`` -> ``"$L^{1}_{1}R^{1}_{1-0}$ BP1+"``."""
    words = name.split()
    for k in range(len(words), 0, -1):
        head = " ".join(words[:k])
        if (tex := latex_of(head)) != head:
            return " ".join([tex, *words[k:]])
    return name


def _free_slot(box, placed, inside) -> bool:
    """Whether a label box (x0, y0, x1, y1, pixels) overlaps none placed and lies inside
    ``inside`` (the axes' box) when that is given."""
    x0, y0, x1, y1 = box
    if inside is not None and not (x0 >= inside.x0 and x1 <= inside.x1
                                   and y0 >= inside.y0 and y1 <= inside.y1):
        return False
    return not any(x0 < q1 and q0 < x1 and y0 < r1 and r0 < y1 for q0, r0, q1, r1 in placed)


def _label_events(ax, points: list[tuple[float, float, str]]) -> None:
    """Name each event marker (LP, NS, ...) beside it: up and right of the marker when that
    place is free, else at the nearest free place (steps of a label's height up or down and
    of three characters left or right, nearest first) inside the axes, with a leader line;
    outside the axes only when no place inside is free. In display units, the axes' limits
    as autoscaled from the branches drawn so far."""
    ax.autoscale_view()
    dpi_scale = ax.figure.dpi / 72.0
    height = 1.25 * LABEL_FONT * dpi_scale  # pixels of one label line
    column = 3 * 0.65 * LABEL_FONT * dpi_scale  # pixels of three characters
    steps = sorted(((dx, dy) for dx in range(-4, 5) for dy in range(-12, 13)),
                   key=lambda d: (np.hypot(d[0] * column, d[1] * height), d[1] < 0, d[0] < 0))
    inside = ax.get_window_extent()
    placed: list[tuple[float, float, float, float]] = []
    for x, y, kind in sorted(points, key=lambda p: (p[0], p[1])):
        text = SHORT.get(kind, kind)
        width = 0.65 * LABEL_FONT * dpi_scale * len(text)
        px, py = ax.transData.transform((x, y))
        px, py = px + 4 * dpi_scale, py + 3 * dpi_scale
        boxes = [(px + dx * column, py + dy * height, px + dx * column + width,
                  py + dy * height + height) for dx, dy in steps]
        box = next((b for b in boxes if _free_slot(b, placed, inside)), None)
        if box is None:  # crowded beyond the axes' room: stack upwards, free of the others
            shift = 0.0
            while not _free_slot((px, py + shift, px + width, py + shift + height), placed,
                                 None):
                shift += height
            box = (px, py + shift, px + width, py + shift + height)
        placed.append(box)
        offset = ((box[0] - px) / dpi_scale + 4, (box[1] - py) / dpi_scale + 3)
        moved = (box[0], box[1]) != (px, py)
        ax.annotate(text, (x, y), textcoords="offset points", xytext=offset,
                    fontsize=LABEL_FONT, zorder=6,
                    arrowprops=dict(arrowstyle="-", lw=0.4, color="0.4") if moved else None)


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
    if ds.sizes.get("sweep", 0):  # a scene may ask for no brute-force sweep
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
        panels[0].plot([], [], "-", color=colour, label=branch_tex(branch))
    # a chain's grazing names its stop (G2: stop 2 grazed)
    stops = ds["event_stop"].values if "event_stop" in ds else np.zeros(ds.sizes["event"])
    events = [(float(ds["event_parameter"].values[e]), str(ds["event_kind"].values[e]),
               ds["event_state"].values[e], int(stops[e])) for e in range(ds.sizes["event"])]
    for j, ax_ in enumerate(panels[:-1]):
        for x, kind, state, _ in events:
            ax_.plot(x, float(state[2 * j]), MARKERS.get(kind, "*"), mfc="white", mec="black",
                     ms=7, zorder=5)
        _label_events(ax_, [(x, float(state[2 * j]), f"{SHORT[kind]}{stop}" if stop else kind)
                            for x, kind, state, stop in events])
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
