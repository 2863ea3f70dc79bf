"""Basin stability (figures 14, 15): shares with Wilson intervals, against t0."""

from __future__ import annotations

import math  # noqa: F401
from functools import partial

import numpy as np

from .. import measures as M
from ..runs import RUNS, MissingRun
from ..verdicts import Measure
from . import CHECKS, PI, _counted, _pct, _share_text, check
from .basins import _plane

# ------------------------------------------------------------------ basin stability

def _stability(runs, run: str, **where) -> dict:
    points = M.stability_points(runs(run))
    for p in points:
        if all(p.get(k) == v if isinstance(v, str) else abs(float(p[k]) - v) < 1e-6
               for k, v in where.items()):
            return p
    raise KeyError(f"{run}: no point at {where}")


def _shares(p: dict, groups: list[str]) -> tuple[list[float], list[tuple[float, float]]]:
    values, cis = [], []
    for g in groups:
        s, ci = M.share(p, g)
        values.append(s)
        cis.append(ci)
    return values, cis


def _share_measure(p: dict, groups: list[str], run: str, label: str = "") -> Measure:
    values, cis = _shares(p, groups)
    return Measure(values if len(values) > 1 else values[0],
                   _share_text(values, cis, p["n"]), (run,), ci=cis, label=label)


DUFFING_C = ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^2", "impacting (all)"]
DUFFING_D = ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^2"]
T0S = (("T/4", 0.25), ("T/2", 0.5), ("3T/4", 0.75))


def _t0_values(runs, run: str) -> dict:
    """{t0 label: point} of a stability run over t0 (fig14c_t0 and fig14d_t0)."""
    ds = runs(run)
    period = 2 * PI / float(RUNS[run].scene().values["w"])
    out = {}
    for p in M.stability_points(ds):
        frac = float(p["t0"]) / period
        out[next((s for s, f in T0S if abs(f - frac) < 1e-6), "0" if frac < 1e-9
                 else f"{frac:.3f} T")] = p
    return out


def _menck(runs, c_c: float, groups: list[str]) -> Measure:
    """Figure 14(c, d) basin stability: the t0 = 0 point of the scene swept over t0 (the
    same samples as figure 15(b) at this c_c), and the other start phases as
    explanations."""
    t0s = "fig14c_t0" if c_c == 10.0 else "fig14d_t0"
    points = _t0_values(runs, t0s)
    m = _share_measure(points["0"], groups, t0s)
    m.shown += ", t0 = 0"
    for key, p in points.items():
        if key != "0":
            m.alternatives.append(_share_measure(p, groups, t0s, label=f"start at t0 = {key}"))
    if c_c == 10.0:
        p = M.stability_points(runs("fig14c_random_t0"))[0]
        m.alternatives.append(_share_measure(p, groups, "fig14c_random_t0",
                                             label="t0 uniform in [0, T) per sample"))
    return m


def _panel_check(measure, c_c: float, groups: list[str], st, runs) -> Measure:
    """A check of a figure 14 (c, d) panel: ``measure(runs, c_c, groups)``."""
    return measure(runs, c_c, groups)


def _plane_shares(runs, c_c: float, groups: list[str]) -> Measure:
    m = _share_measure(_plane(runs, "fig14cd", c_c=c_c), groups, "fig14cd")
    m.shown += ", t0 = 0"
    m.note = "plane shares: Wilson interval over the plane's cells"
    try:
        m.alternatives.append(_share_measure(_plane(runs, "fig14cd_t0half", c_c=c_c), groups,
                                             "fig14cd_t0half", label="start at t0 = T/2"))
    except MissingRun as missing:
        m.pending.append(missing.name)
    return m


# figure 14 (c) at c_c = 10 and (d) at c_c = 2: the plane's shares and the 4-D ones
CHECKS.update({
    "fig14c_plane_shares": partial(_panel_check, _plane_shares, 10.0, DUFFING_C),
    "fig14d_plane_shares": partial(_panel_check, _plane_shares, 2.0, DUFFING_D),
    "fig14c_menck_shares": partial(_panel_check, _menck, 10.0, DUFFING_C),
    "fig14d_menck_shares": partial(_panel_check, _menck, 2.0, DUFFING_D),
})


