"""Time series, phase portraits and stroboscopic points of a trajectory result."""

from __future__ import annotations

import numpy as np

from .common import panel_letter, parameter_text, place_panels, root_figure, start_text

BODY_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                "#e377c2", "#17becf")  # body k; the first two are the pair's


def trajectory_panels(ds) -> int:
    """How many panels the figure of trajectory result ``ds`` has: 2 (one body), 6 (a
    pair), n + 3 (a chain of n bodies: time series, n phase portraits, the stops'
    compressions, a summary)."""
    n = ds.sizes["variable"] // 2
    return n + 3 if "stop_max_penetration" in ds else (6 if n == 2 else 2)


def draw_trajectory(ds, last_periods: int | None = None, ax=None):
    """The matplotlib Figure of a trajectory result.

    Panels: displacements against t/T with the section points; one phase portrait per
    body (transient faint, last ``last_periods`` periods strong, section points as dots);
    for a pair, the contact function x1 - x2 - d against t/T, the configuration plane
    and a text summary; for a chain, every stop's compression against t/T and a text
    summary with each stop's maximum. ``ax``: :func:`trajectory_panels` Axes (2 for one
    body, 6 for a pair, n + 3 for a chain of n bodies) in that order, or a Figure (see
    ``plot``).
    """
    names = [str(v) for v in ds["variable"].values]
    T = float(ds.attrs["forcing_period"])
    t = ds["time"].values / T
    y = ds["state"].values
    st = ds["section_time"].values / T
    sy = ds["section_state"].values
    chain = "stop_max_penetration" in ds
    pair = len(names) == 4 and not chain
    n_bodies = len(names) // 2
    if n_bodies == 1 and not chain:
        bodies = [(0, 1, "x", "\\dot x")]
    else:
        bodies = [(2 * k, 2 * k + 1, f"x_{k + 1}", f"\\dot x_{k + 1}") for k in range(n_bodies)]
    n_sections = np.isfinite(st).sum()
    keep = last_periods if last_periods else max(1, min(20, n_sections // 4))
    t_cut = st[np.isfinite(st)][-1] - keep if n_sections else t[-1]
    steady = t >= t_cut

    n_panels = trajectory_panels(ds)
    ncols = 3 if pair or chain else 2
    shape = (-(-n_panels // ncols), ncols)
    fig, axes = place_panels(ax, shape, [divmod(k, ncols) for k in range(n_panels)],
                             figsize=(4.2 * ncols, 3.6 * shape[0] if shape[0] > 1 else 3.8))
    ax = axes[0]
    for k, (ix, _, xl, _) in enumerate(bodies):
        ax.plot(t, y[:, ix], lw=0.7, color=BODY_COLOURS[k % len(BODY_COLOURS)],
                label=f"${xl}$")
        ax.plot(st, sy[:, ix], ".", ms=3, color="k")
    ax.set_xlabel("$t/T$")
    ax.set_ylabel("displacement")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("time series (dots: $t = t_0 + nT$)", fontsize=9)
    for k, (ix, iv, xl, vl) in enumerate(bodies):
        ax = axes[1 + k]
        ax.plot(y[~steady, ix], y[~steady, iv], lw=0.4, color="0.75")
        ax.plot(y[steady, ix], y[steady, iv], lw=1.0, color=BODY_COLOURS[k % len(BODY_COLOURS)])
        tail = st >= t_cut
        ax.plot(sy[tail, ix], sy[tail, iv], "o", ms=5, mfc="k", mec="w", zorder=3,
                label="Poincaré points")
        if "nonperiodic_cloud" in ds:  # the second stage's section points of its attractor
            cloud = ds["nonperiodic_cloud"].values[0]
            ax.plot(cloud[:, ix], cloud[:, iv], ".", ms=2, color="tab:purple", zorder=4,
                    label=f"{ds.attrs.get('label', 'attractor')} (section)")
        ax.set_xlabel(f"${xl}$")
        ax.set_ylabel(f"${vl}$")
        ax.set_title(f"phase portrait, body {k + 1}" if len(bodies) > 1 else "phase portrait",
                     fontsize=9)
        ax.legend(loc="upper right", fontsize=7)
    if pair:
        d = _parameter(ds, "d")
        ax = axes[ncols]
        ax.plot(t, y[:, 0] - y[:, 2], lw=0.7, color="k")
        if d is not None:
            ax.axhline(d, color="tab:orange", lw=1, ls="--", label=f"$d = {d:g}$")
            ax.fill_between(t, d, np.maximum(y[:, 0] - y[:, 2], d), color="tab:orange",
                            alpha=0.4, label="contact")
            ax.legend(loc="lower right", fontsize=8)
        ax.set_xlabel("$t/T$")
        ax.set_ylabel("$x_1 - x_2$")
        ax.set_title("relative displacement", fontsize=9)
        ax = axes[ncols + 1]
        ax.plot(y[:, 0], y[:, 2], lw=0.4, color="0.6")
        ax.plot(sy[:, 0], sy[:, 2], ".", ms=3, color="k")
        ax.set_xlabel("$x_1$")
        ax.set_ylabel("$x_2$")
        ax.set_title("configuration plane", fontsize=9)
        axes[ncols + 2].axis("off")
        axes[ncols + 2].text(0.0, 1.0, _summary(ds), va="top", family="monospace",
                             fontsize=8, transform=axes[ncols + 2].transAxes)
    if chain:
        _draw_stops(axes[1 + n_bodies], ds, t, y)
        axes[2 + n_bodies].axis("off")
        axes[2 + n_bodies].text(0.0, 1.0, _summary(ds), va="top", family="monospace",
                                fontsize=8, transform=axes[2 + n_bodies].transAxes)
    for k, ax in enumerate(a for a in axes if a.axison):
        panel_letter(ax, k)
    fig.suptitle(_title(ds), fontsize=10)
    return root_figure(fig)


def _draw_stops(ax, ds, t, y) -> None:
    """Every stop's compression against t/T (> 0: in contact), from the stops' table of a
    chain's result (``stop_body``, ``stop_other``, ``stop_sign``, ``stop_offset``)."""
    for k, s in enumerate(ds["stop"].values):
        i, j = int(ds["stop_body"].values[k]), int(ds["stop_other"].values[k])
        other = y[:, 2 * (j - 1)] if j > 0 else 0.0
        delta = ds["stop_sign"].values[k] * (y[:, 2 * (i - 1)] - other) \
            - ds["stop_offset"].values[k]
        ax.plot(t, delta, lw=0.7, label=f"stop {int(s)} ({ds['stop_between'].values[k]})")
    ax.axhline(0.0, color="tab:orange", lw=1, ls="--")
    ax.set_xlabel("$t/T$")
    ax.set_ylabel("compression (> 0: contact)")
    ax.set_title("stops", fontsize=9)
    ax.legend(loc="lower right", fontsize=7)


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
    what = f"{bodies} bod{'y' if bodies == 1 else 'ies'}" if "stop_max_penetration" in ds else (
        "pair" if bodies == 2 else "body")
    return (f"{model} {what}: {parameter_text(ds)}; start at "
            f"{start_text(ds)}\n{outcome_text(ds)}")


def outcome_text(ds) -> str:
    """What the classification found: the attractor's name and Lyapunov exponents
    (1/time) for a chaotic or quasi-periodic one, the period of an orbit, else the
    outcome."""
    a = ds.attrs
    if "nonperiodic_exponents" in ds:
        lam = ", ".join(f"{v:+.4f}" for v in ds["nonperiodic_exponents"].values[0])
        return f"{a.get('label', a.get('outcome'))}: Lyapunov exponents {lam} /time"
    if a.get("outcome") == "converged":
        return f"converged: period {a.get('period')} T"
    return str(a.get("outcome", ""))


def _summary(ds) -> str:
    a = ds.attrs
    lines = [
        f"outcome      {a.get('label', a.get('outcome'))}",
        f"period       {a.get('period')} T",
        f"periods used {a.get('periods_used')}",
        f"contacts/orbit {a.get('contacts_on_orbit')}",
        _contact_line(ds),
        f"method       {a.get('integrator_resolved_method')}",
        f"wall         {float(a.get('wall_s', np.nan)):.3f} s",
    ]
    return "\n".join(lines)


def _contact_line(ds) -> str:
    if "stop_max_penetration" in ds:  # a chain: each stop's max compression
        return "max compression per stop\n" + "\n".join(
            f"  stop {int(s)}: {v:.4g}" for s, v in zip(ds["stop"].values,
                                                     ds["stop_max_penetration"].values,
                                                     strict=True))
    return _pair_contact_line(ds)


def _pair_contact_line(ds) -> str:
    """How close the bodies come on the final orbit: the penetration x1 - x2 - d of an
    impacting orbit, the clearance d - max(x1 - x2) (> 0: never met) of another."""
    g = float(ds.attrs.get("max_penetration", np.nan))
    if not np.isfinite(g):
        return "contact      none measured"
    if int(ds.attrs.get("impacting", 0)) or g >= 0:
        return f"max penetration\n  max(x1 - x2) - d = {g:.4g}"
    return f"min clearance (no contact)\n  d - max(x1 - x2) = {-g:.4g}"
