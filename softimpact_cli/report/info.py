"""What a result file holds, as a dict (``softimpact info``)."""

from __future__ import annotations

import math

import numpy as np

from ..analysis.attributes import attribute_list
from ..analysis.catalogue import search_shares
from ..analysis.stability import basin_stability
from ..config.axes import COUPLING_AXES
from ..kernels import method_traits
from ..kernels.codes import (
    BASE_WIDTH,
    CLASSIFIED_BY,
    NONPERIODIC_BASES,
    STATUS_TABLE,
    UNRESOLVED_LABEL,
)
from ..sweep.result import grid_axes, grid_dims, grid_point  # noqa: F401  (named here too)
from .nonperiodic import nonperiodic_summary
from .verification import verification_summary

SUMMARY_KEYS = (
    "n", "n_chunks", "plan", "executor", "catalogue_source", "t0_mode",
    "analysis", "model", "bodies", "parameters", "outcome", "label", "status_message",
    "classified_by", "second_stage", "period",
    "periods_used", "contacts_on_orbit", "max_penetration", "impacting", "t0",
    "rigid_impacts", "rigid_chatter_sequences", "rigid_sticking_phases", "rigid_sticking_time",
    "integrator_resolved_method", "integrator_rtol", "integrator_atol",
    "integrator_steps_per_period", "integrator_locate_switches", "wall_s", "complete",
    "scene_source", "scene_sha256", "softimpact_version", "started", "finished", "machine",
)


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, float) and not np.isfinite(value):
        return None
    return value


def _first_method(ds) -> str:
    """What the steps that are not Rodas4's are: the explicit pair's, or the exact flow's."""
    exact = method_traits(str(ds.attrs.get("integrator_resolved_method", ""))).closed_form
    return "exact flow" if exact else "explicit"


def describe(ds, kind=None) -> dict:
    """Summary of a result dataset: analysis, outcome, timings, provenance, and the part
    of ``kind`` (its AnalysisKind: ``kinds.results.describe`` passes the result's own)."""
    out = {k: _plain(ds.attrs[k]) for k in SUMMARY_KEYS if k in ds.attrs}
    out.update({k: _plain(v) for k, v in ds.attrs.items() if k.startswith("check_")})
    first = _first_method(ds)
    steps = {phase: {first: int(ds.attrs[f"{phase}_steps"])
                     - int(ds.attrs[f"{phase}_stiff_steps"]),
                     "stiff": int(ds.attrs[f"{phase}_stiff_steps"]),
                     "method_switches": int(ds.attrs[f"{phase}_method_switches"])}
             for phase in ("record", "classify") if f"{phase}_stiff_steps" in ds.attrs}
    if steps:  # a trajectory: steps of the explicit pair and of Rodas4 ('auto' mixes them)
        out["steps_by_method"] = steps
    if "orbit" in ds:
        out["orbit"] = _plain(ds["orbit"].values)
        out["variables"] = [str(v) for v in ds["variable"].values]
    if "destroyed_at" in ds:
        out["branches"] = {
            str(name): {"destroyed_at": _plain(float(ds["destroyed_at"].values[i])),
                        "falls_to": str(ds["falls_to"].values[i]) or None,
                        "impacting_range": [_plain(float(v))
                                            for v in ds["impacting_range"].values[i]]}
            for i, name in enumerate(ds["branch_name"].values)}
    if "d_crit" in ds:
        out["d_crit"] = dcrit_summary(ds)
    if kind is not None and kind.summary is not None:
        out.update(kind.summary(ds))
    if "nonperiodic_code" in ds:  # the second stage's attractors (report/nonperiodic.py)

        out["nonperiodic"] = nonperiodic_summary(ds)
    verification = verification_summary(ds.attrs)
    if verification is not None:
        out["verification"] = verification
    out["scene"] = ds.attrs.get("scene_text", "")
    return {k: _plain(v) for k, v in out.items()}