@check("fig14a_plane_share")
def fig14a_plane_share(st, runs):
    m = _share_measure(_plane(runs, "fig14ab", k_c=8.0), ["non-impacting (sum)"], "fig14ab")
    try:
        m.alternatives.append(_share_measure(_plane(runs, "fig14ab_t0half", k_c=8.0),
                                             ["non-impacting (sum)"], "fig14ab_t0half",
                                             label="start at t0 = T/2"))
    except MissingRun as missing:
        m.pending.append(missing.name)
    return m


@check("fig14a_menck_share")
def fig14a_menck_share(st, runs):
    return _share_measure(_stability(runs, "fig14a_stability", k_c=8.0),
                          ["non-impacting (sum)"], "fig14a_stability")


@check("bilinear_agreement")
def bilinear_agreement(st, runs):
    plane = M.share(_plane(runs, "fig14ab", k_c=8.0), "non-impacting (sum)")
    menck = M.share(_stability(runs, "fig14a_stability", k_c=8.0), "non-impacting (sum)")
    overlap = plane[1][0] <= menck[1][1] and menck[1][0] <= plane[1][1]
    return Measure(overlap, f"figure 14(a): plane {_pct(plane[0])}, basin stability "
                   f"{_pct(menck[0])} [{_pct(menck[1][0])}, {_pct(menck[1][1])}]: intervals "
                   f"{'overlap' if overlap else 'do not overlap'}", ("fig14ab", "fig14a_stability"))


@check("fig14b_both_full")
def fig14b_both_full(st, runs):
    plane = M.share(_plane(runs, "fig14ab", k_c=20.0), "non-impacting (sum)")[0]
    menck = M.share(_stability(runs, "fig14a_stability", k_c=20.0), "non-impacting (sum)")[0]
    return Measure(plane == 1.0 and menck == 1.0, f"plane {_pct(plane)}, basin stability "
                   f"{_pct(menck)}", ("fig14ab", "fig14a_stability"))


def _largest_difference(runs, plane_run: str, t0_key: str) -> float:
    diffs = []
    for c_c, groups, t0_run in ((10.0, DUFFING_C, "fig14c_t0"), (2.0, DUFFING_D, "fig14d_t0")):
        plane = _shares(_plane(runs, plane_run, c_c=c_c), groups)[0]
        menck = _shares(_t0_values(runs, t0_run)[t0_key], groups)[0]
        diffs += [abs(a - b) for a, b in zip(plane, menck, strict=True)]
    return max(diffs)


@check("duffing_method_difference")
def duffing_method_difference(st, runs):
    worst = _largest_difference(runs, "fig14cd", "0")
    m = Measure(worst, f"largest |plane - basin stability| over figure 14(c, d): "
                f"{_pct(worst)} (both at t0 = 0)", ("fig14cd", "fig14c_t0", "fig14d_t0"),
                tolerance=0.03, note="tolerance 3 points: the Wilson half-width at N = 1000")
    try:
        half = _largest_difference(runs, "fig14cd_t0half", "T/2")
        m.alternatives.append(Measure(half, f"{_pct(half)}", ("fig14cd_t0half", "fig14c_t0",
                                                               "fig14d_t0"),
                                      tolerance=0.03, label="both started at t0 = T/2"))
    except MissingRun as missing:
        m.pending.append(missing.name)
    return m


@check("fig15_settings")
def fig15_settings(st, runs):
    parts, ok = [], True
    for name, box, axis, lo, hi in (("fig15a", 2.0, "k_c", 5.0, 20.0),
                                    ("fig15b", 12.0, "c_c", 1.0, 11.0)):
        scene = RUNS[name].scene()
        ic = scene.initial_conditions
        values = scene.grid.axes[axis]
        arr = ic.array()
        ok &= ic.count == 1000 and np.all(np.abs(arr) <= box) and \
            (values[0], values[-1]) == (lo, hi)
        parts.append(f"{name}: N = {ic.count}, samples in [-{box:g}, {box:g}]^4, "
                     f"{axis} {values[0]:g}..{values[-1]:g} ({len(values)} points)")
    return Measure(bool(ok), "; ".join(parts), ("fig15a", "fig15b scenes"))


def _nonimpacting_reached(run: str):
    def fn(st, runs):
        names = set()
        for p in M.stability_points(runs(run)):
            names |= {n for n, c in p["counts"].items() if c > 0 and M.is_solution(n)}
        return _counted(sorted(names), "reached", run)
    return fn


