"""``softimpact info`` as readable text: what applies to the result's kind, as tables.

Works on the dict of :func:`softimpact_cli.report.info.describe` (or ``incomplete_summary``)
and the dataset; never prints a Python repr.
"""

from __future__ import annotations

import numpy as np

from ..analysis.attributes import attribute_list
from ..config.axes import COUPLING_AXES, every_axis
from .info import format_catalogue
from .nonperiodic import nonperiodic_lines
from .rigid import per_period_text
from .verification import verification_lines

# parameters a kind varies or does not use, left out of its "parameters" line
NOT_FIXED = {
    "bifurcation": ("d",),
    "dcrit": COUPLING_AXES,
    "catalogue": ("d", "k_c", "c_c"),
    "design": COUPLING_AXES,
}
SHOWN_ELSEWHERE = {"scene", "points", "stability", "labels", "attractors", "counts",
                   "combinations", "branches", "d_crit", "orbit", "variables", "target",
                   "best", "runners_up", "reference", "robustness", "verification", "tipping",
                   "fractality", "spectra", "fatal_shock", "continuation", "nonperiodic",
                   "status_unresolved"}


def text(value) -> str:
    """One value as text: numbers to 6 significant digits, mappings as 'key value, ...'."""
    if isinstance(value, bool) or value is None:
        return {True: "yes", False: "no", None: "-"}[value]
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, dict):
        return ", ".join(f"{k} {text(v)}" for k, v in value.items())
    if isinstance(value, list | tuple):
        return ", ".join(text(v) for v in value)
    return str(value)


def _parameters(summary: dict, ds) -> str:
    """The fixed parameters: the kind's varied ones and a sweep's grid axes left out."""
    left_out = set(NOT_FIXED.get(summary.get("analysis"), ()))
    left_out |= set(attribute_list(ds.attrs, "grid_swept"))
    kept = [p for p in str(summary["parameters"]).split(", ")
            if p.split("=", 1)[0] not in left_out]
    return ", ".join(f"{k}={float(v):.6g}" if _is_number(v) else f"{k}={v}"
                     for k, v in (p.split("=", 1) for p in kept))


def _status_text(totals: dict, then: dict) -> str:
    """The sweep's status line when the second stage named some first-pass unresolved
    trajectories: "converged 0, unresolved 40 (first pass; then 40 named not periodic,
    0 left unresolved), diverged 0"."""
    return ", ".join(f"{key} {count}" + (f" (first pass; then {text(then)})"
                                         if key == "unresolved" else "")
                     for key, count in totals.items())


def _is_number(v: str) -> bool:
    try:
        float(v)
    except ValueError:
        return False
    return True


def _where(point: dict) -> str:
    """A grid point's axes: a chain's parameters (dotted names, ``stop.1.d``) first, as
    its grid dims are, then the presets' axes it has."""
    axes = [a for a in point if "." in a] + [a for a in every_axis() if a in point]
    return ", ".join(f"{a}={text(point[a])}" for a in axes)


def format_summary(summary: dict, ds, max_points: int = 50, kind=None) -> str:
    """The whole ``info`` text of a result (``summary`` from ``describe``); ``kind``: its
    AnalysisKind (its own lines; ``kinds.results.format_summary`` passes it)."""
    kind_name = summary.get("analysis")
    lines = []
    if "progress" in summary:  # an unfinished sweep
        p = summary["progress"]
        lines.append(f"{kind_name}: incomplete, {p['chunks_done']} of {p['chunks']} chunks done "
                     f"({100 * p['fraction']:.0f}%); finish with "
                     f"softimpact sweep {summary.get('scene_source')} -o RESULT --resume")
    finished = "progress" not in summary  # an unfinished sweep's file holds no results yet
    if finished and kind is not None and kind.info_lines is not None:
        lines += kind.info_lines(ds)
    first = {k: summary[k] for k in ("analysis", "model", "bodies") if k in summary}
    for key, value in {**first, **summary}.items():
        if key in SHOWN_ELSEWHERE or key == "progress":
            continue
        if key == "complete":
            value = bool(value)
        if key == "parameters":
            value = _parameters(summary, ds)
        elif key == "wall_s":
            value = f"{value:.2f} s" if isinstance(value, float) else value
        elif key == "status" and "status_unresolved" in summary:
            value = _status_text(value, summary["status_unresolved"])
        elif key == "impacts_per_period":  # a rigid result's, per impacting label
            value = per_period_text(value) or "none"
        elif key == "steps_by_method" and all(isinstance(v, dict) for v in value.values()):
            value = "; ".join(f"{phase}: {text(v)}" for phase, v in value.items())  # per phase
        lines.append(f"{key:28s} {text(value)}")
    if finished and kind is not None and kind.info_after is not None:
        lines += kind.info_after(ds)
    if "orbit" in summary:
        lines.append(f"orbit: {len(summary['orbit'])} section point(s) of "
                     f"({', '.join(summary['variables'])})")
        lines += [f"  {'  '.join(f'{x:+.6f}' for x in row)}" for row in summary["orbit"]]
    if "attractor" in ds.dims and (kind is None or kind.info_catalogue):
        lines.append("catalogue:")
        lines += [f"  {line}" for line in format_catalogue(ds).splitlines()]
    if "branches" in summary:
        lines += _branch_table(summary["branches"], str(ds.attrs.get("parameter", "d")))
    if "d_crit" in summary:
        lines += _dcrit_table(summary["d_crit"])
    if "nonperiodic" in summary:
        lines += nonperiodic_lines(summary["nonperiodic"])
    lines += verification_lines(ds.attrs)  # the label error, next to the shares
    if "stability" in summary:
        lines += _stability_table(summary["stability"], max_points)
    elif summary.get("points"):
        lines += _point_table(summary["points"], max_points)
    lines.append("scene:")
    lines += [f"  {line}" for line in summary.get("scene", "").splitlines()]
    return "\n".join(lines)


