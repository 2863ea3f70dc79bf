"""Basins of attraction on a plane of initial conditions, one panel per grid point."""

from __future__ import annotations

from math import ceil

import numpy as np

from ..analysis.attributes import attribute_list
from ..analysis.labels import NONPERIODIC_KINDS, parse_label
from ..config.axes import COUPLING_AXES
from ..sweep.result import grid_axes, grid_dims, grid_point
from .common import (
    PARAMETER_TEX,
    axis_value_text,
    is_figure,
    panel_letter,
    parameter_text,
    place_panels,
    root_figure,
    start_text,
    wrap_tex,
)
from .palette import colour_of, solution_order

SYMBOLS = {**PARAMETER_TEX, "t0": "t_0"}  # of every grid axis
AXIS_SYMBOLS = {"x1": "x_1", "x2": "x_2", "v1": r"\dot x_1", "v2": r"\dot x_2", "x": "x",
                "v": r"\dot x"}
# an attractor's section points: its basin's colour inside a black ring and a white
# halo, so they read on any basin (a dot of the basin's own colour read as a hole)
MARKER = {"marker": "o", "ms": 7, "mec": "k", "mew": 1.4, "ls": ""}
# the point cloud of an attractor that is not periodic (up to 200 section points): dots
CLOUD = {"marker": "o", "ms": 2.0, "mec": "w", "mew": 0.3, "ls": ""}


def _not_periodic(name: str) -> bool:
    """A chaotic or quasi-periodic attractor's name (its points are a cloud)."""
    try:
        return parse_label(name).kind in NONPERIODIC_KINDS
    except ValueError:
        return False


def _halo():
    from matplotlib import patheffects

    return [patheffects.withStroke(linewidth=3.5, foreground="w")]


def varying_axes(ds, always=("d", "phi")) -> list[str]:
    """Grid axes whose value differs between panels (pairs: d and phi always)."""
    dims = grid_dims(ds)
    shape = tuple(ds.sizes[d] for d in dims)
    points = [grid_point(ds, index) for index in np.ndindex(*shape)]
    out = []
    for a in grid_axes(ds):
        if a in COUPLING_AXES and int(ds.attrs.get("bodies", 2)) == 1:
            continue  # one body: no coupling
        values = {str(p[a]) for p in points}
        if len(values) > 1 or (a in always and a != "t0"):
            out.append(a)
    return out


def panel_title(ds, index: tuple[int, ...], axes=None) -> str:
    """Parameters of one grid point that vary between panels (``axes``, default
    ``varying_axes``): d and phi for a pair, t0 as a multiple of T."""
    T = float(ds.attrs["forcing_period"])
    point = grid_point(ds, index)
    parts = []
    for a in varying_axes(ds) if axes is None else axes:
        v = point[a]
        if isinstance(v, str):
            continue
        if a not in SYMBOLS:  # a chain's parameter by its name (stop.1.d): plain text
            parts.append(f"{a} = {v:g}")
            continue
        parts.append(f"${SYMBOLS[a]} = {axis_value_text(a, v, T)}$")
    return ", ".join(parts)


def figure_title(ds, varying: list[str], shape: tuple[int, int], n_panels: int) -> str:
    """One title for the figure: model, plane, resolution, start time and every parameter
    that is the same in all panels (those that differ are in the panel titles)."""
    a0, a1 = attribute_list(ds.attrs, "ic_dims")
    variables = [str(v) for v in ds["variable"].values]
    fixed = ds.attrs.get("plane_fixed") or ", ".join(
        f"${AXIS_SYMBOLS.get(v, v)} = 0$" for v in variables if v not in (a0, a1))
    bodies = int(ds.attrs.get("bodies", 2))
    chain = ds.attrs.get("model") == "chain"
    pair = bodies == 2 and not chain
    what = f"of {bodies} bodies" if chain else "pair" if pair else "body"
    head = (f"{ds.attrs.get('model')} {what}: basins on "
            f"$({AXIS_SYMBOLS.get(a0, a0)}, {AXIS_SYMBOLS.get(a1, a1)})$"
            + (f", {fixed}" if fixed else "")
            + f"; {shape[0]} x {shape[1]} initial conditions"
            + (" per panel" if n_panels > 1 else ""))
    T = float(ds.attrs["forcing_period"])
    common = []
    if n_panels and "t0" not in varying:
        common.append(start_text(ds, (0,) * len(grid_dims(ds))))
    first = grid_point(ds, (0,) * len(grid_dims(ds)))
    for a in COUPLING_AXES:
        if a in varying or not pair:
            continue
        common.append(f"${SYMBOLS[a]} = {axis_value_text(a, first[a], T)}$")
    params = parameter_text(ds, exclude=COUPLING_AXES + tuple(varying))
    return head + "\n" + ", ".join(common + ([params] if params else []))


