"""Two-parameter maps: predicted and found numbers of coexisting solutions, and where
they disagree."""

from __future__ import annotations

import numpy as np

from ..analysis.attributes import attribute_list
from ..config import GRID_AXES
from .basins_figure import SYMBOLS
from .common import panel_letter, parameter_text, pi_ticks, place_panels, root_figure, start_text

# what a panel means when it is zero everywhere (drawn as words, not a blank square)
ALL_ZERO = ("no coexisting non-impacting solution in this range",
            "no periodic attractor found in this range",
            "found and predicted agree at every point")


def _say_empty(ax, text: str) -> None:
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", fontsize=9,
            wrap=True, bbox={"boxstyle": "round", "fc": "w", "ec": "0.5"})


def draw_map(ds, ax=None):
    """Three panels over the two swept axes: predicted, found, their difference (``ax``:
    3 Axes in that order, or a Figure; see ``plot``); returns the matplotlib Figure."""
    import matplotlib

    chain = ds.attrs.get("model") == "chain"
    # a chain's axes are its parameters by name (grid_parameters), a preset's GRID_AXES
    axes = attribute_list(ds.attrs, "grid_parameters") if chain else GRID_AXES
    swept = [a for a in axes if ds.sizes.get(a, 1) > 1]
    if len(swept) != 2:
        raise ValueError(f"a map needs exactly two swept axes, got {swept or 'none'}")
    ax_x, ax_y = swept
    pred = ds["predicted_count"].squeeze(drop=True).transpose(ax_y, ax_x).values
    found = ds["found_count"].squeeze(drop=True).transpose(ax_y, ax_x).values
    free = ds["found_nonimpacting"].squeeze(drop=True).transpose(ax_y, ax_x).values
    x = ds[ax_x].values
    y = ds[ax_y].values
    hx = (x[-1] - x[0]) / max(1, len(x) - 1) / 2
    hy = (y[-1] - y[0]) / max(1, len(y) - 1) / 2
    extent = (x[0] - hx, x[-1] + hx, y[0] - hy, y[-1] + hy)  # cells centred on the grid
    top = int(max(pred.max(), found.max(), 1))
    fig, axs = place_panels(ax, (1, 3), [(0, 0), (0, 1), (0, 2)], figsize=(15, 5.0))
    cmap = matplotlib.colormaps["viridis"].resampled(top + 1)
    rule = "no stop reached" if chain else "$d_{crit} < d$"
    panels = ((pred, f"predicted (non-impacting, {rule})"),
              (found, "found (all periodic attractors)"))
    for k, (ax, (data, title)) in enumerate(zip(axs[:2], panels, strict=True)):
        im = ax.imshow(data, origin="lower", aspect="auto", extent=extent, cmap=cmap,
                       vmin=-0.5, vmax=top + 0.5, interpolation="nearest")
        ax.set_title(title, fontsize=9)
        fig.colorbar(im, ax=ax, ticks=range(top + 1), label="solutions")
        if not np.any(data):
            _say_empty(ax, ALL_ZERO[k])
    diff = free - pred
    lim = max(1, int(np.abs(diff).max()))
    im = axs[2].imshow(diff, origin="lower", aspect="auto", extent=extent, cmap="RdBu_r",
                       vmin=-lim - 0.5, vmax=lim + 0.5, interpolation="nearest")
    axs[2].set_title("found non-impacting minus predicted (0: agree)", fontsize=9)
    fig.colorbar(im, ax=axs[2], ticks=range(-lim, lim + 1))
    if not np.any(diff):
        _say_empty(axs[2], ALL_ZERO[2])
    for k, ax in enumerate(axs):
        ax.set_xlabel(f"${SYMBOLS[ax_x]}$" if ax_x in SYMBOLS else ax_x)
        ax.set_ylabel(f"${SYMBOLS[ax_y]}$" if ax_y in SYMBOLS else ax_y)
        for name, axis, (lo, hi) in ((ax_x, ax.xaxis, extent[:2]), (ax_y, ax.yaxis,
                                                                     extent[2:])):
            if name == "phi":
                pi_ticks(axis, lo, hi)
        panel_letter(ax, k)
    kind = "random " if ds.attrs.get("ic_kind") == "random" else ""
    n = int(np.prod([ds.sizes[d] for d in attribute_list(ds.attrs, "ic_dims")]))
    what = f"of {ds.attrs.get('bodies')} bodies" if chain else "pair"
    fig.suptitle(f"{ds.attrs.get('model')} {what} on a {len(x)} x {len(y)} grid, {n} {kind}"
                 f"initial conditions per point, {start_text(ds)}\n"
                 + parameter_text(ds, exclude=swept), fontsize=9)
    return root_figure(fig)
