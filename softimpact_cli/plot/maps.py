"""Two-parameter maps: predicted and found numbers of coexisting solutions, and where
they disagree."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..info import GRID_AXES
from . import parameter_text, pyplot
from .basins import SYMBOLS


def plot_map(ds, out: str | Path) -> Path:
    plt = pyplot()
    swept = [a for a in GRID_AXES if ds.sizes.get(a, 1) > 1]
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
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    cmap = plt.get_cmap("viridis", top + 1)
    panels = ((pred, "predicted (non-impacting, $d_{crit} < d$)"),
              (found, "found (all periodic attractors)"))
    for ax, (data, title) in zip(axs[:2], panels, strict=True):
        im = ax.imshow(data, origin="lower", aspect="auto", extent=extent, cmap=cmap,
                       vmin=-0.5, vmax=top + 0.5, interpolation="nearest")
        ax.set_title(title, fontsize=9)
        fig.colorbar(im, ax=ax, ticks=range(top + 1), label="solutions")
    diff = free - pred
    lim = max(1, int(np.abs(diff).max()))
    im = axs[2].imshow(diff, origin="lower", aspect="auto", extent=extent, cmap="RdBu_r",
                       vmin=-lim - 0.5, vmax=lim + 0.5, interpolation="nearest")
    axs[2].set_title("found non-impacting minus predicted (0: agree)", fontsize=9)
    fig.colorbar(im, ax=axs[2], ticks=range(-lim, lim + 1))
    for ax in axs:
        ax.set_xlabel(f"${SYMBOLS[ax_x]}$")
        ax.set_ylabel(f"${SYMBOLS[ax_y]}$")
    n = int(np.prod([ds.sizes[d] for d in str(ds.attrs["ic_dims"]).split()]))
    fig.suptitle(f"{ds.attrs.get('model')} pair, {n} samples per point: "
                 + parameter_text(ds, exclude=swept), fontsize=9)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=130)
    plt.close(fig)
    return out
