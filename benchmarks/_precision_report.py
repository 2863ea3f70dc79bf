"""The work-precision benchmark's report: a markdown table and a log-log figure.

Measures nothing: takes what ``bench_precision.py`` measured.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

TARGET_AGREEMENT = 0.995  # the basin-label agreement the report names a best setting for
STYLE = {  # family -> (colour, marker, line style, offset of the point labels in pt)
    "RK4, switches located": ("#1f77b4", "o", "-", (4, 3)),
    "RK4 plain (study's scheme)": ("#7f7f7f", "s", "--", (-6, -10)),  # below: it may
    "dopri5": ("#d62728", "^", "-", (4, 3)),                         # coincide with RK4
    "rodas4": ("#2ca02c", "D", "-", (4, 3)),
}


def short(label: str) -> str:
    """'T/1440' -> '1440', '1e-08' -> '1e-8': point annotations in the figure."""
    if label.startswith("T/"):
        return label[2:]
    mantissa, _, exponent = label.partition("e")
    return f"{mantissa}e{int(exponent)}" if exponent else label


def best_for_agreement(rows: list[dict], target: float = TARGET_AGREEMENT) -> dict | None:
    """The fastest basin setting whose labels agree with the reference on >= target."""
    ok = [r for r in rows if 1.0 - r["error"] >= target]
    return min(ok, key=lambda r: r["wall"]) if ok else None


def _trajectory_table(trajectories: dict) -> list[str]:
    cases = list(trajectories.values())
    head = "| method | setting | " + " | ".join(
        f"{c.key}: error | {c.key}: wall (ms) | {c.key}: RHS evals" for c, _ in cases) + " |"
    lines = [head, "|---|---|" + "---:|---:|---:|" * len(cases)]
    first = cases[0][1]["rows"]
    for i, row in enumerate(first):
        cells = []
        for _, res in cases:
            r = res["rows"][i]
            err = f"{r['error']:.1e}" if np.isfinite(r["error"]) else f"failed ({r['status']})"
            cells.append(f"{err} | {1e3 * r['wall']:.2f} | {r['rhs']}")
        lines.append(f"| {row['family']} | {row['label']} | " + " | ".join(cells) + " |")
    return lines


def _basin_table(basin: dict) -> list[str]:
    lines = ["| method | setting | labels differing | agreement | wall (2 workers) | ICs/s "
             "| unresolved | main differences (reference -> this) |",
             "|---|---|---:|---:|---:|---:|---:|---|"]
    for r in basin["rows"]:
        lines.append(f"| {r['family']} | {r['label']} | {r['differ']} / {basin['n']} | "
                     f"{100 * (1 - r['error']):.2f} % | {r['wall']:.1f} s | {r['rate']:.0f} | "
                     f"{r['unresolved']} | {r['top'] or '-'} |")
    ref = basin["reference"]
    lines.append(f"| reference: dopri5 | 1e-11, conv. 1e-9 | - | - | {ref['wall']:.1f} s | "
                 f"{basin['n'] / ref['wall']:.0f} | "
                 f"{int(np.sum(ref['labels'] == 'unresolved'))} | "
                 f"{'cached' if ref['cached'] else 'computed in this run'} |")
    return lines


def write_markdown(path: Path, meta: dict, trajectories: dict, basin: dict | None) -> None:
    md = ["# Work-precision benchmark", "",
          f"Command: `.venv/bin/python {meta['command']}` (niceness {meta['nice']}; total "
          f"{meta['total']})",
          "", f"Code: {meta['code']}. Machine: {meta['machine']}. Date: {meta['date']}. "
          "Load average (1, 5, 15 "
          f"min) at start {meta['load_start']}, at end {meta['load_end']}: the machine is "
          "shared, so timings are indicative.", "",
          "Settings: RK4 at the fixed step T/n, with switch location and with the study's plain "
          "scheme (`locate_switches = false`); dopri5 and rodas4 with atol = rtol / 100. "
          "Everything else at the defaults (`IntegratorSettings()`: "
          f"{meta['defaults']}). numba compilation excluded (one untimed run of every "
          "setting first).", "",
          "## Trajectories: error of the stroboscopic points vs wall time", ""]
    for case, res in trajectories.values():
        floor = (f"; the reference differs from RK4 at T/46080 with location by "
                 f"{res['floor']:.1e} (errors below that are not resolved)"
                 if np.isfinite(res["floor"]) else "")
        md.append(f"- {case.title}: state {list(case.state)}, {res['periods']} forcing "
                  f"periods, {res['contacts']} contacts{floor}; load after {res['load']}.")
    md += ["", "Error: max |difference| over the section points at t = nT, n = 0 ... periods, "
           "and over all state variables, to dopri5 at rtol 1e-13, atol 1e-15. Wall: the "
           "best of several single-process runs of one `record_trajectory` call (at least 3 "
           "and 0.3 s).", "", *_trajectory_table(trajectories), ""]
    if basin is not None:
        n, side = basin["n"], basin["resolution"]
        best = best_for_agreement(basin["rows"])
        ref = basin["reference"]
        md += ["## Basin (figure 6(d)): label disagreement vs wall time", "",
               f"Duffing pair, phi = 0, d = 6, k_c = 8, c_c = 10, {side} x {side} = {n} "
               "initial conditions on (x1, x2) in [-12, 12]^2, v1 = v2 = 0, t0 = 0, labelled "
               f"as a sweep labels them (`run_chunk`, catalogue {', '.join(basin['catalogue'])}"
               "), on a pool of 2 processes. Reference: dopri5 rtol 1e-11, atol 1e-13, "
               "convergence_tol 1e-9, max_periods 6000, no capture near known attractors "
               "(the settings under test capture, as a sweep does by default), cached in "
               f"`{Path(ref['path']).name}`. "
               "Reference shares: " + ", ".join(f"{k} {v}" for k, v in
                                                basin["reference_shares"].items()) + ".", "",
               *_basin_table(basin), ""]
        if best is None:
            md.append(f"No setting reaches {100 * TARGET_AGREEMENT:.1f} % agreement.")
        else:
            agree = 100 * (1 - best["error"])
            md.append(f"**Fastest setting with >= {100 * TARGET_AGREEMENT:.1f} % label "
                      f"agreement: {best['family']} {best['label']}** ({agree:.2f} %, "
                      f"{best['wall']:.1f} s, {best['rate']:.0f} ICs/s).")
        md.append("")
    md += [f"![work-precision]({path.stem}.png)", ""]
    path.write_text("\n".join(md))


def _lines(ax, rows: list[dict], y_of, annotate: bool = True) -> None:
    for family, (colour, marker, style, offset) in STYLE.items():
        pts = [(r["wall"], y_of(r), r["label"]) for r in rows if r["family"] == family]
        if not pts:
            continue
        x, y, labels = zip(*pts, strict=True)
        ax.plot(x, y, color=colour, marker=marker, linestyle=style, markersize=5,
                linewidth=1.3, label=family)
        if annotate:
            for xi, yi, lab in pts:
                ax.annotate(short(lab), (xi, yi), textcoords="offset points", xytext=offset,
                            fontsize=6.5, color=colour)


def plot(path: Path, trajectories: dict, basin: dict | None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FuncFormatter, NullFormatter

    panels = len(trajectories) + (basin is not None)
    cols = 2
    rows_n = -(-panels // cols)
    fig, axes = plt.subplots(rows_n, cols, figsize=(12, 5.2 * rows_n), squeeze=False)
    flat = axes.ravel()
    for ax, (case, res) in zip(flat, trajectories.values(), strict=False):
        _lines(ax, res["rows"], lambda r: r["error"])
        if np.isfinite(res["floor"]):
            ax.axhline(res["floor"], color="k", linestyle=":", linewidth=0.9)
            ax.annotate("reference vs RK4 T/46080", (0.01, res["floor"]),
                        xycoords=("axes fraction", "data"), xytext=(0, -3),
                        textcoords="offset points", ha="left", va="top", fontsize=7)
        same = " (plain scheme = located: nothing to locate)" if res["contacts"] == 0 else ""
        ax.set(xscale="log", yscale="log", xlabel="wall time of one run (s)",
               ylabel="max error of the section points",
               title=f"{case.title}\n{res['periods']} periods, {res['contacts']} contacts{same}")
    if basin is not None:
        ax = flat[len(trajectories)]
        n = basin["n"]
        zero = 50.0 / n  # a share of 0 drawn at half of one label, in %
        _lines(ax, basin["rows"], lambda r: max(100.0 * r["error"], zero))
        ax.axhline(100 * (1 - TARGET_AGREEMENT), color="k", linestyle=":", linewidth=0.9)
        ax.annotate(f"{100 * TARGET_AGREEMENT:.1f} % agreement", (1.0, 100 * (1 -
                    TARGET_AGREEMENT)), xycoords=("axes fraction", "data"), ha="right",
                    va="bottom", fontsize=7)
        ax.axhline(zero, color="0.6", linestyle="-", linewidth=0.6)
        ax.annotate("no label differs", (0.01, zero), xycoords=("axes fraction", "data"),
                    xytext=(0, -4), textcoords="offset points", ha="left", va="top",
                    fontsize=7, color="0.4")
        top = max([100.0 * r["error"] for r in basin["rows"]] + [1.0])
        ax.set_ylim(zero / 4, top * 3)
        side = basin["resolution"]
        ax.set(xscale="log", yscale="log", xlabel="wall time of the basin, 2 workers (s)",
               ylabel="labels differing from the reference",
               title=f"(c) figure 6(d) basin, {side} x {side}\nlabel disagreement")
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g} %"))
        ax.yaxis.set_minor_formatter(NullFormatter())
    for ax in flat[:panels]:
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="major", alpha=0.3)
        ax.grid(True, which="minor", alpha=0.1)
    for ax in flat[panels:]:
        ax.set_visible(False)
    handles, labels = flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), frameon=False,
               fontsize=9, title="RK4: steps per period; dopri5, rodas4: rtol (atol = rtol/100)",
               title_fontsize=8)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(path, dpi=130)
    plt.close(fig)


def write_report(out: Path, meta: dict, trajectories: dict, basin: dict | None
                 ) -> tuple[Path, Path]:
    """Write ``out``.md and ``out``.png; return their paths."""
    out.parent.mkdir(parents=True, exist_ok=True)
    md, png = out.with_suffix(".md"), out.with_suffix(".png")
    write_markdown(md, meta, trajectories, basin)
    plot(png, trajectories, basin)
    return md, png