CHECKS["fig15a_nonimpacting_count"] = _nonimpacting_reached("fig15a")
CHECKS["fig15b_nonimpacting_count"] = _nonimpacting_reached("fig15b")


def _curve(runs, run: str, axis: str, group: str):
    points = M.stability_points(runs(run))
    return [(p[axis], *M.share(p, group)) for p in points]


@check("fig15a_over_75")
def fig15a_over_75(st, runs):
    curve = _curve(runs, "fig15a", "k_c", "non-impacting (sum)")
    low = min(curve, key=lambda c: c[1])
    return Measure(low[1] > st["study"], f"lowest non-impacting share {_pct(low[1])} "
                   f"[{_pct(low[2][0])}, {_pct(low[2][1])}] at k_c = {low[0]:g}", ("fig15a",))


@check("fig15a_full_above")
def fig15a_full_above(st, runs):
    curve = _curve(runs, "fig15a", "k_c", "non-impacting (sum)")
    above = [c for c in curve if c[0] > st["study"]]
    full = [c[0] for c in curve if c[1] == 1.0]
    ok = bool(above) and all(c[1] == 1.0 for c in above)
    return Measure(ok, "100% at k_c = " + (", ".join(f"{k:g}" for k in full) or "none")
                   + f" (grid step {curve[1][0] - curve[0][0]:g}); above {st['study']:g}: "
                   + ", ".join(f"k_c = {c[0]:g}: {_pct(c[1])} [{_pct(c[2][0])}, "
                               f"{_pct(c[2][1])}]" for c in above), ("fig15a",))


@check("fig15a_fluctuations")
def fig15a_fluctuations(st, runs):
    curve = _curve(runs, "fig15a", "k_c", "non-impacting (sum)")
    s = np.array([c[1] for c in curve])
    jumps = np.abs(np.diff(s))
    half = np.mean([(c[2][1] - c[2][0]) / 2 for c in curve])
    ok = half <= 2 * st["study"]
    return Measure(ok, f"median step-to-step change {_pct(np.median(jumps))}, largest "
                   f"{_pct(jumps.max())}; mean 95% Wilson half-width {_pct(half)}",
                   ("fig15a",))


def _impacting_max(st, runs, run: str, t0: str) -> Measure:
    curve = _curve(runs, run, "c_c", "impacting (all)")
    top = max(curve, key=lambda c: c[1])
    return Measure(top[2][0] <= st["study"], f"largest impacting share {_pct(top[1])} "
                   f"[{_pct(top[2][0])}, {_pct(top[2][1])}] at c_c = {top[0]:g} (t0 = {t0})",
                   (run,), label=f"start at t0 = {t0}")


def _sum_range(runs, run: str, t0: str) -> Measure:
    s = np.array([c[1] for c in _curve(runs, run, "c_c", "non-impacting (sum)")])
    return Measure(np.ptp(s) <= 0.1, f"non-impacting sum from {_pct(s.min())} to "
                   f"{_pct(s.max())} over c_c (t0 = {t0})", (run,), label=f"start at t0 = {t0}")


def _with_t0half(m: Measure, make) -> Measure:
    try:
        m.alternatives.append(make())
    except MissingRun as missing:
        m.pending.append(missing.name)
    return m


@check("fig15b_impacting_max")
def fig15b_impacting_max(st, runs):
    return _with_t0half(_impacting_max(st, runs, "fig15b", "0"),
                        lambda: _impacting_max(st, runs, "fig15b_t0half", "T/2"))


@check("fig15b_no_impacting_low")
def fig15b_no_impacting_low(st, runs):
    curve = _curve(runs, "fig15b", "c_c", "impacting (all)")
    low = [c for c in curve if c[0] < st["study"]]
    return Measure(bool(low) and all(c[1] == 0.0 for c in low), "impacting share at c_c = "
                   + ", ".join(f"{c[0]:g}: {_pct(c[1])}" for c in low), ("fig15b",))


@check("fig15b_sum_constant")
def fig15b_sum_constant(st, runs):
    m = _with_t0half(_sum_range(runs, "fig15b", "0"),
                     lambda: _sum_range(runs, "fig15b_t0half", "T/2"))
    m.note = "'nearly constant' read as a range within 10 points"
    return m
