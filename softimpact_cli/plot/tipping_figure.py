"""The tipping matrix (and, over a plane, the basins before and after) of a tipping
result."""

from __future__ import annotations

import numpy as np

from .basins_figure import draw_basins
from .common import place_panels


def draw_tipping(ds, no_basins: bool = False, ax=None):
    """Panels: basins before, basins after (a plane result, unless ``no_basins``), then
    the matrix P(i -> j) as a heat map annotated with its 95% Wilson interval; an Axes
    draws the matrix alone. Returns the Figure."""
    from matplotlib.axes import Axes

    plane = ds.attrs.get("ic_kind") == "plane" and not no_basins
    if isinstance(ax, Axes):
        plane = False
    n = 3 if plane else 1
    container, panels = place_panels(ax, (1, n), [(0, k) for k in range(n)],
                                     (5.0 * n, 4.6))
    if plane:
        draw_basins(ds.drop_vars([v for v in ds.data_vars if str(v).startswith("tip_")]),
                    ax=panels[:2])
        panels[0].set_title(f"before: {ds.attrs.get('tip_before', '')}", fontsize=9)
        panels[1].set_title(f"after: {ds.attrs.get('tip_after', '')}", fontsize=9)
    matrix_panel(ds, panels[-1])
    return container if not isinstance(ax, Axes) else ax.get_figure()


def matrix_panel(ds, ax) -> None:
    rows = [str(n) for n in ds["tip_from"].values]
    cols = [str(n) for n in ds["tip_to"].values]
    p = ds["tip_probability"].values
    low, high = ds["tip_ci95_low"].values, ds["tip_ci95_high"].values
    count = ds["tip_count"].values
    ax.imshow(p, cmap="Blues", vmin=0.0, vmax=1.0, aspect="auto")
    for i, j in np.ndindex(*p.shape):
        if count[i, j] == 0:
            continue
        ax.text(j, i, f"{p[i, j]:.2f}\n[{low[i, j]:.2f}, {high[i, j]:.2f}]", ha="center",
                va="center", fontsize=7, color="white" if p[i, j] > 0.6 else "black")
    shares = ds["tip_from_share"].values
    ax.set_yticks(range(len(rows)), [f"{r}\n({100 * s:.1f}%)" for r, s in
                                     zip(rows, shares, strict=True)], fontsize=7)
    ax.set_xticks(range(len(cols)), cols, fontsize=7, rotation=30, ha="right")
    ax.set_ylabel("basin before (share of starts)")
    ax.set_xlabel("label after")
    ax.set_title(f"tipping P(i -> j): {ds.attrs.get('tip_before', '')} -> "
                 f"{ds.attrs.get('tip_after', '')}", fontsize=9)
