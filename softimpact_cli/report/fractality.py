"""What a fractality result says (``softimpact info``): per plane, S_b and S_bb at a few
box sizes with the ln 2 criterion, alpha and D with their fit intervals, the Wada
verdict."""

from __future__ import annotations

import math

import numpy as np

from ..analysis.attributes import attribute_list
from ..config.axes import GRID_AXES

LN2 = math.log(2.0)


def _num(value) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def ln2_verdict(sizes, sbb, n_basins: int, side: int) -> str:
    """What S_bb says of the boundary by the ln 2 criterion (Daza et al. 2016), from its
    values ``sbb`` at the box sizes ``sizes`` (cells) on a plane of ``side`` cells.

    The criterion is sufficient only for boxes small beside the boundary's features: a
    box over a junction of three smooth boundaries holds three basins and can exceed
    ln 2 too, so a verdict that rests on boxes over a tenth of the plane says so."""
    if n_basins < 2:
        return "no boundary"
    if n_basins == 2:  # one box of two labels has entropy <= ln 2
        return "undecided (two basins: S_bb <= ln 2 always)"
    holds = [int(n) for n, v in zip(sizes, sbb, strict=True) if math.isfinite(v) and v > LN2]
    if not holds:
        return "undecided (S_bb <= ln 2 at every box size)"
    runs: list[list[int]] = []
    for n in holds:  # "2-5, 9": runs of consecutive box sizes
        if runs and n == runs[-1][-1] + 1:
            runs[-1].append(n)
        else:
            runs.append([n])
    where = ", ".join(f"{r[0]}-{r[-1]}" if len(r) > 1 else str(r[0]) for r in runs)
    if min(holds) * 10 > side:
        return (f"inconclusive (S_bb > ln 2 only at n = {where}, boxes over a tenth of the "
                "plane, as junctions of smooth boundaries give too)")
    return f"fractal (S_bb > ln 2 at n = {where})"


def fit_note(p) -> str | None:
    """Why alpha of one plane (a row of the result) is to be read with care, or None."""
    others = (1.0 - float(p["label_share"].max())) * p.sizes["row"] * p.sizes["col"]
    if int(p["n_basins"]) >= 2 and others < 50:
        return ("the basins besides the largest hold fewer than 50 cells: the boundary is "
                "a few points, not a curve")
    f = p["uncertain_fraction"].values[p["in_fit"].values]
    if f.size and f.max() > 0.5:
        return ("saturated: over half the plane is uncertain at the largest radius, so "
                "alpha is biased low (D high); a finer plane or smaller radii are needed")
    halves = (float(p["alpha_small"]), float(p["alpha_large"]))
    if all(math.isfinite(h) for h in halves) and abs(halves[0] - halves[1]) > 0.2:
        return "curved: the two halves of the radii differ by more than 0.2"
    return None


def fractality_summary(ds) -> dict:
    """{"fractality": [one dict per plane]}: the measures with their intervals."""
    sizes = [int(n) for n in ds["box_size"].values]
    points = []
    for i in range(ds.sizes["point"]):
        p = ds.isel(point=i)
        where = {a: float(p[a]) for a in GRID_AXES if a in p.coords}
        n_basins = int(p["n_basins"])
        sbb = p["S_bb"].values
        shares = {str(name): float(s) for name, s in zip(ds["label_name"].values,
                                                         p["label_share"].values, strict=True)
                  if s > 0}
        points.append({
            **where,
            "n_basins": n_basins, "label_shares": shares,
            "S_b": {str(n): _num(v) for n, v in zip(sizes, p["S_b"].values, strict=True)},
            "S_bb": {str(n): _num(v) for n, v in zip(sizes, sbb, strict=True)},
            "S_bb_max": _num(np.nanmax(sbb)) if np.isfinite(sbb).any() else None,
            "ln2_criterion": ln2_verdict(sizes, sbb, n_basins,
                                         min(ds.sizes["row"], ds.sizes["col"])),
            "alpha": _num(p["alpha"]), "alpha_stderr": _num(p["alpha_stderr"]),
            "alpha_ci95": [_num(p["alpha_ci_low"]), _num(p["alpha_ci_high"])],
            "alpha_halves": [_num(p["alpha_small"]), _num(p["alpha_large"])],
            "dimension": _num(p["dimension"]),
            "dimension_ci95": [_num(p["dimension_ci_low"]), _num(p["dimension_ci_high"])],
            "fit_radii": [_num(p["fit_radius_min"]), _num(p["fit_radius_max"])],
            "fit_note": fit_note(p),
            "wada": str(p["verdict"].values),
            "wada_radius": int(p["wada_radius_found"]),
            "wada_fraction": _num(p["wada_fraction"].values[-1]),
            "wada_mismatch": _num(p["mismatch"].values[-1]),
        })
    return {"fractality": points}


