"""Design figure: the (d, phi) plane with the region where only the target survives, the
critical-distance curves, the candidates, the pick and the runners-up; beside it the
basin stability at the pick (and the reference), and the target's share when one
parameter at a time is perturbed."""

from __future__ import annotations

import numpy as np

from ..analysis.labels import latex_of
from ..config.axes import COUPLING_AXES
from ..report.info import design_axes, design_summary
from .common import (
    panel_letter,
    parameter_text,
    phase_text,
    pi_ticks,
    place_panels,
    root_figure,
    start_text,
)
from .dcrit_figure import jumps
from .palette import IMPACTING, colour_of, solution_order

TWO_PI = 2 * np.pi
REGION = "#ffd54f"  # the target-only region: amber, unlike any curve colour
AXIS_TEX = {"d": "d", "phi": r"\varphi", "k_c": "k_c", "c_c": "c_c"}


def _tiled(phi: np.ndarray, values: np.ndarray, lo: float, hi: float, gaps: bool = True):
    """A 2 pi-periodic curve unrolled over [lo, hi], with gaps at its jumps (``gaps``)."""
    xs, ys = [], []
    cut = jumps(values) + 1 if gaps else np.array([], dtype=int)
    x = np.insert(phi, cut, np.nan)
    y = np.insert(values, cut, np.nan)
    for k in range(int(np.floor((lo - phi[-1]) / TWO_PI)), int(np.ceil(hi / TWO_PI)) + 1):
        xs += [x + k * TWO_PI, [np.nan]]
        ys += [y, [np.nan]]
    return np.concatenate(xs), np.concatenate(ys)


def _plane(ax, ds, s: dict, view=None) -> None:
    """The (d, phi) plane over the bounds (``view`` None) or over ``view`` = (phi_lo,
    phi_hi, d_lo, d_hi), a zoom around the pick that also shows the perturbed points."""
    phi = ds["dcrit_phi"].values
    b_phi, b_d = ds.attrs["bounds_phi"], ds.attrs["bounds_d"]
    if view is None:
        pad_phi = max(0.08 * (b_phi[1] - b_phi[0]), 0.05)
        pad_d = max(0.12 * (b_d[1] - b_d[0]), 0.05 * b_d[1])
        view = (b_phi[0] - pad_phi, b_phi[1] + pad_phi, max(b_d[0] - pad_d, 0.0),
                b_d[1] + pad_d)
        zoom = False
    else:
        zoom = True
    x_lo, x_hi, y_lo, y_hi = view
    target = s["target"]
    xs, low = _tiled(phi, ds["region_low"].values, x_lo, x_hi, gaps=False)
    _, high = _tiled(phi, np.minimum(ds["region_high"].values, 1e6), x_lo, x_hi, gaps=False)
    ok = np.isfinite(low) & np.isfinite(high) & (low < high)
    ax.fill_between(xs, np.clip(low, y_lo, y_hi), np.clip(high, y_lo, y_hi), where=ok,
                    color=REGION, alpha=0.45, lw=0,
                    label=f"only {latex_of(target)} survives")
    order = solution_order(ds)
    for i, name in enumerate(str(n) for n in ds["dcrit_name"].values):
        x, y = _tiled(phi, ds["critical_distance"].values[i], x_lo, x_hi)
        ax.plot(x, y, color="k" if name == target else colour_of(name, order),
                lw=2.2 if name == target else 1.1, zorder=2.5 if name == target else 2,
                label=latex_of(name) + (" (target)" if name == target else ""))
    ax.add_patch(_rectangle(b_phi, b_d))
    role = [str(r) for r in ds["role"].values]
    P = {a: ds[f"point_{a}"].values for a in ("d", "phi")}
    sel = [i for i, r in enumerate(role) if r == "screened"]
    score = ds["score"].values[sel]
    dots = ax.scatter(P["phi"][sel], P["d"][sel], c=score, cmap="viridis", s=22,
                      vmin=min(float(score.min(initial=1.0)), 0.9), vmax=1.0, zorder=3,
                      edgecolors="0.2", linewidths=0.4, label="screened")
    if zoom:
        moved = [i for i, r in enumerate(role) if r == "perturbed"]
        ax.plot(P["phi"][moved], P["d"][moved], "+", color="k", ms=8, zorder=4,
                label="perturbed")
    else:
        bar = ax.figure.colorbar(dots, ax=ax, pad=0.01, fraction=0.04)
        bar.set_label(f"screened: score = target share - failed share "
                      f"({ds.attrs['screen_n']} samples)", fontsize=8)
    for k, p in enumerate(s["runners_up"]):
        ax.plot(p["phi"], p["d"], "s", color="#ff7f0e", mec="k", ms=7, zorder=4,
                label="runners-up" if k == 0 else None)
        ax.annotate(str(k + 1), (p["phi"], p["d"]), textcoords="offset points",
                    xytext=(5, 4), fontsize=8, annotation_clip=True)
    if s["reference"]:
        r = s["reference"]
        ax.plot(r["phi"], r["d"], "D", color="w", mec="k", ms=8, zorder=4, label="reference")
    best = s["best"]
    ax.plot(best["phi"], best["d"], "*", color="#d62728", mec="k", ms=16, zorder=5,
            label="pick")
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(y_lo, y_hi)
    pi_ticks(ax.xaxis, x_lo, x_hi, max_ticks=7)
    ax.set_xlabel(r"$\varphi$")
    ax.set_ylabel("$d$")
    if zoom:
        ax.set_title("around the pick (+: perturbed points)", fontsize=9)
        return
    ax.set_title("critical distances; shaded: target alone; dashed: search bounds",
                 fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.13), ncols=3,
              frameon=False)


