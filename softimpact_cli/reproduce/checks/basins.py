"""Plane basins: solutions present, impacting shares, boundaries (figures 3, 6, 7, 9, 12-14)."""

from __future__ import annotations

import math  # noqa: F401

import numpy as np

from ...analysis.attributes import attribute_list
from .. import measures as M
from ..runs import MissingRun
from ..verdicts import Measure
from . import CHECKS, PI, _names, _pct, _share_text, check

# ------------------------------------------------------------------ plane basins

def _plane(runs, run: str, **where) -> dict:
    return M.point_at(M.plane_points(runs(run)), **where)


def _found_text(p: dict) -> str:
    sol, imp = M.found(p)
    parts = [f"{n} {_pct(p['counts'][n] / p['n'])}" for n in sol + imp]
    return f"{len(sol)} non-impacting" + (f" + {len(imp)} impacting" if imp else "") + \
        f" ({', '.join(parts)}; {p['n']} starts)"


def _count(run: str, with_dcrit: tuple | None = None, **where):
    """Number of solutions found on the plane at a grid point (non-impacting and
    impacting); with_dcrit = (dcrit run, d, phi) adds what the critical distances predict
    there, and at -phi."""
    def fn(st, runs):
        p = _plane(runs, run, **where)
        sol, imp = M.found(p)
        m = Measure(len(sol) + len(imp), _found_text(p), (run,))
        if imp:
            m.alternatives.append(Measure(len(sol), f"{len(sol)}", (run,),
                                          label="counting the non-impacting solutions only"))
        if with_dcrit:
            m.alternatives += _predicted(runs, *with_dcrit, count=True)
        return m
    return fn


def _names_found(run: str, with_dcrit: tuple | None = None, **where):
    def fn(st, runs):
        p = _plane(runs, run, **where)
        sol, imp = M.found(p)
        m = Measure(sol + imp, _found_text(p), (run,))
        if with_dcrit:
            m.alternatives += _predicted(runs, *with_dcrit, count=False)
        return m
    return fn


def _predicted(runs, dcrit_run: str, d: float, phi: float, count: bool) -> list[Measure]:
    ds = runs(dcrit_run)
    out = []
    for label, at in (("existence predicted by d_crit at phi", phi),
                      ("existence predicted by d_crit at -phi (phase sign flipped)",
                       (2 * PI - phi) % (2 * PI))):
        names = M.survivors(ds, d, at)
        out.append(Measure(len(names) if count else names, f"{len(names)}: {_names(names)}",
                           (dcrit_run,), label=label))
    return out


FIG12 = "fig12_dcrit"
for _key, _fn in {
    "fig06a_count": _count("fig06", d=22.0, phi=0.0),
    "fig06c_count": _count("fig06", d=10.5, phi=5.28),
    "fig06d_count": _count("fig06", d=6.0, phi=0.0),
    "fig06e_count": _count("fig06", d=9.0, phi=0.573 * PI),
    "fig06f_count": _count("fig06", d=5.0, phi=PI),
    "fig06b_names": _names_found("fig06", ("fig05", 15.0, PI), d=15.0, phi=PI),
    "fig06c_names": _names_found("fig06", ("fig06_dcrit", 10.5, 5.28), d=10.5, phi=5.28),
    "fig12a_count": _count("fig12", (FIG12, 10.0, PI), d=10.0, phi=PI),
    "fig12b_count": _count("fig12", (FIG12, 1.332, 0.60916), d=1.332, phi=0.60916),
    "fig12b_names": _names_found("fig12", (FIG12, 1.332, 0.60916), d=1.332, phi=0.60916),
    "fig12c_count": _count("fig12", (FIG12, 1.0, 0.36424), d=1.0, phi=0.36424),
    "fig12c_names": _names_found("fig12", (FIG12, 1.0, 0.36424), d=1.0, phi=0.36424),
    "fig12d_count": _count("fig12", (FIG12, 2.448, PI), d=2.448, phi=PI, c_c=2.0),
    "fig12d_names": _names_found("fig12", (FIG12, 2.448, PI), d=2.448, phi=PI, c_c=2.0),
    "fig13a_count": _count("fig13", ("fig13_dcrit_points", 10.0, PI), d=10.0, phi=PI),
    "fig13b_count": _count("fig13", ("fig13_dcrit_points", 2.0, 0.4), d=2.0, phi=0.4),
}.items():
    CHECKS[_key] = _fn


