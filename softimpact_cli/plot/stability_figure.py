"""Basin-stability curves (figure 15): one line per non-impacting solution, one for all
impacting solutions, one for the non-impacting sum, with 95% Wilson bands."""

from __future__ import annotations

import numpy as np

from ..analysis.attributes import attribute_list
from ..analysis.labels import latex_of, parse_label
from ..sweep.result import grid_dims
from .basins_figure import SYMBOLS
from .common import parameter_text, pi_ticks, place_panels, root_figure, start_text
from .palette import IMPACTING, colour_of, solution_order


def draw_stability(ds, bs, against: str, ax=None, entropy: bool = False):
    """``bs`` is ``analysis.stability.basin_stability(ds)``; ``against`` a grid axis.
    One panel (``ax``: an Axes or a Figure, see ``plot``); ``entropy``: also the basin
    entropy of the shares H with its 95% bootstrap band, on a right-hand axis of the same
    panel. Returns the matplotlib Figure."""
    dims = grid_dims(ds)
    x = ds[against].values
    T = float(ds.attrs["forcing_period"])
    xs = x / T if against == "t0" else x
    other = [d for d in dims if d != against and bs.sizes.get(d, 1) > 1]
    if other:
        raise ValueError(f"the grid also sweeps {', '.join(other)}; stability curves are "
                         f"drawn against one axis")
    share = bs["share"].squeeze(drop=True)
    lo = bs["ci_low"].squeeze(drop=True)
    hi = bs["ci_high"].squeeze(drop=True)
    fig, (ax,) = place_panels(ax, (1, 1), [(0, 0)], figsize=(9.0, 4.8))
    order = solution_order(ds)
    never = []  # solutions of the catalogue no sample reached, at any grid point
    for g in [str(v) for v in bs["group"].values]:
        if g.startswith("impacting P"):
            continue
        if g in ("unresolved", "diverged"):  # never hidden: they are results too
            colour, style, label = ("0.5", ":", g) if g == "unresolved" else ("k", ":", g)
        elif g == "impacting (all)":
            colour, style, label = IMPACTING, "-", "impacting (all)"
        elif g == "non-impacting (sum)":
            colour, style, label = "k", "--", "non-impacting (sum)"
        else:
            if parse_label(g).kind == "impacting":
                continue
            colour, style, label = colour_of(g, order), "-", latex_of(g)
        s = share.sel(group=g).values
        if label == latex_of(g) and not np.any(s > 0):
            never.append(g)
            continue
        if not np.any(hi.sel(group=g).values > 0):
            continue
        ax.plot(xs, s, style, color=colour, marker="o", ms=3, label=label)
        ax.fill_between(xs, lo.sel(group=g).values, hi.sel(group=g).values, color=colour,
                        alpha=0.18, lw=0)
    ax.set_xlabel(f"${SYMBOLS.get(against, against)}$" + (" / T" if against == "t0" else ""))
    ax.set_ylabel("basin stability")
    ax.set_ylim(-0.02, 1.02)
    if against == "phi":
        pi_ticks(ax.xaxis, float(xs.min()), float(xs.max()))
    t0_text = "" if against == "t0" else f"; {start_text(ds)}"
    swept = set(attribute_list(ds.attrs, "grid_swept")) | {against}
    what = (f"of {ds.attrs.get('bodies')} bodies" if ds.attrs.get("model") == "chain"
            else "pair")
    ax.set_title(f"{ds.attrs.get('model')} {what}, n = {bs.attrs['n']} samples per point, "
                 f"95% Wilson bands{t0_text}\n{parameter_text(ds, exclude=swept)}"
                 + (f"\nnot drawn: {len(never)} catalogue solution"
                    f"{'s' if len(never) > 1 else ''} that no sample reached"
                    if never else ""), fontsize=9)
    handles, labels = ax.get_legend_handles_labels()
    if entropy:
        h_axis = ax.twinx()
        h = bs["entropy"].squeeze(drop=True).values
        line, = h_axis.plot(xs, h, "-.", color="tab:purple", marker="s", ms=3,
                            label="entropy of the shares H (right axis)")
        h_axis.fill_between(xs, bs["entropy_ci_low"].squeeze(drop=True).values,
                            bs["entropy_ci_high"].squeeze(drop=True).values,
                            color="tab:purple", alpha=0.12, lw=0)
        h_axis.set_ylabel("basin entropy of the shares H (nats)", color="tab:purple")
        h_axis.set_ylim(bottom=0)
        handles, labels = handles + [line], labels + [line.get_label()]
    ax.legend(handles, labels, fontsize=8, loc="center left",
              bbox_to_anchor=(1.14 if entropy else 1.01, 0.5))
    return root_figure(fig)