def dcrit_summary(ds) -> dict:
    """{combination: {"phi": [...], "d_crit": [...]}} of a dcrit result, or of the d_crit
    curves a map stores (dims dcrit_combination, dcrit_phi: named after the catalogue's
    combinations, in the order the critical distances were computed). A chain's
    (dims stop, combination, point): one row per stop and product, "stop s: name"."""
    if "stop" in ds["d_crit"].dims:
        axis, points = str(ds.attrs.get("axis", "")), [float(p) for p in ds["point"].values]
        names = [str(n) for n in ds["combination_label"].values]
        return {f"stop {int(s)}: {name}": {"phi": points, "axis": axis,
                                           "d_crit": [_plain(float(v)) for v in row]}
                for s, per_stop in zip(ds["stop"].values, ds["d_crit"].values, strict=True)
                for name, row in zip(names, per_stop, strict=True)}
    if "combination_label" in ds:
        names, phi = [str(n) for n in ds["combination_label"].values], ds["phi"].values
        values = ds["d_crit"].transpose("combination", "phi").values
    else:
        values = ds["d_crit"].transpose("dcrit_combination", "dcrit_phi").values
        phi = ds["dcrit_phi"].values
        names = [str(n) for n in ds["combination_name"].values] \
            if "combination_name" in ds and ds.sizes["combination"] == len(values) \
            else [f"combination {i}" for i in range(len(values))]
    return {name: {"phi": [float(p) for p in phi], "d_crit": [_plain(float(v)) for v in row]}
            for name, row in zip(names, values, strict=True)}


def catalogue_summary(ds) -> dict:
    """Attractors (number, period, amplitude, multipliers, share of the one-body search,
    points) and combinations."""
    attractors = []
    numbers = ds["attractor_number"].values if "attractor_number" in ds \
        else ds["attractor"].values  # a chain's: each body's own numbers
    for i, number in enumerate(numbers):
        p = int(ds["attractor_period"].values[i])
        re, im = ds["multiplier_re"].values[i], ds["multiplier_im"].values[i]
        attractors.append({
            "number": int(number),
            "name": str(ds["attractor_name"].values[i]),
            "period": p,
            "amplitude": float(ds["attractor_amplitude"].values[i]),
            "multipliers": [[float(a), float(b)] for a, b in zip(re, im, strict=True)
                            if np.isfinite(a)],
            "search_share": float(search_shares(ds)[i]),
            "residual": float(ds["attractor_residual"].values[i]),
            "points": ds["attractor_points"].values[i, :p].tolist(),
        })
    out = {"attractors": attractors,
           "counts": {k[6:]: int(v) for k, v in ds.attrs.items() if k.startswith("count_")}}
    if "combination_name" in ds:
        out["combinations"] = [str(n) for n in ds["combination_name"].values]
    if "combination_survives" in ds:  # a chain's: each stop's critical values
        out["critical"] = {str(n): [float(v) for v in row] for n, row in zip(
            ds["combination_name"].values, ds["combination_critical"].values, strict=True)}
        out.update(surviving_summary(ds))
    return out


def surviving_summary(ds) -> dict:
    """A chain's surviving products: ``stops`` (each stop's value) and ``surviving``
    (names) at its one point, or for a sweep of several grid points
    ``surviving_per_point``: [{the point's values, "stops", "surviving"}, ...] (a sweep
    stores each point's own, ``sweep.result.point_survival``)."""
    names = [str(n) for n in ds["combination_name"].values]
    survives, stops = ds["combination_survives"], ds["stop_value"]
    if survives.ndim == 1 or survives.size == len(names):  # one point
        alive = np.ravel(survives.values)
        return {"stops": [float(v) for v in np.ravel(stops.values)],
                "surviving": [n for n, ok in zip(names, alive, strict=True) if ok]}
    dims = grid_dims(ds)
    survives = survives.transpose(*dims, "combination").values
    stops = stops.transpose(*dims, "stop").values
    points = []
    for index in np.ndindex(*survives.shape[:-1]):
        points.append({**grid_point(ds, index), "stops": [float(v) for v in stops[index]],
                       "surviving": [n for n, ok in zip(names, survives[index], strict=True)
                                     if ok]})
    return {"surviving_per_point": points}


