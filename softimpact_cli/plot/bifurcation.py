"""Figure 7: stroboscopic displacements of the left and right body against d, one colour
per followed solution, destruction points as vertical lines, impacting states marked."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..labels import latex_of
from . import parameter_text, pyplot
from .palette import IMPACTING, colour_of, solution_order


def plot_bifurcation(ds, out: str | Path) -> Path:
    plt = pyplot()
    from matplotlib.lines import Line2D

    d = ds["d"].values
    names = [str(n) for n in ds["branch_name"].values]
    order = solution_order(ds)
    fig, axs = plt.subplots(2, 1, figsize=(9, 8.3), sharex=True, constrained_layout=True)
    handles = []
    for i, name in enumerate(names):
        colour = colour_of(name, order)
        imp = ds["impacting"].values[i].astype(bool)
        for ax, var in zip(axs, ("section_x1", "section_x2"), strict=True):
            pts = ds[var].values[i]  # (d, point)
            dd = np.repeat(d[:, None], pts.shape[1], axis=1)
            ok = np.isfinite(pts)
            free = ok & ~imp[:, None]
            hit = ok & imp[:, None]
            ax.plot(dd[free], pts[free], ".", ms=2.5, color=colour)
            ax.plot(dd[hit], pts[hit], "x", ms=3, color=IMPACTING, alpha=0.8)
            x = float(ds["destroyed_at"].values[i])
            if np.isfinite(x):
                ax.axvline(x, color=colour, lw=0.9, ls="--")
        x = float(ds["destroyed_at"].values[i])
        falls = str(ds["falls_to"].values[i])
        fate = (f"falls to {latex_of(falls)}" if falls else
                f"still impacting at $d = {d[-1]:g}$")
        text = (f"destroyed at $d = {x:.4f}$, {fate}" if np.isfinite(x) else
                "not destroyed in the range")
        handles.append(Line2D([], [], color=colour, marker="o", ls="--",
                              label=f"{latex_of(name)}: {text}"))
    handles.append(Line2D([], [], color=IMPACTING, marker="x", ls="", label="impacting"))
    axs[0].set_ylabel("$x_1(nT)$ (left body)")
    axs[1].set_ylabel("$x_2(nT)$ (right body)")
    axs[1].set_xlabel("$d$")
    # below the panels: a legend inside would hide the branches near the top
    fig.legend(handles=handles, fontsize=8, loc="outside lower center", ncols=2)
    if d[0] > d[-1]:
        axs[1].set_xlim(d[0], d[-1])  # d decreases to the right, as it is followed
    fig.suptitle(f"{ds.attrs.get('model')} pair followed in d: "
                 + parameter_text(ds, exclude=("d",)), fontsize=8)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=130)
    plt.close(fig)
    return out
