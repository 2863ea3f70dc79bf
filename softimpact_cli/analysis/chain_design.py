"""Control design on a chain: choose any of its parameters so that only the wanted
non-impacting product survives (``analysis.design`` is the pair's form; this one follows it
step by step, over the chain's parameters by name; the region itself: ``chain_region``).

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

from collections.abc import Callable

import numpy as np
import xarray as xr

from ..systems import System
from .chain_catalogue import ChainCatalogue
from .chain_region import ChainRegion, axis_sort, build_region, critical_of, region_map
from .design import NoRegion, evaluated_rows, group_counts, halton, scores
from .stability import wilson_interval

PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53)
MARGINS = ("relative", "d_to_target", "d_to_boundary", "body_to_boundary")


def candidate_points(region: ChainRegion, bounds: dict, count: int, min_margin: float,
                     seed: int) -> list[dict]:
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


def perturbed_points(pick: dict, relative: float, steps: int) -> list[tuple[str, int, dict]]:
    """(axis, step, point) for each design axis moved by +-k steps, k = 1 .. steps: the
    step is ``relative`` times the value (a phase: times pi); a law parameter stays >= 0."""
    out = []
    for axis in pick:
        unit = relative * (np.pi if axis.startswith("phi.") else abs(pick[axis]))
        if unit == 0.0:
            continue
        for k in [*range(-steps, 0), *range(1, steps + 1)]:
            value = pick[axis] + k * unit
            if axis_sort(axis) == "law" and value < 0:
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
    candidates = candidate_points(region, s.bounds, s.candidates, s.min_margin, s.seed)
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
    rows = evaluated_rows(evaluate, perturbed_points, candidates, screen, cand_margin,
                          label_names, s.target, s, (n, screen_n, robust_n), ref, progress)
    pick = rows[0]["point"]
    progress("margins and Floquet multipliers of the target")
    for r in rows:
        if "margin" not in r:
            r["margin"] = margins_at(r["point"])
        if r["role"] != "screened":
            r["exists"], r["multipliers"] = target_at(region, catalogue_at(r["point"]),
                                                      r["point"], system.dim)
    plane = region_map(region, s.bounds, pick)
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
