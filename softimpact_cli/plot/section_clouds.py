"""The section point clouds of the attractors that are not periodic (the second stage's
``nonperiodic_*`` rows of a sweep result): one colour per attractor, one marker shape per
grid point, the largest Lyapunov exponent in the legend."""

from __future__ import annotations

import numpy as np

from ..analysis.attributes import attribute_list
from ..report.nonperiodic import nonperiodic_summary
from .basins_figure import AXIS_SYMBOLS
from .palette import colour_of

SHAPES = "o^sDvP*Xh<>"  # one per grid point (cycled)


def draw_clouds(ds, ax, variables: tuple[int, int] = (0, 1)) -> None:
    """Scatter each row's cloud on the plane of state ``variables`` (indices into
    ``ds.variable``; default the first body's x and v) in ``ax``."""
    rows = nonperiodic_summary(ds)
    names = [str(v) for v in ds["variable"].values]
    i0, i1 = variables
    points = sorted({int(p) for p in ds["nonperiodic_point"].values})
    for k, row in enumerate(rows):
        cloud = ds["nonperiodic_cloud"].values[k]
        cloud = cloud[np.isfinite(cloud[:, 0])]
        where = ", ".join(f"{a}={v:.4g}" for a, v in row["at"].items()
                          if a in attribute_list(ds.attrs, "grid_swept"))
        shape = SHAPES[points.index(int(ds["nonperiodic_point"].values[k])) % len(SHAPES)]
        label = (f"{row['name']}{' (' + where + ')' if where else ''}: "
                 f"$\\lambda_1$ = {row['exponents'][0]:+.4f}")
        ax.plot(cloud[:, i0], cloud[:, i1], ls="", marker=shape, ms=2.5, mew=0,
                color=colour_of(row["name"]), label=label)
    ax.set_xlabel(f"${AXIS_SYMBOLS.get(names[i0], names[i0])}$")
    ax.set_ylabel(f"${AXIS_SYMBOLS.get(names[i1], names[i1])}$")
    ax.set_title("section points of the attractors that are not periodic", fontsize=9)
    if rows:
        ax.legend(fontsize=7, markerscale=3, loc="best")
    else:
        ax.text(0.5, 0.5, "none in this result", ha="center", va="center",
                transform=ax.transAxes)
