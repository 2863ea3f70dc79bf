"""Compare two results of the same scene layout (``softimpact compare A B``).

Sweeps (basins, stability, map): the labels point by point (the same grid and the same
initial conditions are required) and, per solution and grid point, the share of the
initial conditions reaching it in each result with its 95% Wilson interval. Critical
distances: d_crit per combination and phase. Bifurcations: the destruction point of
each branch. The report is a dict; :func:`limits_exceeded` says which of the CI limits
it passes.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ..analysis.attributes import attribute_list
from ..analysis.stability import wilson_interval
from ..config import ConfigError
from ..config.axes import every_axis
from ..sweep.result import grid_axes, grid_dims, grid_point


def comparable(kinds: Mapping[str, Any]) -> tuple[str, ...]:
    """The kinds of ``kinds`` (the registry) that compare takes: those with a ``compare``."""
    return tuple(name for name, kind in kinds.items() if kind.compare is not None)


def compare_results(a, b, name_a: str, name_b: str, kinds: Mapping[str, Any]) -> dict:
    """The differences of result ``b`` from result ``a`` (xarray Datasets), by the
    ``compare`` of their kind in ``kinds`` (the registry: ``kinds.results`` passes it).

    ConfigError (one line) when the two cannot be compared: another analysis kind, a
    kind compare does not take, or another grid, phase set or set of initial conditions.
    """
    kind_a, kind_b = a.attrs.get("analysis"), b.attrs.get("analysis")
    if kind_a not in comparable(kinds):
        raise ConfigError(f"{name_a}: holds a {kind_a} result; compare takes "
                          f"{', '.join(comparable(kinds))} results")
    if kind_b != kind_a:
        raise ConfigError(f"{name_b}: holds a {kind_b} result, {name_a} a {kind_a} result; "
                          "compare needs two results of the same kind")
    for ds, name in ((a, name_a), (b, name_b)):
        if int(ds.attrs.get("complete", 1)) != 1:
            raise ConfigError(f"{name}: is incomplete; finish it with --resume first")
    report = {"analysis": kind_a, "a": name_a, "b": name_b}
    report.update(kinds[kind_a].compare(a, b, name_a, name_b))
    return report


def _same(a, b, what: str, name_a: str, name_b: str) -> None:
    """ConfigError naming ``what`` when the arrays a and b differ (shape or values)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        raise ConfigError(f"{name_b}: {what} differs from {name_a}'s (shape {b.shape} vs "
                          f"{a.shape}); compare needs the same grid and initial conditions")
    if a.dtype.kind in "fc" and not np.allclose(a, b, rtol=1e-12, atol=0.0, equal_nan=True):
        raise ConfigError(f"{name_b}: {what} differs from {name_a}'s; compare needs the same "
                          "grid and initial conditions")
    if a.dtype.kind not in "fc" and not np.array_equal(a, b):
        raise ConfigError(f"{name_b}: {what} differs from {name_a}'s; compare needs the same "
                          "grid and initial conditions")


def _names(ds, dims: list[str]) -> np.ndarray:
    """Per-trajectory label names, over ``dims`` (grid dims, then initial-condition dims)."""
    table = dict(zip((int(c) for c in ds["label_code"].values),
                     (str(n) for n in ds["label_name"].values), strict=True))
    return np.vectorize(table.__getitem__, otypes=[object])(ds["label"].transpose(*dims).values)


