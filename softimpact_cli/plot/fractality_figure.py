"""A fractality result: per plane, S_b and S_bb against the box size (with ln 2), the
uncertainty exponent's log-log fit, and the boundary map of the Wada test."""

from __future__ import annotations

import math

import numpy as np

from ..analysis.attributes import attribute_list
from .basins_figure import AXIS_SYMBOLS
from .common import place_panels

WHERE = (("d", "d"), ("phi", r"\varphi"), ("k_c", "k_c"), ("c_c", "c_c"))


def _where(ds, i: int) -> str:
    if int(ds.attrs.get("bodies", 2)) == 1:
        return "one body"
    return ", ".join(f"${tex} = {float(ds[a].values[i]):.4g}$" for a, tex in WHERE
                     if a in ds.coords)


def _entropy(ax, ds, i: int) -> None:
    n = ds["box_size"].values
    ax.plot(n, ds["S_b"].values[i], "o-", ms=3, label=r"$S_b$")
    ax.plot(n, ds["S_bb"].values[i], "s-", ms=3, label=r"$S_{bb}$")
    ax.axhline(math.log(2), color="k", ls="--", lw=0.8, label=r"$\ln 2$")
    ax.set_xlabel("box size n (cells)")
    ax.set_ylabel("entropy (nat)")
    ax.set_ylim(0, max(math.log(max(2, int(ds["n_basins"].values[i]))) * 1.05, 0.75))
    ax.legend(fontsize=7, loc="lower right")


def _uncertainty(ax, ds, i: int) -> None:
    r = ds["radius"].values.astype(float)
    f = ds["uncertain_fraction"].values[i]
    used = ds["in_fit"].values[i]
    ax.loglog(r[used], f[used], "o", ms=4, label="f(r)")
    alpha = float(ds["alpha"].values[i])
    if math.isfinite(alpha):
        rr = np.geomspace(r[used].min(), r[used].max(), 20)
        ax.loglog(rr, np.exp(float(ds["alpha_intercept"].values[i])) * rr**alpha, "-",
                  color="C3", label=(rf"$\alpha = {alpha:.3f}$ "
                                     rf"[{float(ds['alpha_ci_low'].values[i]):.3f}, "
                                     rf"{float(ds['alpha_ci_high'].values[i]):.3f}]"
                                     f"\n$D = {2 - alpha:.3f}$"))
    ax.set_xlabel(r"radius $\varepsilon$ (cells)")
    ax.set_ylabel("uncertain share f")
    ax.legend(fontsize=7, loc="lower right")


def _wada(ax, ds, i: int) -> None:
    from matplotlib.colors import ListedColormap

    k = max(int(ds["n_basins"].values[i]), 1)
    grid = ds["wada_map"].values[i].astype(float)
    grid[grid == 0] = np.nan
    cmap = ListedColormap(["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                           "#8c564b"][: max(1, k - 1)] + (["#000000"] if k >= 2 else [])
                          ).with_extremes(bad="#eeeeee")  # cells inside a basin
    vertical, horizontal = ds["row"].values, ds["col"].values
    a_v, a_h = attribute_list(ds.attrs, "plane_axes", ("y", "x"))
    if attribute_list(ds.attrs, "ic_dims")[:1] == [a_v]:  # the plane's first axis
        grid, vertical, horizontal, a_v, a_h = grid.T, horizontal, vertical, a_h, a_v
    im = ax.imshow(grid, origin="lower", aspect="auto", cmap=cmap, vmin=0.5,
                   vmax=max(k, 1) + 0.5 if k > 1 else 1.5, interpolation="nearest",
                   extent=(horizontal[0], horizontal[-1], vertical[0], vertical[-1]))
    ax.set_xlabel(f"${AXIS_SYMBOLS.get(a_h, a_h)}$")
    ax.set_ylabel(f"${AXIS_SYMBOLS.get(a_v, a_v)}$")
    verdict = str(ds["verdict"].values[i])
    if verdict != "n/a":
        frac = float(ds["wada_fraction"].values[i][-1])
        verdict += f": {frac:.2f} of the boundary near all {k}"
    ax.set_title(f"boundary cells (Wada {verdict})", fontsize=8)
    cb = ax.figure.colorbar(im, ax=ax, ticks=range(1, k + 1), shrink=0.8)
    cb.set_label(f"merged boundaries within r = {ds.attrs.get('wada_max_radius')}",
                 fontsize=7)


def draw_fractality(ds, max_panels: int = 8, ax=None):
    """Rows of three panels (entropy, uncertainty fit, boundary map), one row per plane
    (at most ``max_panels``); ``ax``: see ``plot``. Returns the Figure."""
    n = min(int(ds.sizes["point"]), int(max_panels))
    order = [(r, c) for r in range(n) for c in range(3)]
    fig, axes = place_panels(ax, (n, 3), order, figsize=(13.0, 3.6 * n))
    for i in range(n):
        _entropy(axes[3 * i], ds, i)
        _uncertainty(axes[3 * i + 1], ds, i)
        _wada(axes[3 * i + 2], ds, i)
        axes[3 * i].set_title(_where(ds, i), fontsize=9, loc="left")
    rows, cols = attribute_list(ds.attrs, "plane_shape", ("?", "?"))
    title = (f"{ds.attrs.get('model', '')}: basin entropy, uncertainty exponent and Wada "
             f"test on {rows} x {cols} planes")
    if ds.sizes["point"] > n:
        title += f" (first {n} of {ds.sizes['point']})"
    fig.suptitle(title, fontsize=10)
    return fig
