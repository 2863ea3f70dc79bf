"""Lyapunov exponents with their standard errors.

A grid run: the exponents against the swept parameter (error bars: the segments'
standard error), above the section states (x of each body every forcing period while
averaging, a bifurcation diagram of the same runs). Otherwise one panel: each run's
exponents as points with error bars, the Floquet exponents of catalogue solutions as
crosses beside them.
"""

from __future__ import annotations

import numpy as np

from .common import PARAMETER_TEX, parameter_text, place_panels, root_figure

COLOURS = ("tab:red", "tab:blue", "tab:green", "tab:purple")


def draw_lyapunov(ds, ax=None):
    """Two panels for a grid run (exponents, section states; ``ax``: 2 Axes or a Figure),
    one otherwise; returns the matplotlib Figure."""
    if ds.attrs.get("source") == "grid":
        return _along_parameter(ds, ax)
    return _per_run(ds, ax)


def _title(ds) -> str:
    salt = "" if ds.attrs.get("saltation", 1) else " (WITHOUT saltation)"
    return f"Lyapunov exponents{salt}"


def _along_parameter(ds, ax):
    axis = ds.attrs["axis"]
    x = ds[axis].values
    fig, (top, bottom) = place_panels(ax, (2, 1), [(0, 0), (1, 0)], figsize=(8, 7.5),
                                      sharex=True)
    for k in range(ds.sizes["order"]):
        top.errorbar(x, ds["exponent"].values[:, k], yerr=ds["exponent_stderr"].values[:, k],
                     fmt="o-", ms=3, lw=1, capsize=2, color=COLOURS[k % len(COLOURS)],
                     label=rf"$\lambda_{k + 1}$")
    top.axhline(0.0, color="0.5", lw=0.8)
    top.set_ylabel(r"$\lambda$ (1/time)")
    top.legend(loc="best", fontsize=8)
    names = [str(v) for v in ds["variable"].values]
    sec = ds["section_state"].values  # (run, section, variable)
    for j, name in enumerate(n for n in names if n.startswith("x")):
        col = names.index(name)
        xs = np.repeat(x, sec.shape[1])
        bottom.plot(xs, sec[:, :, col].ravel(), ".", ms=1.5, color=COLOURS[j % len(COLOURS)],
                    alpha=0.6)
        bottom.plot([], [], "s", color=COLOURS[j % len(COLOURS)], label=f"${name}$")
    bottom.set_ylabel("section states (every T)")
    bottom.set_xlabel(f"${PARAMETER_TEX.get(axis, axis)}$")
    bottom.legend(loc="best", fontsize=8)
    root_figure(fig).suptitle(f"{_title(ds)}\n{parameter_text(ds, exclude=(axis,))}",
                              fontsize=9)
    return root_figure(fig)


def _per_run(ds, ax):
    fig, (panel,) = place_panels(ax, (1, 1), [(0, 0)], figsize=(8, 4.5))
    runs = ds.sizes["run"]
    n = ds.sizes["order"]
    for i in range(runs):
        offsets = i + np.linspace(-0.25, 0.25, n)
        panel.errorbar(offsets, ds["exponent"].values[i], yerr=ds["exponent_stderr"].values[i],
                       fmt="o", ms=4, capsize=2, color="k",
                       label="Benettin (saltation)" if i == 0 else None)
        if runs <= 8:
            for k, (o, e) in enumerate(zip(offsets, ds["exponent"].values[i], strict=True)):
                panel.annotate(rf"$\lambda_{k + 1}$ = {e:+.4f}", (o, e), fontsize=7,
                               xytext=(4, 4), textcoords="offset points")
        floquet = ds["floquet_exponent"].values[i]
        if np.all(np.isfinite(floquet)):
            panel.plot(offsets + 0.04, floquet, "x", color="tab:red",
                       label="ln|mu| / qT (Floquet)" if i == 0 else None)
    panel.axhline(0.0, color="0.5", lw=0.8)
    panel.set_xlim(-0.5, runs - 0.5)
    panel.set_xticks(range(runs), [str(s) for s in ds["solution"].values], fontsize=8)
    panel.set_ylabel(r"$\lambda$ (1/time)")
    panel.legend(loc="best", fontsize=8)
    root_figure(fig).suptitle(f"{_title(ds)}\n{parameter_text(ds)}", fontsize=9)
    return root_figure(fig)