def compare_sweeps(a, b, name_a: str, name_b: str) -> dict:
    """Label agreement point by point and share differences per solution and grid point."""
    _same(list(grid_dims(a)), list(grid_dims(b)), "grid layout", name_a, name_b)
    for axis in grid_axes(a):
        _same(a[axis].values, b[axis].values, f"grid axis {axis}", name_a, name_b)
    ic_dims = attribute_list(a.attrs, "ic_dims")
    _same(ic_dims, attribute_list(b.attrs, "ic_dims"), "initial-condition layout",
          name_a, name_b)
    for dim in ic_dims:
        _same(a[dim].values, b[dim].values, f"initial conditions ({dim})", name_a, name_b)
    for var in ("initial_state", "sample_t0"):
        if (var in a) != (var in b):
            raise ConfigError(f"{name_b}: {var} is in only one of the two results; compare "
                              "needs the same initial conditions")
        if var in a:
            _same(a[var].values, b[var].values, var.replace("_", " "), name_a, name_b)
    dims = list(grid_dims(a))
    la, lb = _names(a, dims + ic_dims), _names(b, dims + ic_dims)
    grid_shape = la.shape[: len(dims)]
    n_points = int(np.prod(grid_shape))
    la, lb = la.reshape(n_points, -1), lb.reshape(n_points, -1)
    n = la.shape[1]
    changed = la != lb
    changes: dict[str, int] = {}
    for x, y in zip(la[changed], lb[changed], strict=True):
        changes[f"{x} -> {y}"] = changes.get(f"{x} -> {y}", 0) + 1
    solutions = sorted(set(la.ravel()) | set(lb.ravel()))
    shares = []
    for k, index in enumerate(np.ndindex(*grid_shape)):
        rows = {}
        for s in solutions:
            ka, kb = int(np.sum(la[k] == s)), int(np.sum(lb[k] == s))
            if ka == kb == 0:
                continue
            (lo_a,), (hi_a,) = wilson_interval(np.array([ka]), n)
            (lo_b,), (hi_b,) = wilson_interval(np.array([kb]), n)
            rows[s] = {"a": ka / n, "a_ci95": [float(lo_a), float(hi_a)],
                       "b": kb / n, "b_ci95": [float(lo_b), float(hi_b)],
                       "change": (kb - ka) / n}
        shares.append({**grid_point(a, index), "n": n, "shares": rows})
    largest = max((abs(r["change"]) for p in shares for r in p["shares"].values()),
                  default=0.0)
    return {"trajectories": int(la.size), "label_changed": int(changed.sum()),
            "label_change_share": float(changed.mean()) if la.size else 0.0,
            "changes": changes, "max_share_change": float(largest), "points": shares}


def dcrit_curves(ds) -> tuple[str, np.ndarray, dict[str, np.ndarray]]:
    """(axis name, axis values, {curve name: d_crit along the axis}) of a dcrit result: a
    pair's combinations along phi, or a chain's (stop, product) pairs along its axis
    ("stop 2: 1:P1^1 2:P1-0^1 ...")."""
    labels = [str(n) for n in ds["combination_label"].values]
    d = ds["d_crit"].values
    if "stop" in ds["d_crit"].dims:  # a chain: d_crit(stop, combination, point)
        curves = {f"stop {int(s)}: {name}": d[k, i]
                  for k, s in enumerate(ds["stop"].values) for i, name in enumerate(labels)}
        return str(ds.attrs.get("axis", "point")), ds["point"].values, curves
    return "phi", ds["phi"].values, {name: d[i] for i, name in enumerate(labels)}


def compare_dcrit(a, b, name_a: str, name_b: str) -> dict:
    """d_crit of every combination (a chain's: every stop's of every product) at every
    point of the axis: B - A."""
    axis, points, curves_a = dcrit_curves(a)
    axis_b, points_b, curves_b = dcrit_curves(b)
    if axis_b != axis:
        raise ConfigError(f"{name_b}: its critical values run along {axis_b}, {name_a}'s "
                          f"along {axis}")
    _same(points, points_b, f"grid of {axis}", name_a, name_b)
    rows = {}
    for name in sorted(set(curves_a) | set(curves_b)):
        if name not in curves_a or name not in curves_b:
            rows[name] = {"in": name_a if name in curves_a else name_b}
            continue
        diff = np.abs(curves_b[name] - curves_a[name])
        worst = int(np.nanargmax(diff)) if np.isfinite(diff).any() else 0
        rows[name] = {"max_change": float(np.nanmax(diff)) if np.isfinite(diff).any() else 0.0,
                      "at": float(points[worst])}
    largest = max((r.get("max_change", 0.0) for r in rows.values()), default=0.0)
    only = sorted(n for n, r in rows.items() if "in" in r)
    return {"axis": axis, "combinations": rows, "max_d_change": float(largest),
            "only_in_one": only}


def compare_bifurcations(a, b) -> dict:
    """Destruction point (in the followed parameter) of every branch both results
    follow: B - A."""
    da = {str(n): float(v) for n, v in zip(a["branch_name"].values, a["destroyed_at"].values,
                                           strict=True)}
    db = {str(n): float(v) for n, v in zip(b["branch_name"].values, b["destroyed_at"].values,
                                           strict=True)}
    rows = {}
    for name in sorted(set(da) | set(db)):
        x, y = da.get(name), db.get(name)
        row = {"a": x, "b": y}
        if x is not None and y is not None:
            if np.isfinite(x) and np.isfinite(y):
                row["change"] = y - x
            elif np.isfinite(x) != np.isfinite(y):
                row["change"] = "destroyed in one only"
            else:
                row["change"] = 0.0
        rows[name] = row
    numeric = [abs(r["change"]) for r in rows.values() if isinstance(r.get("change"), float)]
    one_sided = [n for n, r in rows.items() if not isinstance(r.get("change", 0.0), float)
                 or "change" not in r]
    return {"parameter": str(a.attrs.get("parameter", "d")), "branches": rows,
            "max_d_change": max(numeric, default=0.0), "differ_in_kind": one_sided}


