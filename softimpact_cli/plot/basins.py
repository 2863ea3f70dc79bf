"""Basins of attraction on a plane of initial conditions, one panel per grid point."""

from __future__ import annotations

from math import ceil
from pathlib import Path

import numpy as np

from ..expressions import format_multiple
from ..info import GRID_AXES, grid_dims, grid_point
from . import parameter_text, pyplot
from .palette import colour_of, solution_order

SYMBOLS = {"d": "d", "phi": r"\varphi", "k_c": "k_c", "c_c": "c_c", "t0": "t_0"}
AXIS_SYMBOLS = {"x1": "x_1", "x2": "x_2", "v1": r"\dot x_1", "v2": r"\dot x_2", "x": "x",
                "v": r"\dot x"}


def panel_title(ds, index: tuple[int, ...], always=("d", "phi")) -> str:
    """Parameters of one grid point: the swept ones and d, phi (t0 as a fraction of T)."""
    swept = str(ds.attrs.get("grid_swept", "")).split()
    T = float(ds.attrs["forcing_period"])
    point = grid_point(ds, index)
    parts = []
    for a in GRID_AXES:
        if a not in swept and a not in always:
            continue
        if a in ("d", "phi") and int(ds.attrs.get("bodies", 2)) == 1:
            continue
        v = point[a]
        text = (format_multiple(v, "\\pi", np.pi) if a == "phi" else
                format_multiple(v, "T", T) if a == "t0" else f"{v:.6g}").replace("*", "")
        parts.append(f"${SYMBOLS[a]} = {text}$")
    if "t0" not in swept:
        mode = ds.attrs.get("t0_mode", "fixed")
        parts.append("random $t_0$" if mode == "random" else
                     f"$t_0 = {format_multiple(point['t0'], 'T', T).replace('*', '')}$")
    return ", ".join(parts)


def plot_basins(ds, out: str | Path, max_panels: int = 36) -> Path:
    """Categorical basin maps: one colour per label (fixed palette), attractors' section
    points projected as dots, a legend with LaTeX names and each basin's share."""
    plt = pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    axes_names = str(ds.attrs["ic_dims"]).split()
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
    fig, axs = plt.subplots(nrows, ncols, figsize=(4.6 * ncols, 5.0 * nrows + 0.4),
                            squeeze=False, constrained_layout=True)
    for k, index in enumerate(np.ndindex(*grid_shape)):
        ax = axs[k // ncols, k % ncols]
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
            if pts.size:
                ax.plot(pts[:, i0], pts[:, i1], "o", ms=6, mfc=colour, mec="k", mew=1.0,
                        zorder=3)
            handles.append(Patch(facecolor=colour, edgecolor="k",
                                 label=f"{latex[j]}  {100 * count / total:.1f}%"))
        ax.set_xlim(x[0] - dx, x[-1] + dx)
        ax.set_ylim(y[0] - dy, y[-1] + dy)
        ax.set_xlabel(f"${AXIS_SYMBOLS.get(a0, a0)}$")
        ax.set_ylabel(f"${AXIS_SYMBOLS.get(a1, a1)}$")
        ax.set_title(panel_title(ds, index), fontsize=9)
        # below the panel: a legend inside could hide basins and attractor dots
        ax.legend(handles=handles, fontsize=7, loc="upper center",
                  bbox_to_anchor=(0.5, -0.13), ncols=min(3, len(handles)), frameon=False)
    for k in range(n_panels, nrows * ncols):
        axs[k // ncols, k % ncols].axis("off")
    fixed = ds.attrs.get("plane_fixed") or ", ".join(
        f"{v} = 0" for v in variables if v not in (a0, a1))
    fixed = f"; {fixed}" if fixed else ""
    import textwrap

    swept = set(str(ds.attrs.get("grid_swept", "")).split())
    params = "\n".join(textwrap.wrap(parameter_text(ds, exclude=swept), 60 * ncols))
    fig.suptitle(f"{ds.attrs.get('model')} basins{fixed}\n{params}", fontsize=9)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=130)
    plt.close(fig)
    return out