def draw_basins(ds, max_panels: int = 36, ax=None):
    """Categorical basin maps: one colour per label (fixed palette), the attractors'
    section points as ringed markers, per panel a legend pairing each basin's colour with
    its attractor's marker and its share; returns the matplotlib Figure.

    One panel per grid point (in the grid's C order), three per row; ``ax``: an Axes
    for a result of one grid point, one Axes per grid point, or a Figure (see ``plot``).
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.legend_handler import HandlerTuple
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    axes_names = attribute_list(ds.attrs, "ic_dims")
    if ds.attrs.get("ic_kind") != "plane" or len(axes_names) != 2:
        raise ValueError("basin plots need initial conditions on a plane")
    a0, a1 = axes_names
    codes = [int(c) for c in ds["label_code"].values]
    names = [str(n) for n in ds["label_name"].values]
    latex = [str(n) for n in ds["label_latex"].values]
    label = ds["label"].transpose(*grid_dims(ds), a0, a1).values
    grid_shape = label.shape[: len(grid_dims(ds))]
    n_panels = int(np.prod(grid_shape))
    if n_panels > max_panels:
        raise ValueError(f"{n_panels} grid points; at most {max_panels} panels (raise "
                         "--max-panels)")
    position = {c: i for i, c in enumerate(codes)}
    order = solution_order(ds)
    cmap = ListedColormap([colour_of(n, order) for n in names])
    x = ds[a0].values
    y = ds[a1].values
    variables = [str(v) for v in ds["variable"].values]
    i0, i1 = variables.index(a0), variables.index(a1)
    ncols = min(3, n_panels)
    nrows = ceil(n_panels / ncols)
    own_axes = ax is not None and not is_figure(ax)  # the caller's Axes, in its own figure
    fig, panels = place_panels(ax, (nrows, ncols),
                               [divmod(k, ncols) for k in range(n_panels)],
                               figsize=(4.6 * ncols, 5.0 * nrows + 0.6))
    varying = varying_axes(ds)
    halo = _halo()
    for k, index in enumerate(np.ndindex(*grid_shape)):
        ax = panels[k]
        lab = label[index]
        img = np.vectorize(position.get)(lab)
        dx = (x[-1] - x[0]) / max(1, len(x) - 1) / 2
        dy = (y[-1] - y[0]) / max(1, len(y) - 1) / 2
        ax.imshow(img.T, origin="lower", cmap=cmap, vmin=-0.5, vmax=len(codes) - 0.5,
                  extent=(x[0] - dx, x[-1] + dx, y[0] - dy, y[-1] + dy), aspect="auto",
                  interpolation="nearest")
        handles = []
        total = lab.size
        for j, code in enumerate(codes):
            count = int((lab == code).sum())
            pts = ds["attractor_points"].values[(j,) + index]
            pts = pts[np.isfinite(pts[:, 0])]
            if count == 0 and pts.size == 0:
                continue
            colour = colour_of(names[j], order)
            patch = Patch(facecolor=colour, edgecolor="k", lw=0.5)
            text = f"{latex[j]}  {100 * count / total:.1f}%"
            if pts.size:
                cloud = _not_periodic(names[j])  # dots, no halo: many points
                ax.plot(pts[:, i0], pts[:, i1], mfc=colour, zorder=3,
                        path_effects=[] if cloud else halo, **(CLOUD if cloud else MARKER))
                marker = Line2D([], [], mfc=colour, path_effects=halo, **MARKER)
                handles.append(((patch, marker), text))
            else:
                handles.append((patch, text))
        ax.set_xlim(x[0] - dx, x[-1] + dx)
        ax.set_ylim(y[0] - dy, y[-1] + dy)
        ax.set_xlabel(f"${AXIS_SYMBOLS.get(a0, a0)}$")
        ax.set_ylabel(f"${AXIS_SYMBOLS.get(a1, a1)}$")
        title = panel_title(ds, index, varying)
        if n_panels > 1:
            panel_letter(ax, k)
            ax.set_title(title, fontsize=9)
        # below the panel: a legend inside could hide basins and attractor markers
        ax.legend([h for h, _ in handles], [t for _, t in handles], fontsize=7,
                  loc="upper center", bbox_to_anchor=(0.5, -0.13),
                  ncols=min(3, len(handles)), frameon=False,
                  handler_map={tuple: HandlerTuple(ndivide=None, pad=0.3)})
    head = figure_title(ds, varying, (len(x), len(y)), n_panels)
    note = ("markers: each attractor's points at $t = t_0 + nT$, in its basin's colour; "
            "legend: basin, attractor, share of the plane")
    if n_panels == 1 and own_axes:
        # one panel among the caller's: its parameters only; the figure and the other
        # panels are the caller's, and a five-line description on each would repeat
        panels[0].set_title(panel_title(ds, (0,) * len(grid_shape), varying), fontsize=9)
    elif n_panels == 1:
        title = panel_title(ds, (0,) * len(grid_shape), varying)
        head = head.replace("\n", (", " + title if title else "") + "\n", 1)
        panels[0].set_title(wrap_tex(f"{head}\n{note}", 75), fontsize=8)
    else:
        fig.suptitle(wrap_tex(f"{head}\n{note}", 100 * ncols), fontsize=9)
    return root_figure(fig)