@check("fig06_no_impacting")
def fig06_no_impacting(st, runs):
    points = M.plane_points(runs("fig06"))
    imp = [(p["d"], M.share(p, "impacting (all)")[0]) for p in points]
    return Measure(all(s == 0 for _, s in imp), "impacting share per panel: "
                   + ", ".join(f"d={d:g}: {_pct(s)}" for d, s in imp), ("fig06",))


@check("fig06a_outside_own_basin")
def fig06a_outside_own_basin(st, runs):
    ds = runs("fig06")
    points = M.plane_points(ds)
    panel = points.index(M.point_at(points, d=22.0, phi=0.0))
    label, axes, table = M.plane_labels(ds, panel)
    ic_dims = attribute_list(ds.attrs, "ic_dims")
    names = M.combination_names(ds)
    orbits = ds["combination_orbit"].values
    variables = [str(v) for v in ds["variable"].values]
    outside = []
    for i, name in enumerate(names):
        pts = orbits[i][np.all(np.isfinite(orbits[i]), axis=1)]
        own = 0
        for p in pts:
            idx = tuple(int(np.argmin(np.abs(ax - p[variables.index(dim)])))
                        for ax, dim in zip(axes, ic_dims, strict=True))
            own += table.get(int(label[idx]), "") == name
        if own == 0:
            outside.append(name)
    return Measure(len(outside), f"{len(outside)} of {len(names)} attractors have no "
                   f"stroboscopic point (projected on v1 = v2 = 0) inside their own basin: "
                   f"{_names(outside)}", ("fig06",))


def _impacting_share(run_name: str, d: float):
    def fn(st, runs):
        def one(run):
            p = _plane(runs, run, d=d)
            s, ci = M.share(p, "impacting (all)")
            return Measure(s, _share_text([s], [ci], p["n"]) + " at t0 = "
                           + ("T/2" if "t0half" in run else "0"), (run,), ci=[ci])
        m = one(run_name)
        m.note = "plane shares: Wilson interval over the plane's cells (a stand-in for " \
            "the resolution error)"
        try:
            alt = one(run_name + "_t0half")
            alt.label = "start at t0 = T/2"
            m.alternatives.append(alt)
        except MissingRun as missing:
            m.pending.append(missing.name)
        return m
    return fn


CHECKS["fig07_impacting_8_2"] = _impacting_share("fig07_basins", 8.2)
CHECKS["fig07_impacting_10_25"] = _impacting_share("fig07_basins", 10.25)
CHECKS["fig07_impacting_16_25"] = _impacting_share("fig07_basins", 16.25)


@check("fig07_impacting_small")
def fig07_impacting_small(st, runs):
    b = M.branches(runs("fig07"))
    widths = [max(v["impacting_range"]) - min(v["impacting_range"]) for n, v in b.items()
              if n != "L1^1 R1-0^1"]
    shares = [M.share(p, "impacting (all)")[0] for p in M.plane_points(runs("fig07_basins"))]
    ok = max(widths) < 1.0 and max(shares) < 0.5
    return Measure(ok, "impacting ranges after destruction "
                   + ", ".join(f"{w:.2f}" for w in widths) + "; impacting basin shares "
                   + ", ".join(_pct(s) for s in shares), ("fig07", "fig07_basins"))


def _coexist(run: str, want: bool, **where):
    def fn(st, runs):
        p = _plane(runs, run, **where)
        sol, imp = M.found(p)
        ok = bool(sol) and (bool(imp) == want)
        return Measure(ok, _found_text(p), (run,))
    return fn


CHECKS["fig14a_coexist"] = _coexist("fig14ab", True, k_c=8.0)
CHECKS["fig14b_only_nonimpacting"] = _coexist("fig14ab", False, k_c=20.0)
CHECKS["fig14c_coexist"] = _coexist("fig14cd", True, c_c=10.0)
CHECKS["fig14d_only_nonimpacting"] = _coexist("fig14cd", False, c_c=2.0)


@check("fig09_period2_dominant")
def fig09_period2_dominant(st, runs):
    p = M.plane_points(runs("fig09"))[0]
    shares = {n: c / p["n"] for n, c in p["counts"].items()}
    two = sum(v for n, v in shares.items() if n.startswith("L2^"))
    five = sum(v for n, v in shares.items() if n.startswith("L5^"))
    return Measure(two > five, f"period 2: {_pct(two)}, period 5: {_pct(five)} of "
                   f"{p['n']} starts", ("fig09",))


