"""Time series, phase portraits and stroboscopic points of a trajectory result."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import pyplot

BODY_COLOURS = ("#1f77b4", "#d62728")


def plot_trajectory(ds, out: str | Path, last_periods: int | None = None) -> Path:
    """Draw a trajectory result to ``out`` (PNG/PDF/SVG by suffix).

    Panels: displacements against t/T with the section points; one phase portrait per
    body (transient faint, last ``last_periods`` periods strong, section points as dots);
    for a pair, the contact function x1 - x2 - d against t/T.
    """
    plt = pyplot()
    names = [str(v) for v in ds["variable"].values]
    T = float(ds.attrs["forcing_period"])
    t = ds["time"].values / T
    y = ds["state"].values
    st = ds["section_time"].values / T
    sy = ds["section_state"].values
    pair = len(names) == 4
    bodies = [(0, 1, "x_1", "\\dot x_1"), (2, 3, "x_2", "\\dot x_2")] if pair else [
        (0, 1, "x", "\\dot x")]
    n_sections = np.isfinite(st).sum()
    keep = last_periods if last_periods else max(1, min(20, n_sections // 4))
    t_cut = st[np.isfinite(st)][-1] - keep if n_sections else t[-1]
    steady = t >= t_cut

    ncols = 3 if pair else 2
    fig, axes = plt.subplots(2 if pair else 1, ncols, figsize=(4.2 * ncols, 7 if pair else 3.6),
                             squeeze=False, constrained_layout=True)
    ax = axes[0, 0]
    for k, (ix, _, xl, _) in enumerate(bodies):
        ax.plot(t, y[:, ix], lw=0.7, color=BODY_COLOURS[k], label=f"${xl}$")
        ax.plot(st, sy[:, ix], ".", ms=3, color="k")
    ax.set_xlabel("$t/T$")
    ax.set_ylabel("displacement")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("time series (dots: $t = nT$)", fontsize=9)
    for k, (ix, iv, xl, vl) in enumerate(bodies):
        ax = axes[0, 1 + k]
        ax.plot(y[~steady, ix], y[~steady, iv], lw=0.4, color="0.75")
        ax.plot(y[steady, ix], y[steady, iv], lw=1.0, color=BODY_COLOURS[k])
        tail = st >= t_cut
        ax.plot(sy[tail, ix], sy[tail, iv], "o", ms=5, mfc="k", mec="w", zorder=3,
                label="Poincaré points")
        ax.set_xlabel(f"${xl}$")
        ax.set_ylabel(f"${vl}$")
        ax.set_title(f"phase portrait, body {k + 1}" if pair else "phase portrait", fontsize=9)
        ax.legend(loc="upper right", fontsize=7)
    if pair:
        d = _parameter(ds, "d")
        ax = axes[1, 0]
        ax.plot(t, y[:, 0] - y[:, 2], lw=0.7, color="k")
        if d is not None:
            ax.axhline(d, color="tab:orange", lw=1, ls="--", label=f"$d = {d:g}$")
            ax.fill_between(t, d, np.maximum(y[:, 0] - y[:, 2], d), color="tab:orange",
                            alpha=0.4, label="contact")
            ax.legend(loc="lower right", fontsize=8)
        ax.set_xlabel("$t/T$")
        ax.set_ylabel("$x_1 - x_2$")
        ax.set_title("relative displacement", fontsize=9)
        ax = axes[1, 1]
        ax.plot(y[:, 0], y[:, 2], lw=0.4, color="0.6")
        ax.plot(sy[:, 0], sy[:, 2], ".", ms=3, color="k")
        ax.set_xlabel("$x_1$")
        ax.set_ylabel("$x_2$")
        ax.set_title("configuration plane", fontsize=9)
        axes[1, 2].axis("off")
        axes[1, 2].text(0.0, 1.0, _summary(ds), va="top", family="monospace", fontsize=8,
                        transform=axes[1, 2].transAxes)
    fig.suptitle(_title(ds), fontsize=10)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=130)
    plt.close(fig)
    return out


def _parameter(ds, name: str) -> float | None:
    for item in str(ds.attrs.get("parameters", "")).split(", "):
        key, _, value = item.partition("=")
        if key == name:
            try:
                return float(value)
            except ValueError:
                return None
    return None


def _title(ds) -> str:
    model = ds.attrs.get("model", "")
    bodies = int(ds.attrs.get("bodies", 1))
    params = str(ds.attrs.get("parameters", "")).replace("law=paper", "").strip(", ")
    t0 = float(ds.attrs.get("t0", 0.0)) / float(ds.attrs["forcing_period"])
    return (f"{model} {'pair' if bodies == 2 else 'body'}: {params}; start at $t_0 = "
            f"{t0:.4g}\\,T$")


def _summary(ds) -> str:
    a = ds.attrs
    lines = [
        f"outcome      {a.get('outcome')}",
        f"period       {a.get('period')} T",
        f"periods used {a.get('periods_used')}",
        f"contacts/orbit {a.get('contacts_on_orbit')}",
        f"max penetr.  {float(a.get('max_penetration', np.nan)):.4g}",
        f"method       {a.get('integrator_resolved_method')}",
        f"wall         {float(a.get('wall_s', np.nan)):.3f} s",
    ]
    return "\n".join(lines)