def format_catalogue(ds) -> str:
    """A plain-text table of a catalogue result."""
    summary = catalogue_summary(ds)
    lines = [f"{'attractor':10s} {'period':>6s} {'amplitude':>10s} {'|multipliers|':>20s} "
             f"{'search':>7s} {'residual':>9s}"]
    for a in summary["attractors"]:
        mods = ", ".join(f"{np.hypot(*m):.4f}" for m in a["multipliers"])
        lines.append(f"{a['name']:10s} {a['period']:6d} {a['amplitude']:10.4f} {mods:>20s} "
                     f"{a['search_share']:7.3f} {a['residual']:9.1e}")
    counts = summary["counts"]
    if counts:  # a sweep's stored catalogue keeps no sample counts
        lines.append("samples: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
    if "combinations" in summary:
        names = summary["combinations"]
        lines.append(f"combinations ({len(names)}): " + ", ".join(names))
    if "critical" in summary and "surviving" in summary:  # a chain's products at one point
        stops = summary["stops"]
        width = max(len(n) for n in summary["critical"]) if summary["critical"] else 10
        lines.append(f"{'product':{width}s} " + " ".join(
            f"{f'stop {s} ({v:g})':>14s}" for s, v in enumerate(stops, 1)) + "  survives")
        for name, row in summary["critical"].items():
            lines.append(f"{name:{width}s} " + " ".join(f"{v:14.6f}" for v in row)
                         + f"  {'yes' if name in summary['surviving'] else 'no'}")
        lines.append(f"surviving ({len(summary['surviving'])}): "
                     + (", ".join(summary["surviving"]) or "none"))
    elif "critical" in summary:  # a sweep's: the critical values, each point's survivors
        width = max(len(n) for n in summary["critical"]) if summary["critical"] else 10
        n_stops = len(next(iter(summary["critical"].values()), []))
        lines.append(f"{'product':{width}s} " + " ".join(
            f"{f'stop {s}':>14s}" for s in range(1, n_stops + 1)))
        for name, row in summary["critical"].items():
            lines.append(f"{name:{width}s} " + " ".join(f"{v:14.6f}" for v in row))
        for point in summary["surviving_per_point"]:
            where = ", ".join(f"{k}={v:g}" for k, v in point.items()
                              if k not in ("stops", "surviving") and isinstance(v, float))
            lines.append(f"surviving at {where} ({len(point['surviving'])}): "
                         + (", ".join(point["surviving"]) or "none"))
    return "\n".join(lines)


def sweep_summary(ds) -> dict:
    """Label table, per-grid-point counts and fractions, and status totals of a sweep."""
    codes = [int(c) for c in ds["label_code"].values]
    names = [str(n) for n in ds["label_name"].values]
    table = dict(zip(codes, names, strict=True))
    ic_dims = attribute_list(ds.attrs, "ic_dims")
    label = ds["label"].transpose(*grid_dims(ds), *ic_dims).values
    grid_shape = label.shape[: len(grid_dims(ds))]
    flat = label.reshape(int(np.prod(grid_shape)), -1)
    points = []
    for k, index in enumerate(np.ndindex(*grid_shape)):
        values, counts = np.unique(flat[k], return_counts=True)
        n = flat.shape[1]
        point = grid_point(ds, index)
        point["counts"] = {table[int(v)]: int(c) for v, c in zip(values, counts, strict=True)}
        point["fractions"] = {table[int(v)]: c / n for v, c in zip(values, counts, strict=True)}
        points.append(point)
    status = {}
    if "status" in ds:  # (a result made by hand may hold labels only: no totals then)
        totals = {"converged": 0, "unresolved": 0, "diverged": 0}
        for code, count in zip(*np.unique(ds["status"].values, return_counts=True),
                               strict=True):
            totals[STATUS_TABLE[int(code)][0]] += int(count)
        status["status"] = totals
    out = {}
    named = unresolved_then_named(ds) if "status" in ds else None
    if named is not None:
        out["status_unresolved"] = named
    if "predicted_count" in ds:
        for k, index in enumerate(np.ndindex(*grid_shape)):
            sel = dict(zip(grid_dims(ds), index, strict=True))
            points[k]["predicted"] = int(ds["predicted_count"].isel(sel).values)
            points[k]["found"] = int(ds["found_count"].isel(sel).values)
            points[k]["found_nonimpacting"] = int(ds["found_nonimpacting"].isel(sel).values)
    if "captured" in ds:  # how trajectories were classified, and by which method
        how = ds["captured"].values
        out["classified_by"] = {name: int(np.sum(how == code))
                                for code, name in CLASSIFIED_BY.items()}
    if "steps" in ds:
        stiff = int(ds["stiff_steps"].values.sum())
        out["steps_by_method"] = {_first_method(ds): int(ds["steps"].values.sum()) - stiff,
                                  "stiff": stiff}
    return {**out, "complete": bool(int(ds.attrs.get("complete", 0))),
            "n": int(ds.attrs.get("n", label.size)),
            "wall_s": float(ds.attrs.get("wall_s", np.nan)),
            "labels": {str(c): n for c, n in table.items()},
            "points": points, **status}


def unresolved_then_named(ds) -> dict | None:
    """How the trajectories whose first pass ended unresolved (status) ended after the
    second stage: {"named not periodic": n, "left unresolved": m}, or None when the
    second stage named none (the status line then says all). A recurrent set keeps the
    first pass's status; its label is the attractor's."""
    status, label = ds["status"].values.ravel(), ds["label"].values.ravel()
    first_unresolved = np.isin(status, [c for c, (what, _) in STATUS_TABLE.items()
                                        if what == "unresolved"])
    base = np.where(label > 0, label // BASE_WIDTH * BASE_WIDTH, -1)
    named = first_unresolved & np.isin(base, list(NONPERIODIC_BASES.values()))
    if not named.any():
        return None
    return {"named not periodic": int(named.sum()),
            "left unresolved": int(np.sum(first_unresolved & (label == UNRESOLVED_LABEL)))}


def incomplete_summary(header, done: int) -> dict:
    """What an unfinished sweep file says: its plan and how far it got."""
    total = int(header.attrs.get("n_chunks", 0))
    return {"complete": False, "analysis": header.attrs.get("analysis"),
            "n": int(header.attrs.get("n", 0)), "plan": header.attrs.get("plan"),
            "progress": {"chunks_done": done, "chunks": total,
                         "fraction": done / total if total else 0.0},
            "scene_source": header.attrs.get("scene_source"),
            "scene": header.attrs.get("scene_text", "")}


def stability_summary(ds) -> list[dict]:
    """Per grid point: share and 95% Wilson interval of every group."""
    bs = basin_stability(ds)
    dims = grid_dims(ds)
    share = bs["share"].transpose(*dims, "group").values
    lo = bs["ci_low"].transpose(*dims, "group").values
    hi = bs["ci_high"].transpose(*dims, "group").values
    groups = [str(g) for g in bs["group"].values]
    out = []
    for index in np.ndindex(*share.shape[:-1]):
        point = grid_point(ds, index)
        point["n"] = int(bs.attrs["n"])
        point["shares"] = {g: {"share": float(share[index][j]),
                               "ci95": [float(lo[index][j]), float(hi[index][j])]}
                           for j, g in enumerate(groups)}
        h = [float(bs[k].transpose(*dims).values[index])
             for k in ("entropy", "entropy_ci_low", "entropy_ci_high")]
        point["entropy"] = {"H": h[0], "ci95": h[1:], "units": "nat"}
        out.append(point)
    return out


def compare_shares(plane, stability) -> list[dict]:
    """Plane basin shares beside 4-D basin-stability shares at common parameter points.

    Points match on (d, phi, k_c, c_c) to 1e-9; t0 of both is reported.
    """
    a = {tuple(round(p[k], 9) for k in COUPLING_AXES): p for p in sweep_summary(plane)["points"]}
    rows = []
    for point in stability_summary(stability):
        key = tuple(round(point[k], 9) for k in COUPLING_AXES)
        if key not in a:
            continue
        names = sorted(set(a[key]["fractions"]) | {g for g in point["shares"]
                                                    if "(" not in g})
        rows.append({
            **{k: point[k] for k in COUPLING_AXES},
            "t0_plane": a[key]["t0"], "t0_stability": point["t0"],
            "shares": {n: {"plane": a[key]["fractions"].get(n, 0.0),
                           "stability": point["shares"].get(n, {}).get("share", 0.0),
                           "ci95": point["shares"].get(n, {}).get("ci95")}
                       for n in names},
        })
    return rows


# ------------------------------------------------------------------ design results

def _finite(value):
    """JSON-safe: NaN and infinities become None, recursively."""
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    value = _plain(value)
    return None if isinstance(value, float) and not np.isfinite(value) else value


MARGIN_KEYS = ("relative", "d_to_target", "d_to_boundary", "phi_to_boundary",
               "body_to_boundary")  # a pair's margins, and a chain's (body axes)


def design_axes(ds) -> tuple[str, ...]:
    """The axes of a design result: d, phi, k_c, c_c (a pair) or a chain's parameters."""
    return tuple(str(a) for a in np.atleast_1d(ds.attrs.get("design_axes", COUPLING_AXES)))


def design_point(ds, i: int) -> dict:
    """One evaluated point of a design: parameters, target and impacting shares with 95%
    Wilson intervals, score, margins, and the target's existence and multipliers there."""
    target = str(ds.attrs["target"])
    group = [str(g) for g in ds["group"].values]
    share, lo, hi = (ds[k].values[i] for k in ("share", "ci_low", "ci_high"))
    t, m = group.index(target), group.index("impacting (all)")
    exists = int(ds["target_exists"].values[i])
    mult = ds["multiplier_re"].values[i] + 1j * ds["multiplier_im"].values[i]
    return _finite({
        **{a: float(ds[f"point_{a}"].values[i]) for a in design_axes(ds)},
        "n": int(ds["n_samples"].values[i]),
        "share": float(share[t]), "ci95": [float(lo[t]), float(hi[t])],
        "impacting_share": float(share[m]), "impacting_ci95": [float(lo[m]), float(hi[m])],
        "unresolved_share": float(share[group.index("unresolved")]) if "unresolved" in group
        else 0.0,
        "score": float(ds["score"].values[i]),
        "margin": {k: float(ds[f"margin_{k}"].values[i])
                   for k in MARGIN_KEYS if f"margin_{k}" in ds},
        "target_exists": None if exists < 0 else bool(exists),
        "multipliers": [[float(z.real), float(z.imag)] for z in mult] if exists == 1 else None,
        "shares": {g: float(share[j]) for j, g in enumerate(group) if share[j] > 0},
    })


def design_summary(ds) -> dict:
    """The pick, the runners-up, the reference and the perturbed points of a design."""
    role = [str(r) for r in ds["role"].values]
    rank = ds["rank"].values
    runners = sorted((i for i, r in enumerate(role) if r == "runner-up"), key=lambda i: rank[i])
    return {
        "target": str(ds.attrs["target"]),
        "best": design_point(ds, role.index("best")),
        "runners_up": [design_point(ds, i) for i in runners],
        "reference": design_point(ds, role.index("reference")) if "reference" in role
        else None,
        "robustness": [{"parameter": str(ds["perturbed_axis"].values[i]),
                        "step": int(ds["perturbed_step"].values[i]), **design_point(ds, i)}
                       for i, r in enumerate(role) if r == "perturbed"],
        "screened": sum(r in ("best", "runner-up", "screened") for r in role),
        "screen_n": int(ds.attrs["screen_n"]), "robust_n": int(ds.attrs["robust_n"]),
        "fatal_shock": {role: {"magnitude": float(ds.attrs[f"fatal_shock_{role}"]),
                               "time": ds.attrs.get(f"fatal_shock_{role}_time"),
                               "destination": ds.attrs.get(f"fatal_shock_{role}_destination")}
                        for role in ("best", "reference")
                        if f"fatal_shock_{role}" in ds.attrs},
    }


def format_design(ds) -> str:
    """A plain-text table of a design result."""
    s = design_summary(ds)
    head = (f"design for {s['target']}: {s['screened']} candidates screened on "
            f"{s['screen_n']} samples; shares with 95% Wilson intervals")
    chain = ds.attrs.get("model") == "chain"
    axes = design_axes(ds)
    if chain:  # a chain's axes by name, each as wide as its name
        widths = {a: max(len(a), 8) for a in axes}
        columns = " ".join(f"{a:>{widths[a]}s}" for a in axes)
    else:
        columns = f"{'d':>8s} {'phi':>8s} {'k_c':>7s} {'c_c':>7s}"
    lines = [head, f"{'':10s} {columns} {'n':>5s} "
                   f"{'target share [95%]':>24s} {'impacting':>9s} {'unresolved':>10s} "
                   f"{'margin':>7s} {'d-d_crit':>8s}"]

    def row(name: str, p: dict) -> str:
        ci = p["ci95"]
        at = (" ".join(f"{p[a]:{widths[a]}.4f}" for a in axes) if chain else
              f"{p['d']:8.4f} {p['phi']:8.4f} {p['k_c']:7.3f} {p['c_c']:7.3f}")
        return (f"{name:10s} {at} "
                f"{p['n']:5d} {p['share']:7.3f} [{ci[0]:.3f}, {ci[1]:.3f}] "
                f"{p['impacting_share']:9.3f} {p['unresolved_share']:10.3f} "
                f"{p['margin']['relative']:7.3f} "
                f"{p['margin']['d_to_target']:8.3f}")

    lines.append(row("best", s["best"]))
    lines += [row(f"runner-up{k + 1}", p) for k, p in enumerate(s["runners_up"])]
    if s["reference"]:
        lines.append(row("reference", s["reference"]))
    if s["best"]["multipliers"]:
        mods = ", ".join(f"{abs(complex(*z)):.4f}" for z in s["best"]["multipliers"])
        lines.append(f"target's Floquet multipliers at the pick: |mu| = {mods}")
    lines.append(f"robustness ({s['robust_n']} samples per point): target share when one "
                 "parameter moves")
    for p in s["robustness"]:
        exists = "exists" if p["target_exists"] else "DESTROYED"
        lines.append(f"  {p['parameter']:>3s} {p['step']:+d} step: {p['parameter']} = "
                     f"{p[p['parameter']]:.4f}  share {p['share']:.3f} "
                     f"[{p['ci95'][0]:.3f}, {p['ci95'][1]:.3f}], impacting "
                     f"{p['impacting_share']:.3f}, unresolved {p['unresolved_share']:.3f}, "
                     f"target {exists}")
    if s["fatal_shock"]:
        lines.append(f"minimal fatal shock of the target (an upper bound; "
                     f"{ds.attrs.get('fatal_shock_settings', '')}):")
        for role, f in s["fatal_shock"].items():
            name = "pick" if role == "best" else role
            if f["destination"] is not None:
                text = f"{f['magnitude']:.4g} at t = {float(f['time']):.4g} -> " \
                       f"{f['destination']}"
            elif math.isnan(f["magnitude"]):
                text = "target absent"
            else:
                text = "none up to the largest shock scanned"
            lines.append(f"  {name}: {text}")
    return "\n".join(lines)