def _interval(pair) -> str:
    lo, hi = pair
    return "-" if lo is None or hi is None else f"[{lo:.3f}, {hi:.3f}]"


def _f(value, spec: str = ".3f") -> str:
    return "-" if value is None else format(value, spec)


def fractality_lines(ds) -> list[str]:
    """The table ``info`` prints after the result's keys."""
    summary = fractality_summary(ds)["fractality"]
    rows, cols = attribute_list(ds.attrs, "plane_shape", ("?", "?"))
    sizes = [int(n) for n in ds["box_size"].values]
    shown = [n for n in (sizes[0], 5, 10, sizes[-1]) if n in sizes]
    shown = sorted(set(shown))
    cell = [str(c) for c in attribute_list(ds.attrs, "cell_size")]
    out = [f"fractality of {len(summary)} plane(s) of {rows} x {cols} cells "
           f"({' '.join(attribute_list(ds.attrs, 'plane_axes'))}; cell "
           f"{' x '.join(cell)}); every label its own basin",
           f"  S_b, S_bb at box sizes {', '.join(map(str, shown))} cells (all of "
           f"{sizes[0]}..{sizes[-1]} stored); alpha from f(r) over r = "
           f"{' '.join(map(str, attribute_list(ds.attrs, 'radii')))} cells (95% fit "
           f"interval); Wada by merging up to "
           f"r = {ds.attrs.get('wada_max_radius')} cells, tol {ds.attrs.get('wada_tol')}"]
    for p in summary:
        axes = GRID_AXES if int(ds.attrs.get("bodies", 2)) == 2 \
            else ("t0",)  # one body: no coupling
        where = ", ".join(f"{a}={p[a]:.6g}" for a in axes if a in p)
        shares = ", ".join(f"{k} {v:.3f}" for k, v in p["label_shares"].items())
        out.append(f"  {where}: {p['n_basins']} basin{'s' * (p['n_basins'] != 1)} "
                   f"({shares})")
        out.append("    S_b  " + "  ".join(f"n={n}: {_f(p['S_b'][str(n)])}" for n in shown))
        out.append("    S_bb " + "  ".join(f"n={n}: {_f(p['S_bb'][str(n)])}" for n in shown)
                   + f"  -> {p['ln2_criterion']}")
        if p["alpha"] is None:
            out.append("    alpha -: no uncertain cell at any radius (no boundary)")
        else:
            out.append(f"    alpha {_f(p['alpha'])} {_interval(p['alpha_ci95'])} (halves "
                       f"{_f(p['alpha_halves'][0])}, {_f(p['alpha_halves'][1])}; r "
                       f"{_f(p['fit_radii'][0], '.0f')}..{_f(p['fit_radii'][1], '.0f')}); "
                       f"D = {_f(p['dimension'])} {_interval(p['dimension_ci95'])}")
        if p["fit_note"]:
            out.append(f"    note: {p['fit_note']}")
        wada = p["wada"]
        if wada != "n/a":
            at = f" at r = {p['wada_radius']}" if p["wada_radius"] > 0 else ""
            wada += (f"{at}; {_f(p['wada_fraction'])} of boundary cells on every merged "
                     f"boundary, mismatch {_f(p['wada_mismatch'])} (r = "
                     f"{ds.attrs.get('wada_max_radius')})")
        else:
            wada += " (fewer than three basins)"
        out.append(f"    Wada: {wada}")
    return out
