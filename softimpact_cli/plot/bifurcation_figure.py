"""Figure 7: stroboscopic displacements of the left and right body against d. Each point
takes the colour of the solution the followed state is on at that d (so a destroyed
branch that falls onto another solution is drawn in that solution's colour); impacting
and unresolved states have their own markers; destruction points are vertical lines in
the colour of the solution destroyed."""

from __future__ import annotations

import numpy as np

from ..analysis.labels import latex_of
from .common import (
    PARAMETER_TEX,
    panel_letter,
    parameter_text,
    place_panels,
    root_figure,
    start_text,
)
from .palette import IMPACTING, SPECIAL, colour_of, solution_order

TRANSIENT = SPECIAL["unresolved"]


def point_styles(ds) -> dict[tuple[int, int], tuple[str, str]]:
    """(branch, step) -> (kind, solution name): kind 'solution' (a non-impacting
    solution of the catalogue, drawn in its colour), 'impacting', or 'transient' (no
    period found, diverged, or a solution outside the catalogue)."""
    table = {int(c): str(n) for c, n in zip(ds["label_code"].values, ds["label_name"].values,
                                            strict=True)}
    order = solution_order(ds) or [str(n) for n in ds["branch_name"].values]
    label = ds["label"].values
    impacting = ds["impacting"].values.astype(bool)
    out = {}
    for (i, j), code in np.ndenumerate(label):
        name = table.get(int(code), f"code {int(code)}")
        if impacting[i, j] or name.startswith("impacting"):
            out[i, j] = ("impacting", name)
        elif name in order:
            out[i, j] = ("solution", name)
        else:
            out[i, j] = ("transient", name)
    return out