def _zoom_view(ds, best: dict) -> tuple[float, float, float, float]:
    """A window around the pick: a few perturbation steps, and the region's edges at the
    pick when they are near."""
    m = best["margin"]
    rel = float(ds.attrs["perturbation"]) * int(ds.attrs["perturbation_steps"])
    half_phi = float(np.clip(1.6 * m["phi_to_boundary"], 4 * rel * np.pi, np.pi / 2))
    edge = max(m["d_to_target"], m["d_to_boundary"])
    half_d = float(np.clip(1.4 * edge, 4 * rel * best["d"], 0.5 * best["d"]))
    return (best["phi"] - half_phi, best["phi"] + half_phi, best["d"] - half_d,
            best["d"] + half_d)


def _rectangle(b_phi, b_d):
    from matplotlib.patches import Rectangle

    return Rectangle((b_phi[0], b_d[0]), b_phi[1] - b_phi[0], b_d[1] - b_d[0], fill=False,
                     ls="--", lw=1.0, ec="0.3")


def _bars(ax, s: dict) -> None:
    shown = [("pick", s["best"], "#d62728")]
    if s["reference"]:
        shown.append(("reference", s["reference"], "0.55"))
    names = list(dict.fromkeys([s["target"], "impacting (all)"] + [
        g for _, p, _ in shown for g in p["shares"]
        if g != "non-impacting (sum)" and not g.startswith("impacting P")]))
    names.sort(key=lambda g: (g != s["target"], g == "impacting (all)", g))
    width = 0.8 / len(shown)
    x = np.arange(len(names))
    for k, (what, p, colour) in enumerate(shown):
        share = np.array([p["shares"].get(g, 0.0) for g in names])
        ax.bar(x + (k - (len(shown) - 1) / 2) * width, share, width, color=colour,
               alpha=0.85, label=f"{what}: n = {p['n']}")
    # intervals of the two shares the design is about (95% Wilson)
    for k, (_, p, _) in enumerate(shown):
        for g, key in ((s["target"], "ci95"), ("impacting (all)", "impacting_ci95")):
            if g in names:
                xi = names.index(g) + (k - (len(shown) - 1) / 2) * width
                v = p["share"] if key == "ci95" else p["impacting_share"]
                ax.errorbar(xi, v, yerr=[[v - p[key][0]], [p[key][1] - v]], color="k",
                            capsize=3, lw=1)
                ax.annotate(f"{v:.3f}", (xi, p[key][1]), textcoords="offset points",
                            xytext=(0, 3), ha="center", fontsize=7)
    ax.set_xticks(x, [latex_of(g) if g != "impacting (all)" else "impacting\n(all)"
                      for g in names], fontsize=8, rotation=20)
    for tick, g in zip(ax.get_xticklabels(), names, strict=True):
        tick.set_color(IMPACTING if g.startswith("impacting") else "k")
    ax.set_ylim(0, 1.25)
    ax.set_yticks(np.linspace(0, 1, 6))
    ax.set_ylabel("basin stability")
    ax.set_title("at the pick (95% Wilson intervals)", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", ncols=2, frameon=False)


def _chain_plane(ax, ds, s: dict) -> None:
    """A chain's region map: the plane of its first two design axes (``map_x_axis``,
    ``map_y_axis``; the others at the pick), shaded where only the target survives, grey
    by the number of surviving products elsewhere, with the evaluated points."""
    from matplotlib.colors import ListedColormap

    x_axis, y_axis = str(ds.attrs["map_x_axis"]), str(ds.attrs["map_y_axis"])
    xs, ys = ds["map_x"].values, ds["map_y"].values
    count, target = ds["map_survivors"].values, ds["map_target"].values
    alone = (count == 1) & (target == 1)
    shade = np.where(alone, -1, np.minimum(count, 4)).astype(float)
    cmap = ListedColormap([REGION, "white", "0.88", "0.78", "0.68", "0.58"])
    y_edges = _edges(ys) if y_axis else np.array([0.0, 1.0])
    ax.pcolormesh(_edges(xs), y_edges, shade, cmap=cmap, vmin=-1.5, vmax=4.5,
                  shading="flat")
    role = [str(r) for r in ds["role"].values]
    px = ds[f"point_{x_axis}"].values
    py = ds[f"point_{y_axis}"].values if y_axis else np.full(px.size, 0.5)
    sel = [i for i, r in enumerate(role) if r == "screened"]
    if sel:
        score = ds["score"].values[sel]
        dots = ax.scatter(px[sel], py[sel], c=score, cmap="viridis", s=22, zorder=3,
                          vmin=min(float(score.min(initial=1.0)), 0.9), vmax=1.0,
                          edgecolors="0.2", linewidths=0.4)
        bar = ax.figure.colorbar(dots, ax=ax, pad=0.01, fraction=0.04)
        bar.set_label(f"screened: score ({ds.attrs['screen_n']} samples)", fontsize=8)
    for k, i in enumerate(i for i, r in enumerate(role) if r == "runner-up"):
        ax.plot(px[i], py[i], "s", color="#ff7f0e", mec="k", ms=7, zorder=4,
                label="runners-up" if k == 0 else None)
    moved = [i for i, r in enumerate(role) if r == "perturbed"]
    ax.plot(px[moved], py[moved], "+", color="k", ms=8, zorder=4, label="perturbed")
    if "reference" in role:
        i = role.index("reference")
        ax.plot(px[i], py[i], "D", color="w", mec="k", ms=8, zorder=4, label="reference")
    i = role.index("best")
    ax.plot(px[i], py[i], "*", color="#d62728", mec="k", ms=16, zorder=5, label="pick")
    ax.fill_between([], [], color=REGION, label=f"only {latex_of(s['target'])} survives")
    ax.set_xlabel(x_axis)
    if x_axis.startswith("phi."):
        pi_ticks(ax.xaxis, *ax.get_xlim(), max_ticks=7)
    if y_axis:
        ax.set_ylabel(y_axis)
        if y_axis.startswith("phi."):
            pi_ticks(ax.yaxis, *ax.get_ylim(), max_ticks=7)
    else:
        ax.set_yticks([])
    others = [a for a in design_axes(ds) if a not in (x_axis, y_axis)]
    ax.set_title("surviving products (white: none; light grey to dark: 1, 2, 3, 4+)"
                 + (f"; {', '.join(others)} at the pick" if others else ""), fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.13), ncols=3,
              frameon=False)


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around ``centres`` (ascending; one centre: a unit cell)."""
    if centres.size == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])


def _robustness(ax, s: dict, relative: float, axes=COUPLING_AXES) -> None:
    best = s["best"]
    for j, axis in enumerate(axes):
        rows = sorted([p for p in s["robustness"] if p["parameter"] == axis],
                      key=lambda p: p["step"])
        rows = rows[: len(rows) // 2] + [{**best, "step": 0}] + rows[len(rows) // 2:] \
            if rows else []
        if not rows:
            continue
        steps = np.array([p["step"] for p in rows]) + (j - 1.5) * 0.06
        share = np.array([p["share"] for p in rows])
        err = np.array([[p["share"] - p["ci95"][0], p["ci95"][1] - p["share"]] for p in rows])
        line = ax.errorbar(steps, share, yerr=err.T, marker="o", ms=4, capsize=2, lw=1,
                           label=f"${AXIS_TEX[axis]}$" if axis in AXIS_TEX else axis)
        gone = [k for k, p in enumerate(rows) if p["target_exists"] is False]
        ax.plot(steps[gone], share[gone], "x", color=line[0].get_color(), ms=10, mew=2)
    low = min([p["ci95"][0] for p in s["robustness"]] + [best["ci95"][0]])
    ax.set_ylim(max(0.0, min(low - 0.03, 0.9)), 1.02)
    unit = f"{100 * relative:g}% of the value ($\\varphi$: of $\\pi$)"
    ax.set_xlabel(f"perturbation steps ({unit})", fontsize=8)
    ax.set_ylabel("target's basin stability")
    ax.set_title("one parameter at a time (x: target destroyed)", fontsize=9)
    ax.legend(fontsize=7, loc="best")


def draw_design(ds, ax=None):
    """The four panels of a design result: the (d, phi) plane, a zoom around the pick,
    the basin stability at the pick, the perturbations (``ax``: 4 Axes in that order, or
    a Figure; see ``plot``); returns the matplotlib Figure."""
    s = design_summary(ds)
    if ds.attrs.get("model") == "chain":
        return _draw_chain_design(ds, s, ax)
    fig, axs = place_panels(ax, (1, 4), [(0, k) for k in range(4)], figsize=(20.0, 5.8),
                            gridspec_kw={"width_ratios": [1.5, 0.9, 1.0, 1.0]})
    _plane(axs[0], ds, s)
    _plane(axs[1], ds, s, _zoom_view(ds, s["best"]))
    _bars(axs[2], s)
    _robustness(axs[3], s, float(ds.attrs["perturbation"]))
    b = s["best"]
    for k, ax in enumerate(axs):
        panel_letter(ax, k)
    fig.suptitle(
        f"{ds.attrs.get('model')} pair: design for {latex_of(s['target'])}; pick d = "
        f"{b['d']:.4g}, $\\varphi = {phase_text(b['phi'])}$, $k_c$ = {b['k_c']:.4g}, $c_c$ = "
        f"{b['c_c']:.4g}; samples in {ds.attrs.get('sample_box', '?')}, {start_text(ds)}\n"
        f"{parameter_text(ds, exclude=('d', 'phi', 'k_c', 'c_c', 'law'))}", fontsize=9)
    return root_figure(fig)


def _draw_chain_design(ds, s: dict, ax=None):
    """A chain's design: its region map, the basin stability at the pick, the
    perturbations (``ax``: 3 Axes or a Figure)."""
    fig, axs = place_panels(ax, (1, 3), [(0, k) for k in range(3)], figsize=(17.0, 5.8),
                            gridspec_kw={"width_ratios": [1.4, 1.0, 1.0]})
    _chain_plane(axs[0], ds, s)
    _bars(axs[1], s)
    axes = design_axes(ds)
    _robustness(axs[2], s, float(ds.attrs["perturbation"]), axes)
    for k, a in enumerate(axs):
        panel_letter(a, k)
    b = s["best"]
    pick = ", ".join(f"{a} = {b[a]:.4g}" for a in axes)
    fig.suptitle(f"chain of {ds.attrs.get('bodies', '?')} bodies: design for "
                 f"{latex_of(s['target'])}; pick {pick}; samples in "
                 f"{ds.attrs.get('sample_box', '?')}, {start_text(ds)}", fontsize=9)
    return root_figure(fig)