def limits_exceeded(report: dict, max_label_change: float | None = None,
                    max_share_change: float | None = None,
                    max_d_change: float | None = None) -> list[str]:
    """Why the report fails the given limits (empty: it passes)."""
    why = []
    if max_label_change is not None and "label_change_share" in report \
            and report["label_change_share"] > max_label_change:
        why.append(f"label change share {report['label_change_share']:.4f} > "
                   f"--max-label-change {max_label_change:g}")
    if max_share_change is not None and "max_share_change" in report \
            and report["max_share_change"] > max_share_change:
        why.append(f"largest share change {report['max_share_change']:.4f} > "
                   f"--max-share-change {max_share_change:g}")
    if max_d_change is not None and "max_d_change" in report:
        if report["max_d_change"] > max_d_change:
            why.append(f"largest d change {report['max_d_change']:.4g} > "
                       f"--max-d-change {max_d_change:g}")
        if report.get("only_in_one") or report.get("differ_in_kind"):
            why.append("a combination or branch differs in kind: "
                       + ", ".join(report.get("only_in_one") or report.get("differ_in_kind")))
    return why


def format_comparison(report: dict, compare_text, max_points: int = 20) -> str:
    """The report as plain text; ``compare_text(report, max_points)``: its kind's lines."""
    head = f"{report['analysis']}: {report['b']} against {report['a']}"
    return "\n".join([head, *compare_text(report, max_points)])


def sweep_comparison_text(report: dict, max_points: int) -> list[str]:
    """Labels changed, then the shares per grid point with their intervals."""
    lines = []
    if report["label_changed"] == 0:
        lines.append(f"labels: identical ({report['trajectories']} trajectories)")
    else:
        lines.append(f"labels: {report['label_changed']} of {report['trajectories']} "
                     f"changed ({100 * report['label_change_share']:.2f}%)")
        for change, count in sorted(report["changes"].items(), key=lambda kv: -kv[1]):
            lines.append(f"  {change}: {count}")
    lines.append(f"largest share change at a grid point: {report['max_share_change']:.4f}")
    width = max([len(s) for p in report["points"] for s in p["shares"]] + [8])
    for point in report["points"][:max_points]:
        where = ", ".join(f"{k}={point[k]:.6g}" if isinstance(point[k], float)
                          else f"{k}={point[k]}" for k in every_axis() if k in point)
        lines.append(f"{where} ({point['n']} trajectories)")
        lines.append(f"  {'solution':{width}s} {'A':>6s} {'95% interval':>15s} "
                     f"{'B':>6s} {'95% interval':>15s} {'B - A':>7s}")
        for s, r in point["shares"].items():
            lines.append(f"  {s:{width}s} {r['a']:6.3f} [{r['a_ci95'][0]:.3f}, "
                         f"{r['a_ci95'][1]:.3f}] {r['b']:6.3f} [{r['b_ci95'][0]:.3f}, "
                         f"{r['b_ci95'][1]:.3f}] {r['change']:+7.3f}")
    if len(report["points"]) > max_points:
        lines.append(f"... {len(report['points']) - max_points} more grid points "
                     "(--json lists all)")
    return lines


def dcrit_comparison_text(report: dict) -> list[str]:
    """The largest d_crit change per combination."""
    width = max([16] + [len(n) for n in report["combinations"]])
    at = f"at {report.get('axis', 'phi')}"
    lines = [f"largest d_crit change: {report['max_d_change']:.4g}",
             f"  {'combination':{width}s} {'max |B - A|':>12s} {at:>8s}"]
    for name, r in report["combinations"].items():
        if "in" in r:
            lines.append(f"  {name:{width}s} only in {r['in']}")
        else:
            lines.append(f"  {name:{width}s} {r['max_change']:12.4g} {r['at']:8.4f}")
    return lines


def bifurcation_comparison_text(report: dict) -> list[str]:
    """The destruction point of each branch in both results."""
    width = max([16] + [len(n) for n in report["branches"]])
    head = f"A: destroyed at {report.get('parameter', 'd')}"
    lines = [f"largest change of a destruction point: {report['max_d_change']:.4g}",
             f"  {'branch':{width}s} {head:>18s} {'B':>10s} {'B - A':>10s}"]

    def at(v):
        return "-" if v is None else ("never" if not np.isfinite(v) else f"{v:.4g}")

    for name, r in report["branches"].items():
        change = r.get("change", "branch in one only")
        change = f"{change:+.4g}" if isinstance(change, float) else change
        lines.append(f"  {name:{width}s} {at(r['a']):>{max(18, len(head))}s} "
                     f"{at(r['b']):>10s} {change:>10s}")
    return lines