def _branch_table(branches: dict, parameter: str = "d") -> list[str]:
    """Each branch's destruction point and impacting range in the followed ``parameter``."""
    width = max([len(n) for n in branches] + [6])
    head = f"destroyed at {parameter}"
    at_width = max(14, len(head))
    out = [f"{'branch':{width}s}  {head:>{at_width}s}  {'falls to':16s}  impacting for "
           f"{parameter} in"]
    for name, b in branches.items():
        lo, hi = b["impacting_range"]
        at = "never" if b["destroyed_at"] is None else f"{b['destroyed_at']:.6g}"
        impacting = "-" if lo is None else f"[{lo:.6g}, {hi:.6g}]"
        out.append(f"{name:{width}s}  {at:>{at_width}s}  {b['falls_to'] or '-':16s}  "
                   f"{impacting}")
    return out


def _dcrit_table(dcrit: dict) -> list[str]:
    """All values when there are few phases, else the range over phi with where."""
    width = max([len(n) for n in dcrit] + [11])
    phis = next(iter(dcrit.values()))["phi"] if dcrit else []
    axis = next(iter(dcrit.values())).get("axis", "phi") if dcrit else "phi"
    if len(phis) <= 6:
        out = [f"{'d_crit':{width}s}  " + "  ".join(f"{axis + '=' + f'{p:.4g}':>10s}"
                                                    for p in phis)]
        for name, r in dcrit.items():
            out.append(f"{name:{width}s}  " + "  ".join(
                f"{'-' if v is None else f'{v:.4f}':>10s}" for v in r["d_crit"]))
        return out
    head = f"d_crit over {len(phis)} values of {axis}"
    width = max(width, len(head))
    at = f"at {axis}"
    out = [f"{head:{width}s}  "
           f"{'min':>9s} {at:>8s}  {'max':>9s} {at:>8s}"]
    for name, r in dcrit.items():
        v = np.array([np.nan if x is None else x for x in r["d_crit"]], dtype=float)
        if not np.isfinite(v).any():
            out.append(f"{name:{width}s}  no finite value")
            continue
        i, j = int(np.nanargmin(v)), int(np.nanargmax(v))
        out.append(f"{name:{width}s}  {v[i]:9.4f} {r['phi'][i]:8.4f}  {v[j]:9.4f} "
                   f"{r['phi'][j]:8.4f}")
    return out


def _point_table(points: list[dict], max_points: int) -> list[str]:
    out = [f"grid points ({len(points)}): share of initial conditions per label"]
    for point in points[:max_points]:
        shares = ", ".join(f"{n} {f:.3f}" for n, f in sorted(point["fractions"].items()))
        if point.get("impacts_per_period"):  # a rigid result's impacting labels
            shares += f"; impacts per period: {per_period_text(point['impacts_per_period'])}"
        counted = (f"; predicted {point['predicted']}, found {point['found']} "
                   f"({point['found_nonimpacting']} non-impacting)"
                   if "predicted" in point else "")
        out.append(f"  {_where(point)}: {shares}{counted}")
    if len(points) > max_points:
        out.append(f"  ... {len(points) - max_points} more points (--json lists all)")
    return out


def _stability_table(points: list[dict], max_points: int) -> list[str]:
    out = [f"basin stability ({len(points)} grid points): share [95% Wilson interval]"]
    for point in points[:max_points]:
        out.append(f"  {_where(point)} (n = {point['n']})")
        width = max(len(g) for g in point["shares"])
        for group, v in point["shares"].items():
            lo, hi = v["ci95"]
            out.append(f"    {group:{width}s} {v['share']:.3f} [{lo:.3f}, {hi:.3f}]")
        if "entropy" in point:
            h, (lo, hi) = point["entropy"]["H"], point["entropy"]["ci95"]
            out.append(f"    {'basin entropy of the shares H':{width}s} {h:.3f} [{lo:.3f}, "
                       f"{hi:.3f}] nat (95% bootstrap)")
    if len(points) > max_points:
        out.append(f"  ... {len(points) - max_points} more points (--json lists all)")
    return out
