"""Control design on a chain: choose any of its parameters so that only the wanted
non-impacting product survives (``analysis.design`` is the pair's form; this one follows it
step by step, over the chain's parameters by name).

While no stop engages, the bodies are independent oscillators: a non-impacting solution is
a *product* of one attractor per body (``chain_dcrit``), and it is a solution of the chain
exactly when every stop lies beyond its critical value on it (``chain_catalogue.survival``).
The design axes (``[analysis] bounds``, by the chain's names) are of three sorts:

- **stop positions** (``stop.s.d``, ``stop.s.wall``): they move the stops, not the
  products; the region is exact in them (each product's critical values are known);
- **body parameters** (``phi.2``, ``F.1``, ``w`` ...: every parameter but a stop's): they
  change the products themselves, so the catalogue is computed on a grid of their values
  (``grid_points`` per axis over its bounds, every combination of them);
- **stop laws** (``stop.s.k_c``, ``stop.s.c_c``, ...): no non-impacting solution feels them;
  only the basin stability does.

1. **Region.** At each body grid point g, product P survives at stop values v iff
   ``sign_s (v_s - crit_s(P, g)) > 0`` for every stop s (sign -1 for a left wall); the
   region is where the target T is the only survivor.
2. **Margins** of a point. Along a stop axis a (stop s): the target dies when v_s crosses
   crit_s(T) (``to_target``), and another product P revives when v_s crosses crit_s(P) if
   s is the only stop that kills P there; ``d_to_target`` and ``d_to_boundary`` are the
   smallest of these over the stop axes (the pair's d margins, in the stops' units). Along
   a body axis: the distance to the nearest grid point outside the region on that axis's
   line, less half a step (the line's span when none is outside), relative to pi for a
   phase and to the value otherwise (``body_to_boundary``). ``relative`` is the smallest
   of every stop axis's distance over its value and every body axis's relative distance.
3. **Candidates** inside region and bounds with ``relative >= min_margin``, from a Halton
   set (seed-rotated) over (body grid point, every other axis within its bounds).
4. **Screening, refinement, verification, robustness**: as the pair's (``design.scores``,
   ``design.ranking``); a perturbed axis moves by +-k perturbation of its value (a phase:
   of pi).
5. **The target at a point**: it exists when it survives there (its catalogue's critical
   values at the point's body parameters); its Floquet multipliers over the joint period q
   are the union of each body's raised to q / p_i (no stop acts on the linearisation of a
   non-impacting orbit: the pair's argument, body by body).

The caller gives ``catalogue_at(point)`` (the chain's catalogue at the scene's values with
the point's; cached) and ``evaluate(points, start, stop)`` (label codes, as for the pair).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..systems import System
from .chain_catalogue import ChainCatalogue
from .chain_dcrit import chain_model, stop_coefficients
from .design import NoRegion, group_counts, halton, rank_codes, scores
from .stability import wilson_interval

PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53)
MARGINS = ("relative", "d_to_target", "d_to_boundary", "body_to_boundary")
MAP_STEPS = 241  # raster of a stop axis in the region map


def axis_sort(system: System, axis: str) -> str:
    """"stop" (a stop's gap or wall), "law" (a stop's law parameter) or "body"."""
    if not axis.startswith("stop."):
        return "body"
    return "stop" if axis.rsplit(".", 1)[1] in ("d", "wall") else "law"


def axis_scale(axis: str, value: float) -> float:
    """What a relative change of ``axis`` is relative to: pi for a phase, else |value|."""
    return float(np.pi) if axis.startswith("phi.") else max(abs(value), 1e-12)


@dataclass(frozen=True)
class ChainRegion:
    """The products' critical values on the body grid, and the target-only region.

    body_axes : (B,) names; grid : (G, B) body values, C order over ``shape``;
    names : (C,) products; critical : (G, C, S), NaN where a product is absent;
    target : index in names; stop_axes : {axis: stop index (0-based)};
    signs : (S,) +1 (between bodies, right wall) or -1 (left wall);
    stops : (S,) the scene's stop values (gap or wall).
    """

    body_axes: tuple[str, ...]
    shape: tuple[int, ...]
    grid: np.ndarray
    names: tuple[str, ...]
    critical: np.ndarray
    target: int
    stop_axes: dict
    signs: np.ndarray
    stops: np.ndarray

    def stop_vector(self, point: dict) -> np.ndarray:
        """(S,) the stop values at ``point`` (the scene's where it gives none)."""
        v = self.stops.copy()
        for axis, s in self.stop_axes.items():
            if axis in point:
                v[s] = point[axis]
        return v

    def survivors(self, critical: np.ndarray, stops: np.ndarray) -> np.ndarray:
        """(C,) bool: which products survive at ``stops`` given ``critical`` (C, S)."""
        with np.errstate(invalid="ignore"):
            return np.all(self.signs * (stops - critical) > 0.0, axis=1)

    def alone(self, critical: np.ndarray, stops: np.ndarray) -> bool:
        alive = self.survivors(critical, stops)
        return bool(alive[self.target] and alive.sum() == 1)

    def nearest(self, point: dict) -> int:
        """The flat index of the body grid point nearest to ``point``, axis by axis."""
        index = []
        for b, axis in enumerate(self.body_axes):
            values = np.unique(self.grid[:, b])
            index.append(int(np.argmin(np.abs(values - point[axis]))))
        return int(np.ravel_multi_index(index, self.shape)) if index else 0

    def stop_margins(self, critical: np.ndarray, stops: np.ndarray
                     ) -> tuple[float, float, float]:
        """(d_to_target, d_to_boundary, relative) over the stop axes (module docstring);
        NaN, NaN, inf without stop axes."""
        if not self.stop_axes:
            return np.nan, np.nan, np.inf
        with np.errstate(invalid="ignore"):
            killed = self.signs * (stops - critical) <= 0.0  # (C, S)
        present = np.isfinite(critical).all(axis=1)
        to_target, to_boundary, relative = [], [], []
        for s in self.stop_axes.values():
            t = self.signs[s] * (stops[s] - critical[self.target, s])
            revive = [self.signs[s] * (critical[p, s] - stops[s])
                      for p in range(len(self.names))
                      if p != self.target and present[p] and killed[p, s]
                      and killed[p].sum() == 1]
            edge = min([t, *revive])
            to_target.append(t)
            to_boundary.append(edge)
            relative.append(edge / max(abs(stops[s]), 1e-12))
        return float(min(to_target)), float(min(to_boundary)), float(min(relative))

    def body_margin(self, point: dict, stops: np.ndarray) -> float:
        """The smallest relative distance along a body axis from ``point`` to the grid
        points outside the region (module docstring); inf without swept body axes."""
        out = np.inf
        if not self.body_axes:
            return out
        at = np.unravel_index(self.nearest(point), self.shape)
        for b, axis in enumerate(self.body_axes):
            if self.shape[b] < 2:
                continue
            line = [int(np.ravel_multi_index((*at[:b], k, *at[b + 1:]), self.shape))
                    for k in range(self.shape[b])]
            values = self.grid[line, b]
            outside = [values[k] for k, g in enumerate(line)
                       if not self.alone(self.critical[g], stops)]
            step = float(values[1] - values[0])
            gap = (float(np.min(np.abs(np.array(outside) - point[axis]))) - 0.5 * step
                   if outside else float(values[-1] - values[0]))
            out = min(out, max(gap, 0.0) / axis_scale(axis, point[axis]))
        return out

    def margins(self, critical: np.ndarray, point: dict) -> dict[str, float]:
        """Margins of ``point`` given the exact critical values (C, S) at its body values."""
        stops = self.stop_vector(point)
        if not self.alone(critical, stops):
            to_target, to_boundary, _ = self.stop_margins(critical, stops)
            return {"relative": 0.0, "d_to_target": to_target,
                    "d_to_boundary": min(to_boundary, 0.0), "body_to_boundary": 0.0}
        to_target, to_boundary, relative = self.stop_margins(critical, stops)
        body = self.body_margin(point, stops)
        rel = min(relative, body)
        return {"relative": float(rel if np.isfinite(rel) else 1.0),
                "d_to_target": to_target, "d_to_boundary": to_boundary,
                "body_to_boundary": float(body if np.isfinite(body) else np.nan)}


def critical_of(cat: ChainCatalogue, names, n_stops: int) -> np.ndarray:
    """(len(names), S) the catalogue's critical values in the order of ``names`` (NaN where
    it has no such product)."""
    out = np.full((len(names), n_stops), np.nan)
    index = {p.name: k for k, p in enumerate(cat.products)}
    for j, name in enumerate(names):
        if name in index:
            out[j] = cat.critical[index[name]]
    return out


def body_grid(bounds: dict, body_axes, points: int) -> tuple[tuple[int, ...], np.ndarray]:
    """(shape, (G, B) values): ``points`` values over each body axis's bounds (one when
    its low and high are equal), every combination, C order."""
    lines = [np.linspace(*bounds[a], points) if bounds[a][0] < bounds[a][1]
             else np.array([bounds[a][0]]) for a in body_axes]
    shape = tuple(len(line) for line in lines)
    points = list(itertools.product(*lines))  # one empty point without body axes
    grid = np.array(points, dtype=float).reshape(len(points), len(body_axes))
    return shape, grid


def build_region(system: System, values: dict, settings, catalogue_at,
                 progress=lambda s: None) -> ChainRegion:
    """The region on the body grid (``catalogue_at(point) -> ChainCatalogue``)."""
    axes = tuple(settings.bounds)
    body_axes = tuple(a for a in axes if axis_sort(system, a) == "body")
    model = chain_model(system)
    stop_axes = {a: int(a.split(".")[1]) - 1 for a in axes if axis_sort(system, a) == "stop"}
    signs = np.array([stop_coefficients(system, s)[1]
                      for s in range(1, len(model.stops) + 1)])
    stops = np.array([float(values[f"stop.{s}.{'wall' if st.wall else 'd'}"])
                      for s, st in enumerate(model.stops, 1)])
    shape, grid = body_grid(settings.bounds, body_axes, settings.grid_points)
    progress(f"the chain's catalogue at {len(grid)} body grid points")
    cats = [catalogue_at(dict(zip(body_axes, g, strict=True))) for g in grid]
    names = tuple(dict.fromkeys(n for c in cats for n in c.names))
    if settings.target not in names:
        raise NoRegion(f"{settings.target!r} is not a product of the chain's catalogue "
                       f"({', '.join(names) or 'none found'})")
    critical = np.stack([critical_of(c, names, len(model.stops)) for c in cats])
    return ChainRegion(body_axes, shape, grid, names, critical, names.index(settings.target),
                       stop_axes, signs, stops)


def candidate_points(region: ChainRegion, system: System, bounds: dict, count: int,
                     min_margin: float, seed: int) -> list[dict]:
    """Up to ``count`` points inside region and bounds with relative margin >=
    ``min_margin``, from a rotated Halton set; [] when none is found."""
    axes = tuple(bounds)
    free = [a for a in axes if a not in region.body_axes]
    dims = 1 + len(free)
    shift = np.random.default_rng(seed).uniform(size=dims)
    out: list[dict] = []
    for i in range(1, 256 * count + 1):
        u = (np.array([halton(i, PRIMES[k % len(PRIMES)]) for k in range(dims)]) + shift) % 1
        g = min(int(u[0] * len(region.grid)), len(region.grid) - 1)
        point = dict(zip(region.body_axes, map(float, region.grid[g]), strict=True))
        for k, a in enumerate(free, 1):
            lo, hi = bounds[a]
            point[a] = float(lo + u[k] * (hi - lo))
        point = {a: point[a] for a in axes}
        if region.margins(region.critical[g], point)["relative"] < min_margin:
            continue
        out.append(point)
        if len(out) == count:
            break
    return out


def perturbed_points(pick: dict, relative: float, steps: int, system: System
                     ) -> list[tuple[str, int, dict]]:
    """(axis, step, point) for each design axis moved by +-k steps, k = 1 .. steps: the
    step is ``relative`` times the value (a phase: times pi); a law parameter stays >= 0."""
    out = []
    for axis in pick:
        unit = relative * (np.pi if axis.startswith("phi.") else abs(pick[axis]))
        if unit == 0.0:
            continue
        for k in [*range(-steps, 0), *range(1, steps + 1)]:
            value = pick[axis] + k * unit
            if axis_sort(system, axis) == "law" and value < 0:
                continue
            out.append((axis, k, {**pick, axis: float(value)}))
    return out


def target_at(region: ChainRegion, cat: ChainCatalogue, point: dict, n_dim: int
              ) -> tuple[bool, np.ndarray]:
    """(exists, multipliers (n_dim,) complex) of the target at ``point`` from its
    catalogue ``cat`` there (module docstring, 5); NaN multipliers when it is absent."""
    target = region.names[region.target]
    stops = region.stop_vector(point)
    names = cat.names
    if target not in names:
        return False, np.full(n_dim, np.nan + 0j)
    k = names.index(target)
    alive = region.survivors(cat.critical[k][None, :], stops)[0]
    if not alive:
        return False, np.full(n_dim, np.nan + 0j)
    product = cat.products[k]
    q = product.orbit.shape[0]
    mult = np.concatenate([a.multipliers ** (q // a.period) for a in product.attractors])
    return True, mult[np.lexsort((np.angle(mult), -np.abs(mult)))]


def region_map(region: ChainRegion, system: System, bounds: dict, pick: dict) -> dict:
    """The plane the figure draws: x the first stop axis (else the first body axis), y the
    first body axis (else the next stop axis, else none), the other axes at the pick;
    per cell the number of surviving products and whether the target is among them."""
    axes = list(bounds)
    stop_axes = [a for a in axes if a in region.stop_axes]
    order = stop_axes[:1] + list(region.body_axes[:1]) + stop_axes[1:2] + list(
        region.body_axes[1:2])
    x_axis = order[0] if order else axes[0]
    y_axis = next((a for a in order[1:] if a != x_axis), "")

    def values(axis):
        if not axis:
            return np.array([0.0])
        if axis in region.body_axes:
            return np.unique(region.grid[:, region.body_axes.index(axis)])
        return np.linspace(*bounds[axis], MAP_STEPS if axis == x_axis else MAP_STEPS // 2)

    xs, ys = values(x_axis), values(y_axis)
    count = np.zeros((ys.size, xs.size), dtype=np.int64)
    target = np.zeros((ys.size, xs.size), dtype=np.int8)
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            point = {**pick, x_axis: float(x), **({y_axis: float(y)} if y_axis else {})}
            g = region.nearest(point)
            alive = region.survivors(region.critical[g], region.stop_vector(point))
            count[j, i] = alive.sum()
            target[j, i] = alive[region.target]
    return {"x_axis": x_axis, "y_axis": y_axis, "x": xs, "y": ys, "count": count,
            "target": target}


Evaluate = Callable[[list[dict], int, int], np.ndarray]


def chain_design(system: System, values: dict, settings, n: int, evaluate: Evaluate,
                 catalogue_at: Callable[[dict], ChainCatalogue],
                 label_names: Callable[[], tuple[str, ...]],
                 progress: Callable[[str], None] = lambda s: None) -> xr.Dataset:
    """Run the chain's design (module docstring) for ``settings`` (a ``DesignAnalysis``
    with ``bounds`` over the chain's parameter names) with n samples per verified point;
    ``evaluate`` gives label codes whose names are ``label_names()`` (every name the
    catalogues met so far, in code order). Raises NoRegion when no candidate is found."""
    s = settings
    screen_n = min(s.screen_n, n)
    robust_n = min(s.robust_n or n, n)
    ref = dict(s.reference) if s.reference else None
    region = build_region(system, values, s, catalogue_at, progress)
    candidates = candidate_points(region, system, s.bounds, s.candidates, s.min_margin,
                                  s.seed)
    if not candidates:
        box = ", ".join(f"{a} in [{lo:.4g}, {hi:.4g}]" for a, (lo, hi) in s.bounds.items())
        raise NoRegion(f"{s.target!r} is never the only surviving product with a relative "
                       f"margin >= {s.min_margin:g} for {box}")
    progress(f"screening {len(candidates)} candidates on {screen_n} samples")
    screen = evaluate(candidates, 0, screen_n)
    n_stops = region.critical.shape[2]

    def margins_at(point):
        column = critical_of(catalogue_at(point), region.names, n_stops)
        return region.margins(column, point)

    cand_margin = [margins_at(p) for p in candidates]
    order = rank_codes(screen, label_names(), s.target, [m["relative"] for m in cand_margin])
    finalists = [int(i) for i in order[: s.refine]]
    progress(f"verifying the best {len(finalists)} on {n} samples")
    rest = evaluate([candidates[i] for i in finalists], screen_n, n)
    full = np.concatenate([screen[finalists], rest], axis=1)
    final = rank_codes(full, label_names(), s.target,
                  [cand_margin[i]["relative"] for i in finalists])
    finalists = [finalists[int(k)] for k in final]
    full = full[final]
    pick = candidates[finalists[0]]
    perturbed = perturbed_points(pick, s.perturbation, s.perturbation_steps, system)
    progress(f"robustness: {len(perturbed)} perturbed points on {robust_n} samples"
             + (f"; reference on {n}" if ref else ""))
    robust = evaluate([p for _, _, p in perturbed], 0, robust_n)
    ref_codes = evaluate([ref], 0, n) if ref else None

    rows: list[dict] = []
    for rank, (i, codes) in enumerate(zip(finalists, full, strict=True)):
        rows.append({"point": candidates[i], "role": "best" if rank == 0 else "runner-up",
                     "rank": rank, "codes": codes, "margin": cand_margin[i]})
    if ref:
        rows.append({"point": ref, "role": "reference", "codes": ref_codes[0]})
    for (axis, k, p), codes in zip(perturbed, robust, strict=True):
        rows.append({"point": p, "role": "perturbed", "axis": axis, "step": k,
                     "codes": codes})
    for i, p in enumerate(candidates):
        if i not in finalists:
            rows.append({"point": p, "role": "screened", "codes": screen[i],
                         "margin": cand_margin[i]})
    progress("margins and Floquet multipliers of the target")
    for r in rows:
        if "margin" not in r:
            r["margin"] = margins_at(r["point"])
        if r["role"] != "screened":
            r["exists"], r["multipliers"] = target_at(region, catalogue_at(r["point"]),
                                                      r["point"], system.dim)
    plane = region_map(region, system, s.bounds, pick)
    return chain_design_dataset(rows, region, plane, s, n, screen_n, robust_n,
                                label_names(), system.dim)


def chain_design_dataset(rows: list[dict], region: ChainRegion, plane: dict, s, n: int,
                         screen_n: int, robust_n: int, label_names, n_dim: int
                         ) -> xr.Dataset:
    """The design as a Dataset: the pair's variables on ``design_point`` and ``group``
    (``point_<axis>`` per design axis by the chain's names; margins ``d_to_target``,
    ``d_to_boundary`` in the stops' units, ``body_to_boundary`` relative), the products'
    critical values on the body grid, and the region map the figure draws."""
    axes = tuple(s.bounds)
    group_names: list[str] = []
    per_row = []
    for r in rows:
        g, c = group_counts(r["codes"][None, :], label_names)
        per_row.append(dict(zip(g, c[0].tolist(), strict=True)))
        group_names += [x for x in g if x not in group_names]
    counts = np.array([[pr.get(g, 0) for g in group_names] for pr in per_row], dtype=np.int64)
    n_samples = np.array([r["codes"].size for r in rows], dtype=np.int64)
    share = counts / n_samples[:, None]
    lo, hi = zip(*(wilson_interval(counts[i], int(n_samples[i])) for i in range(len(rows))),
                 strict=True)
    mult = np.array([r.get("multipliers", np.full(n_dim, np.nan + 0j)) for r in rows])
    unitless = {"units": "1"}
    data = {
        **{f"point_{a}": (("design_point",), [float(r["point"][a]) for r in rows],
                          {"units": "rad" if a.startswith("phi.") else "1"}) for a in axes},
        "role": (("design_point",), np.array([r["role"] for r in rows], dtype=object)),
        "rank": (("design_point",), [r.get("rank", -1) for r in rows],
                 {"long_name": "rank after verification (0: the pick; -1: not ranked)"}),
        "perturbed_axis": (("design_point",), np.array([r.get("axis", "") for r in rows],
                                                       dtype=object)),
        "perturbed_step": (("design_point",), [r.get("step", 0) for r in rows],
                           {"long_name": "steps of the perturbation (signed)"}),
        "n_samples": (("design_point",), n_samples),
        "count": (("design_point", "group"), counts),
        "share": (("design_point", "group"), share, {"long_name": "basin stability",
                                                     **unitless}),
        "ci_low": (("design_point", "group"), np.array(lo), {"long_name": "95% Wilson, low"}),
        "ci_high": (("design_point", "group"), np.array(hi),
                    {"long_name": "95% Wilson, high"}),
        "score": (("design_point",), scores(group_names, counts, s.target, n_samples),
                  {"long_name": "target share minus impacting, unresolved and diverged "
                                "shares", **unitless}),
        **{f"margin_{k}": (("design_point",), [r["margin"][k] for r in rows], unitless)
           for k in MARGINS},
        "target_exists": (("design_point",), [int(r["exists"]) if "exists" in r else -1
                                              for r in rows],
                          {"long_name": "target survives every stop (1), not (0), not "
                                        "computed (-1)"}),
        "multiplier_re": (("design_point", "target_multiplier"), mult.real,
                          {"long_name": "target's Floquet multipliers (union of the "
                                        "bodies'), real"}),
        "multiplier_im": (("design_point", "target_multiplier"), mult.imag,
                          {"long_name": "target's Floquet multipliers, imaginary"}),
        "region_body_value": (("region_point", "body_axis"), region.grid),
        "region_critical": (("region_point", "dcrit_combination", "stop"), region.critical,
                            {"long_name": "each stop's critical value on each product at "
                                          "each body grid point (NaN: absent)",
                             **unitless}),
        "dcrit_name": (("dcrit_combination",), np.array(region.names, dtype=object)),
        "stop_sign": (("stop",), region.signs,
                      {"long_name": "+1: survives above the critical value; -1: below (a "
                                    "left wall)"}),
        "map_survivors": (("map_y", "map_x"), plane["count"],
                          {"long_name": "surviving products (the other axes at the pick)"}),
        "map_target": (("map_y", "map_x"), plane["target"],
                       {"long_name": "1: the target survives"}),
    }
    coords = {"design_point": np.arange(len(rows)),
              "group": np.array(group_names, dtype=object),
              "target_multiplier": np.arange(n_dim),
              "region_point": np.arange(region.grid.shape[0]),
              "body_axis": np.array(region.body_axes, dtype=object),
              "dcrit_combination": np.arange(len(region.names)),
              "stop": np.arange(1, region.signs.size + 1),
              "map_x": plane["x"], "map_y": plane["y"]}
    attrs = {"analysis": "design", "model": "chain", "target": s.target, "n": n,
             "screen_n": screen_n, "robust_n": robust_n, "candidates": s.candidates,
             "refine": s.refine, "perturbation": s.perturbation,
             "perturbation_steps": s.perturbation_steps, "min_margin": s.min_margin,
             "design_seed": s.seed, "grid_points": s.grid_points,
             "design_axes": list(axes),
             **{f"bounds_{a}": np.array(s.bounds[a], dtype=float) for a in axes},
             "map_x_axis": plane["x_axis"], "map_y_axis": plane["y_axis"],
             "interval": "95% Wilson score"}
    return xr.Dataset(data, coords=coords, attrs=attrs)