def _boundary(run: str):
    ds = run
    label, _, _ = M.plane_labels(ds, 0)
    return M.boundary_dimension(label)


@check("duffing_smooth_boundary")
def duffing_smooth_boundary(st, runs):
    dim = _boundary(runs("fig03"))
    return Measure(dim < 1.2, f"box-counting dimension of the basin boundary {dim:.2f} "
                   "(1 for a smooth curve; < 1.2 taken as smooth)", ("fig03",))


def _velocity_rows(ds, code_name: str) -> np.ndarray:
    label, _, table = M.plane_labels(ds, 0)
    ic_dims = attribute_list(ds.attrs, "ic_dims")
    codes = [c for c, n in table.items() if n.startswith(code_name)]
    hit = np.isin(label, codes)
    return hit.mean(axis=ic_dims.index("x"))  # share per velocity


def _rows_measure(runs, run: str, label: str = "") -> Measure:
    rows = _velocity_rows(runs(run), "L1^1")
    return Measure(rows.min() == 0.0 and rows.max() == 1.0,
                   f"share of L1^1 per velocity row: {_pct(rows.min())} to {_pct(rows.max())}",
                   (run,), label=label)


@check("fig03_velocity_rows")
def fig03_velocity_rows(st, runs):
    m = _rows_measure(runs, "fig03")
    try:
        m.alternatives.append(_rows_measure(runs, "fig03_wide_r50",
                                            "a wider velocity window, [-40, 40]"))
    except MissingRun as missing:
        m.pending.append(missing.name)
    return m


@check("fig09_velocity_rows")
def fig09_velocity_rows(st, runs):
    ds = runs("fig09")
    rows = _velocity_rows(ds, "L2^")
    dim = _boundary(ds)
    ok = rows.min() > 0.0 and rows.max() < 1.0
    return Measure(ok, f"share of the period-2 basin per velocity row: {_pct(rows.min())} "
                   f"to {_pct(rows.max())} (no row without either attractor); boundary "
                   f"box-counting dimension {dim:.2f}", ("fig09",))


@check("reduced_to_one")
def reduced_to_one(st, runs):
    single, used = [], []
    for run in ("fig06", "fig12", "fig13"):
        try:
            points = M.plane_points(runs(run))
        except MissingRun:
            if run == "fig06":  # figure 6(f) is the study's example: needed
                raise
            continue
        used.append(run)
        for p in points:
            sol, imp = M.found(p)
            if len(sol) + len(imp) == 1:
                single.append(f"{run} d={p['d']:g} phi={p['phi']:.4g}: {sol[0] if sol else imp[0]}")
    return Measure(bool(single), "; ".join(single) or "no panel with a single solution",
                   tuple(used))


@check("stop_parameters_eliminate")
def stop_parameters_eliminate(st, runs):
    b = _plane(runs, "fig14ab", k_c=20.0)
    d = _plane(runs, "fig14cd", c_c=2.0)
    sb, sd = M.share(b, "impacting (all)")[0], M.share(d, "impacting (all)")[0]
    return Measure(sb == 0 and sd == 0, f"impacting share: bilinear k_c = 20 {_pct(sb)}, "
                   f"Duffing c_c = 2 {_pct(sd)} (plane, t0 = 0)", ("fig14ab", "fig14cd"))




_fig06c_names = CHECKS["fig06c_names"]


@check("fig06c_names")
def fig06c_names(st, runs):
    """Figure 6(c)'s names, and whether the phase-sign explanation is consistent with
    figure 7 (whose destruction order tells the two mixed combinations apart)."""
    m = _fig06c_names(st, runs)
    ds = runs("fig05")
    a, b = (M.dcrit_at(ds, n, 5 * PI / 8) for n in ("L1^1 R1-0^2", "L1^2 R1-0^1"))
    caveat = (f"at figure 7's phi = 5pi/8 softimpact's sign puts L1^1 R1-0^2's line "
              f"({a:.2f}) above L1^2 R1-0^1's ({b:.2f}), as the study's figure 7 does "
              "(S31, S33); a flipped sign would swap them, so no single phase convention "
              "explains both figures")
    for alt in m.alternatives:
        if "sign flipped" in alt.label:
            alt.caveat = caveat
    return m