def draw_bifurcation(ds, ax=None):
    """Two panels (left body, right body; one body: displacement, velocity) sharing the
    followed parameter, d by default (``ax``: 2 Axes in that order, or a Figure; see
    ``plot``); returns the matplotlib Figure."""
    from matplotlib.lines import Line2D

    p = str(ds.attrs.get("parameter", "d"))
    sym = PARAMETER_TEX.get(p, p)
    pair = "section_x2" in ds
    d = ds[p].values
    names = [str(n) for n in ds["branch_name"].values]
    order = solution_order(ds) or names
    styles = point_styles(ds)
    fig, axs = place_panels(ax, (2, 1), [(0, 0), (1, 0)], figsize=(9, 8.6), sharex=True)
    groups: dict[tuple[str, str], list[int]] = {}
    for (i, j), key in styles.items():
        groups.setdefault(key, []).append(i * len(d) + j)
    drawn = [n for n in order if ("solution", n) in groups]

    def rank(key):
        kind, name = key
        return (kind == "solution", drawn.index(name) if name in drawn else 0)

    variables = ("section_x1", "section_x2") if pair else ("section_x1", "section_v1")
    for ax, var in zip(axs, variables, strict=True):
        pts = ds[var].values.reshape(len(names) * len(d), -1)  # (branch * d, point)
        dd = np.tile(d, len(names))
        for (kind, name), rows in sorted(groups.items(), key=lambda g: rank(g[0])):
            y = pts[rows]
            x = np.repeat(dd[rows][:, None], y.shape[1], axis=1)
            ok = np.isfinite(y)
            if kind == "solution":
                # solutions that share a body's state (L1^1 R^1 and L1^1 R^2 on the left)
                # lie on one another: concentric dots, the first in catalogue order largest
                size = 2.5 + 1.3 * (len(drawn) - 1 - drawn.index(name))
                ax.plot(x[ok], y[ok], "o", ms=size, mew=0, color=colour_of(name, order),
                        zorder=3)
            elif kind == "impacting":
                ax.plot(x[ok], y[ok], "x", ms=3.5, color=IMPACTING, alpha=0.8, zorder=2)
            else:
                ax.plot(x[ok], y[ok], "+", ms=3, color=TRANSIENT, alpha=0.6, zorder=1)
        for i, name in enumerate(names):
            at = float(ds["destroyed_at"].values[i])
            if np.isfinite(at):
                ax.axvline(at, color=colour_of(name, order), lw=0.9, ls="--")
    handles = []
    for i, name in enumerate(names):
        at = float(ds["destroyed_at"].values[i])
        falls = str(ds["falls_to"].values[i])
        fate = (f"falls to {latex_of(falls)}" if falls else
                f"no non-impacting solution reached by ${sym} = {d[-1]:g}$")
        text = (f"destroyed at ${sym} = {at:.4f}$ (dashed), {fate}" if np.isfinite(at) else
                "not destroyed in the range")
        handles.append(Line2D([], [], color=colour_of(name, order), marker="o", ls="--",
                              label=f"{latex_of(name)}: {text}"))
    kinds = {kind for kind, _ in styles.values()}
    if "impacting" in kinds:
        handles.append(Line2D([], [], color=IMPACTING, marker="x", ls="",
                              label="impacting state"))
    if "transient" in kinds:
        handles.append(Line2D([], [], color=TRANSIENT, marker="+", ls="",
                              label="no period found (transient) or diverged"))
    if pair:
        axs[0].set_ylabel("$x_1(t_0 + nT)$ (left body)")
        axs[1].set_ylabel("$x_2(t_0 + nT)$ (right body)")
    else:
        axs[0].set_ylabel("$x(t_0 + nT)$")
        axs[1].set_ylabel("$\\dot x(t_0 + nT)$")
    axs[1].set_xlabel(f"${sym}$")
    for k, ax in enumerate(axs):
        panel_letter(ax, k)
    # below the panels: a legend inside would hide the branches near the top
    fig.legend(handles=handles, fontsize=8, loc="outside lower center", ncols=2,
               title=f"each point in the colour of the solution it is on at that ${sym}$",
               title_fontsize=8)
    if d[0] > d[-1]:
        axs[1].set_xlim(d[0], d[-1])  # decreasing to the right, as it is followed
    step = abs(float(d[1] - d[0])) if len(d) > 1 else 0.0
    fig.suptitle(f"{ds.attrs.get('model')} {'pair' if pair else 'body'} followed in ${sym}$ "
                 f"from {d[0]:g} to {d[-1]:g} (step {step:g}), {start_text(ds)}\n"
                 + parameter_text(ds, exclude=(p,)), fontsize=9)
    return root_figure(fig)


def draw_chain_bifurcation(ds, ax=None):
    """A chain's (dims branch, step, point, body): one panel per body, its section
    displacements against the followed parameter, a colour per branch (filled while on
    it, hollow after), the destruction points as dashed lines."""
    bodies = [int(b) for b in ds["body"].values]
    container, panels = place_panels(ax, (1, len(bodies)), [(0, k) for k in range(len(bodies))],
                                     (3.6 * len(bodies), 3.4), sharex=True)
    p = str(ds.attrs.get("parameter", ""))
    steps = ds["step"].values
    names = [str(n) for n in ds["branch_name"].values]
    for k, panel in enumerate(panels):
        for i, name in enumerate(names):
            colour = f"C{i % 10}"
            alive = ds["alive"].values[i].astype(bool)
            x = ds["section_x"].values[i, :, :, k]
            for mask, face in ((alive, colour), (~alive, "none")):
                s = np.repeat(steps[mask], x.shape[1])
                panel.scatter(s, x[mask].ravel(), s=6, facecolors=face, edgecolors=colour,
                              linewidths=0.6, label=name if face != "none" and k == 0 else None)
            at = ds["destroyed_at"].values[i]
            if np.isfinite(at):
                panel.axvline(at, color=colour, ls="--", lw=0.8)
        panel.set_xlabel(p)
        panel.set_ylabel(f"x{bodies[k]}")
        panel_letter(panel, k)
    if names:
        panels[0].legend(fontsize="x-small")
    return root_figure(container)
