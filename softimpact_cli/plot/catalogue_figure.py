"""Catalogue figures: the one-body attractors (figs 4, 9) and the combinations (fig 10)."""

from __future__ import annotations

from math import ceil

import numpy as np

from ..analysis.labels import latex_of
from ..config.axes import COUPLING_AXES
from .common import (
    is_figure,
    new_figure,
    panel_letter,
    parameter_text,
    phase_text,
    place_panels,
    root_figure,
    start_text,
)
from .palette import colour_of

# A catalogue with more combinations than this (figure 13's 28) is laid out compactly:
# six columns of smaller panels sharing one x1/x2 scale, the attractors in the top left.
COMPACT_AFTER = 9
COMPACT_COLUMNS = 6


def _catalogue_panels(ax, n_combos: int):
    """(container, attractor panel, combination panels): the attractors in a column
    spanning the figure's height beside three columns of combinations (or, past
    COMPACT_AFTER combinations, in the top left of six columns), or ``ax``."""
    if ax is not None and not is_figure(ax):
        fig, panels = place_panels(ax, (1, 1 + n_combos),
                                   [(0, k) for k in range(1 + n_combos)], None)
        return fig, panels[0], panels[1:]
    if n_combos > COMPACT_AFTER:
        cols, half = COMPACT_COLUMNS, COMPACT_COLUMNS // 2
        rows = 2 + ceil(max(0, n_combos - 2 * half) / cols)
        fig = new_figure(figsize=(2.6 * cols, 2.1 * rows + 0.8)) if ax is None else ax
        grid = fig.add_gridspec(rows, cols)
        first = fig.add_subplot(grid[:2, :half])
        cells = [(r, c) for r in range(2) for c in range(half, cols)]
        cells += [(r, c) for r in range(2, rows) for c in range(cols)]
        combo_axes = []
        for r, c in cells[:n_combos]:
            share = combo_axes[0] if combo_axes else None
            combo_axes.append(fig.add_subplot(grid[r, c], sharey=share))
        return fig, first, combo_axes
    ncols = 4 if n_combos else 1
    nrows_c = ceil(n_combos / (ncols - 1)) if n_combos else 0
    nrows = max(1, nrows_c, 2 if n_combos else 1)
    fig = new_figure(figsize=(4.0 * ncols, 2.6 * nrows + 0.6)) if ax is None else ax
    grid = fig.add_gridspec(nrows, ncols)
    first = fig.add_subplot(grid[:, 0] if n_combos else grid[0, 0])
    return fig, first, [fig.add_subplot(grid[n // (ncols - 1), 1 + n % (ncols - 1)])
                        for n in range(n_combos)]


BODY_STYLES = (("tab:blue", "o"), ("tab:red", "s"), ("tab:green", "^"), ("tab:purple", "v"),
               ("tab:orange", "D"), ("tab:brown", "P"), ("tab:pink", "X"), ("tab:olive", "*"))


def _body_curves(ds, n: int, spp: int):
    """Per body of combination ``n``: (x(t) over its joint period, ``spp`` samples per
    period; its section displacements). A pair's bodies are the left attractor and the
    right body's; a chain's (``combination_attractor``), each body's own attractor."""
    q = int(ds["combination_period"].values[n])
    idx = np.arange(q * spp)
    orbit = ds["combination_orbit"].values[n, :q]
    if "combination_attractor" in ds:  # a chain: (body, number) -> its attractor row
        rows = {(int(b), int(k)): i for i, (b, k) in enumerate(zip(
            ds["attractor_body"].values, ds["attractor_number"].values, strict=True))}
        out = []
        for b, (number, s) in enumerate(zip(ds["combination_attractor"].values[n],
                                            ds["combination_shift"].values[n], strict=True)):
            i = rows[(b + 1, int(number))]
            p = int(ds["attractor_period"].values[i])
            x = ds["attractor_curve"].values[i, (idx + int(s) * spp) % (p * spp), 0]
            out.append((x, orbit[:, 2 * b]))
        return out
    i_l = list(ds["attractor"].values).index(int(ds["combination_left"].values[n]))
    i_r = list(ds["attractor"].values).index(int(ds["combination_right"].values[n]))
    s = int(ds["combination_shift"].values[n])
    pl = int(ds["attractor_period"].values[i_l])
    pr = int(ds["attractor_period"].values[i_r])
    x1 = ds["attractor_curve"].values[i_l, idx % (pl * spp), 0]
    x2 = ds["right_curve"].values[i_r, (idx + s * spp) % (pr * spp), 0]
    return [(x1, orbit[:, 0]), (x2, orbit[:, 2])]


def draw_catalogue(ds, ax=None):
    """Left: attractors on (x, x') with section points. Right: one panel per combination,
    x1(t) and x2(t) over the joint period, section times marked. Returns the Figure.

    ``ax``: an Axes (a one-body catalogue), 1 + one per combination Axes (attractors
    first), or a Figure (see ``plot``)."""
    names = [str(n) for n in ds["attractor_name"].values]
    combos = [str(n) for n in ds["combination_name"].values] if "combination_name" in ds else []
    fig, ax, combo_axes = _catalogue_panels(ax, len(combos))
    spp = int(ds.attrs["curve_samples_per_period"])
    for i, name in enumerate(names):
        p = int(ds["attractor_period"].values[i])
        curve = ds["attractor_curve"].values[i, : p * spp]
        pts = ds["attractor_points"].values[i, :p]
        c = colour_of(name, names)
        ax.plot(curve[:, 0], curve[:, 1], color=c, lw=1.2, label=latex_of(name))
        ax.plot(pts[:, 0], pts[:, 1], "o", ms=6, color=c, mec="k", zorder=3)
        for k, (x, v) in enumerate(pts):
            ax.annotate(str(k), (x, v), textcoords="offset points", xytext=(4, 4), fontsize=8)
        if "right_curve" in ds:
            rc = ds["right_curve"].values[i, : p * spp]
            rp = ds["right_points"].values[i, :p]
            ax.plot(rc[:, 0], rc[:, 1], color=c, lw=0.8, ls="--")
            ax.plot(rp[:, 0], rp[:, 1], "s", ms=4, color=c, mec="k", zorder=3)
    ax.set_xlabel("$x$")
    ax.set_ylabel(r"$\dot x$")
    title = "attractors (dots: $t = t_0 + nT$, numbered in canonical order)"
    if "right_curve" in ds:
        title += "\nsolid/circles: left body, dashed/squares: right body"
    ax.set_title(title, fontsize=8)
    ax.legend(fontsize=8, loc="best")
    T = float(ds.attrs["forcing_period"])
    for n, cname in enumerate(combos):
        cax = combo_axes[n]
        q = int(ds["combination_period"].values[n])
        t = np.arange(q * spp) / spp
        curves = _body_curves(ds, n, spp)
        styles = [BODY_STYLES[b % len(BODY_STYLES)] for b in range(len(curves))]
        for b, ((x, _), (colour, _)) in enumerate(zip(curves, styles, strict=True)):
            cax.plot(t, x, color=colour, lw=1, label=f"$x_{{{b + 1}}}$")
        for (_, orbit_x), (colour, marker) in zip(curves, styles, strict=True):
            cax.plot(np.arange(q), orbit_x, marker, ms=3, color=colour)
        cax.set_title(latex_of(cname), fontsize=11)
        for spine in cax.spines.values():  # the label's colour, as in the basin figures
            spine.set_edgecolor(colour_of(cname, combos))
            spine.set_linewidth(2.0)
        compact = len(combos) > COMPACT_AFTER
        if not compact or n >= len(combos) - COMPACT_COLUMNS:  # the bottom row only
            cax.set_xlabel("$(t - t_0)/T$", fontsize=9)
        if compact and cax.get_subplotspec().colspan.start not in (0, COMPACT_COLUMNS // 2):
            cax.tick_params(labelleft=False)  # one shared x1/x2 scale: the row's first
        cax.tick_params(labelsize=8)
        if n == 0:
            cax.legend(fontsize=8, loc="upper right")
    if combos:
        for k, a in enumerate([ax, *combo_axes]):
            panel_letter(a, k, fontsize=10)
    phi = ds.attrs.get("phi")
    params = parameter_text(ds, exclude=COUPLING_AXES)
    fig.suptitle(f"{ds.attrs.get('model', '')} catalogue: {params}"
                 + (f", right body's forcing phase $\\varphi = {phase_text(float(phi))}$"
                    if phi is not None and combos else "")
                 + f"; {start_text(ds)}, $T = 2\\pi/\\omega = {T:.4g}$", fontsize=10)
    return root_figure(fig)
