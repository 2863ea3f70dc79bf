"""Control design: choose (d, phi, k_c, c_c) so that only the wanted solution survives.

1. **Region.** On a grid of phases over [0, 2 pi) (plus the ends of the phi bounds and
   the reference phase, computed exactly), the critical distances of every combination
   (:mod:`.critical_distance`) give the region where the target T is the only
   non-impacting combination:

       d_crit_T(phi) < d < min over the other combinations C of d_crit_C(phi)

   (T fits without touching, every other combination would collide: it is destroyed).
2. **Margins** of a point (d, phi): ``d_to_target = d - d_crit_T(phi)``;
   ``d_to_boundary`` = the smaller of that and ``min_C d_crit_C(phi) - d``;
   ``phi_to_boundary`` = how far phi can move at this d before the point leaves the
   region (to within half a grid step); ``relative = min(d_to_boundary / d,
   phi_to_boundary / pi)``: the relative perturbation the point tolerates (phi is an
   angle, so its scale is pi, not its value).
3. **Candidates.** ``candidates`` points inside region and bounds with ``relative >=
   min_margin``, spread by a Halton set (bases 2, 3, 5, 7, rotated by the seed) over
   (grid phase, d within the allowed interval at that phase, k_c, c_c): a 4-D lattice of
   48 points would give two or three levels per axis, a Halton set 48 on each.
4. **Screening and refinement.** Score = basin stability of T minus the share of samples
   that failed: all impacting solutions, and unresolved and diverged outcomes too (a
   sample that did not settle within the budget is not known to reach T; rewarding it
   would favour points where trajectories merely settle slowly), on the first
   ``screen_n`` samples; the best ``refine`` are rerun on all n
   samples (the screened prefix is reused, not recomputed) and ranked again. Ranking:
   the best score; points whose score lies within the Wilson half-width of the best
   one's target share are tied, and among tied points the larger relative margin wins.
5. **Verification** at the pick, the runners-up and an optional reference point, on the
   same samples, with 95% Wilson intervals (:mod:`.stability`).
6. **Robustness.** Each of d, k_c, c_c moved by +-k * perturbation * value and phi by
   +-k * perturbation * pi (k = 1 .. perturbation_steps), shares on ``robust_n`` samples,
   and the target's Floquet multipliers there.

**Floquet multipliers of a non-impacting pair.** The catalogue computes multipliers for
one body. Along a non-impacting joint orbit the stop never acts, so the coupled
linearisation is the uncoupled one: the joint orbit's multipliers (over its period
q = lcm(pl, pr)) are the union of the left body's multipliers raised to q / pl and the
right body's raised to q / pr, for every d above d_crit and every k_c, c_c (the tests
check this against a finite-difference monodromy of the coupled flow). At a perturbed
point the coupled flow along the orbit shows whether it still exists (no contact).

Basin stability itself needs many classified trajectories: :func:`design` takes an
``evaluate(points, start, stop)`` callable that returns the label codes of samples
[start, stop) at each point (the sweep machinery provides it), so this module stays free
of pools and files.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..config.axes import COUPLING_AXES
from ..kernels.codes import OK
from .catalogue import SHOOTING, body_problem, combinations, right_attractors
from .critical_distance import critical_distances
from .engine import Problem, flow
from .labels import name_of
from .stability import groups, wilson_interval

AXES = COUPLING_AXES  # a design searches over the coupling
IMPACTING = "impacting (all)"
TWO_PI = 2 * np.pi


class NoRegion(ValueError):
    """The target is never the only non-impacting combination within the bounds."""


@dataclass(frozen=True)
class Region:
    """Critical distances on a phase grid and the target-only region they imply.

    phi : (P,) phases in [0, 2 pi), ascending; names : (C,) combination names;
    d_crit : (C, P); target : index of the target in names.
    """

    phi: np.ndarray
    names: tuple[str, ...]
    d_crit: np.ndarray
    target: int

    @property
    def low(self) -> np.ndarray:
        """(P,) the target's critical distance: below it the target collides."""
        return self.d_crit[self.target]

    @property
    def high(self) -> np.ndarray:
        """(P,) the smallest critical distance of the others (inf when there are none)."""
        others = np.delete(self.d_crit, self.target, axis=0)
        return others.min(axis=0) if others.size else np.full(self.phi.size, np.inf)

    def inside(self, d: float) -> np.ndarray:
        """(P,) whether (d, phi_j) lies in the region, at every grid phase."""
        return (self.low < d) & (d < self.high)

    def index(self, phi: float) -> int:
        """Index of the grid phase nearest to phi (circularly)."""
        return int(np.argmin(np.abs((phi - self.phi + np.pi) % TWO_PI - np.pi)))

    def phi_to_boundary(self, d: float, phi: float) -> float:
        """Circular distance from phi to the nearest grid phase outside the region at d,
        less half a grid step (pi when the region holds the whole circle at this d)."""
        out = ~self.inside(d)
        if not out.any():
            return float(np.pi)
        gap = np.abs((phi - self.phi[out] + np.pi) % TWO_PI - np.pi).min()
        step = TWO_PI / max(self.phi.size, 1)
        return float(max(gap - 0.5 * step, 0.0))


def phase_grid(points: int, extra=()) -> np.ndarray:
    """``points`` phases over [0, 2 pi) plus ``extra`` ones (wrapped), sorted, distinct."""
    grid = np.linspace(0.0, TWO_PI, points, endpoint=False)
    return np.unique(np.concatenate([grid, np.mod(np.asarray(extra, dtype=float), TWO_PI)]))


def critical_columns(system, values: dict, left: list, phis) -> tuple[tuple[str, ...],
                                                                     np.ndarray]:
    """(names, d_crit (C, len(phis))) of every combination at the given phases."""
    ds = critical_distances(system, values, left, np.asarray(phis, dtype=float))
    return tuple(str(n) for n in ds["combination_label"].values), ds["d_crit"].values


def margins(region: Region, column: np.ndarray, d: float, phi: float) -> dict[str, float]:
    """Margins of (d, phi) given the exact critical distances ``column`` (C,) at phi."""
    low = float(column[region.target])
    others = np.delete(column, region.target)
    high = float(others.min()) if others.size else np.inf
    to_boundary = min(d - low, high - d)
    phi_gap = region.phi_to_boundary(d, phi) if to_boundary > 0 else 0.0
    return {"relative": float(min(to_boundary / d, phi_gap / np.pi)),
            "d_to_target": d - low, "d_to_boundary": to_boundary, "phi_to_boundary": phi_gap}


def halton(index: int, base: int) -> float:
    """The radical inverse of ``index`` in ``base`` (one coordinate of a Halton set)."""
    f, r = 1.0, 0.0
    while index > 0:
        f /= base
        r += f * (index % base)
        index //= base
    return r


def candidate_points(region: Region, bounds: dict, count: int, min_margin: float,
                     seed: int) -> list[dict]:
    """Up to ``count`` points inside region and bounds, each with relative margin >=
    ``min_margin`` (see the module docstring); [] when there is no such point."""
    lo, hi = bounds["phi"]
    phases, intervals = [], []
    for j, p in enumerate(region.phi):
        for phi in p + TWO_PI * np.arange(np.floor((lo - p) / TWO_PI),
                                          np.ceil((hi - p) / TWO_PI) + 1):
            if not lo - 1e-12 <= phi <= hi + 1e-12:
                continue
            # d - low >= m d and high - d >= m d, within the d bounds
            a = max(bounds["d"][0], region.low[j] / (1 - min_margin))
            b = min(bounds["d"][1], region.high[j] / (1 + min_margin))
            if a <= b:
                phases.append((float(phi), j))
                intervals.append((a, b))
    if not phases:
        return []
    shift = np.random.default_rng(seed).uniform(size=4)
    out: list[dict] = []
    for i in range(1, 64 * count + 1):
        u = (np.array([halton(i, b) for b in (2, 3, 5, 7)]) + shift) % 1.0
        k = min(int(u[0] * len(phases)), len(phases) - 1)
        (phi, j), (a, b) = phases[k], intervals[k]
        d = a + u[1] * (b - a)
        if region.phi_to_boundary(d, phi) < min_margin * np.pi:
            continue
        out.append({"d": d, "phi": phi,
                    "k_c": bounds["k_c"][0] + u[2] * (bounds["k_c"][1] - bounds["k_c"][0]),
                    "c_c": bounds["c_c"][0] + u[3] * (bounds["c_c"][1] - bounds["c_c"][0])})
        if len(out) == count:
            break
    return out


def perturbed_points(pick: dict, relative: float, steps: int) -> list[tuple[str, int, dict]]:
    """(axis, step, point) for each axis moved by +-k steps, k = 1 .. steps; the step is
    ``relative`` times the value for d, k_c, c_c (none when the value is 0) and
    ``relative * pi`` for phi."""
    out = []
    for axis in AXES:
        unit = relative * (np.pi if axis == "phi" else abs(pick[axis]))
        if unit == 0.0:  # a relative step of zero moves nothing
            continue
        for k in [*range(-steps, 0), *range(1, steps + 1)]:
            value = pick[axis] + k * unit
            if axis in ("k_c", "c_c") and value < 0:
                continue
            out.append((axis, k, {**pick, axis: float(value)}))
    return out


def group_counts(codes: np.ndarray, catalogue_names: tuple[str, ...]
                 ) -> tuple[list[str], np.ndarray]:
    """(group names, counts (points, groups)) of label codes (points, samples): every
    catalogue solution and outcome met, all impacting together, the non-impacting sum."""
    present = sorted(set(range(len(catalogue_names))) | set(np.unique(codes).tolist()))
    label_names = [name_of(c, catalogue_names) for c in present]
    per_label = np.stack([(codes == c).sum(axis=-1) for c in present], axis=-1)
    grouping = groups(label_names)
    counts = np.stack([per_label[:, idx].sum(axis=-1) if idx else
                       np.zeros(codes.shape[0], dtype=np.int64)
                       for idx in grouping.values()], axis=-1)
    return list(grouping), counts


FAILED = (IMPACTING, "unresolved", "diverged")  # outcomes the score counts against T


def scores(group_names: list[str], counts: np.ndarray, target: str, n) -> np.ndarray:
    """(points,) target share minus the failed share (impacting, unresolved, diverged)
    from group counts (points, groups) of n samples each."""
    failed = sum(counts[:, group_names.index(g)] for g in FAILED if g in group_names)
    return (counts[:, group_names.index(target)] - failed) / n


def ranking(score: np.ndarray, target_count: np.ndarray, n: int,
            margin: np.ndarray) -> np.ndarray:
    """Indices from best to worst (see the module docstring for the tie rule)."""
    best = int(np.lexsort((-margin, -score))[0])
    lo, hi = wilson_interval(target_count[best], n)
    tied = score >= score[best] - 0.5 * float(hi - lo)
    return np.lexsort((-score, -np.where(tied, margin, -np.inf), ~tied))


def target_multipliers(system, values: dict, left: list, target: str, point: dict
                       ) -> tuple[bool, np.ndarray]:
    """(exists, multipliers (4,) complex) of the target's joint orbit at ``point``.

    It exists when its uncoupled orbit stays clear of the stop there (max of x1 - x2 - d
    < 0 over the joint period, on the coupled flow). Its multipliers over the joint period
    q are then the union of the left body's multipliers to the power q / pl and the right
    body's to the power q / pr (module docstring), sorted by modulus then angle; NaN when
    it does not exist.
    """
    values = {**values, **point}
    body = system.extra
    right = right_attractors(body_problem(system, values, SHOOTING), left, point["phi"],
                             body["right_sign"], body["right_phase"])
    combo = next(c for c in combinations(left, right) if c.name == target)
    pair = Problem(system, values, SHOOTING)
    q = combo.orbit.shape[0]
    status, _, max_g = flow(pair, combo.orbit[0], 0.0, q * pair.period)
    if status != OK or max_g >= 0.0:
        return False, np.full(4, np.nan + 0j)
    mult = np.concatenate([combo.left.multipliers ** (q // combo.left.period),
                           combo.right.multipliers ** (q // combo.right.period)])
    return True, mult[np.lexsort((np.angle(mult), -np.abs(mult)))]


Evaluate = Callable[[list[dict], int, int], np.ndarray]


def design(system, values: dict, left: list, settings, n: int, evaluate: Evaluate,
           progress: Callable[[str], None] = lambda s: None) -> xr.Dataset:
    """Run the design (module docstring) for ``settings`` (a ``config.DesignAnalysis``)
    with n samples per verified point; ``evaluate(points, start, stop)`` returns the label
    codes (len(points), stop - start) of samples [start, stop) at each point.

    Raises NoRegion when the target is never alone (with the margin) within the bounds.
    """
    s = settings
    target = s.target
    screen_n = min(s.screen_n, n)
    robust_n = min(s.robust_n or n, n)
    ref = dict(s.reference) if s.reference else None
    extra = [*s.bounds["phi"], *([ref["phi"]] if ref else [])]
    progress(f"critical distances at {s.phi_points} phases")
    phases = phase_grid(s.phi_points, extra)
    names, d_crit = critical_columns(system, values, left, phases)
    if target not in names:
        raise NoRegion(f"{target!r} is not a combination of the catalogue "
                       f"({', '.join(names)})")
    region = Region(phases, names, d_crit, names.index(target))
    candidates = candidate_points(region, s.bounds, s.candidates, s.min_margin, s.seed)
    if not candidates:
        b = s.bounds
        raise NoRegion(f"{target!r} is never the only non-impacting combination with a "
                       f"relative margin >= {s.min_margin:g} for d in [{b['d'][0]:g}, "
                       f"{b['d'][1]:g}], phi in [{b['phi'][0]:.4g}, {b['phi'][1]:.4g}]")
    progress(f"screening {len(candidates)} candidates on {screen_n} samples")
    screen = evaluate(candidates, 0, screen_n)
    cand_margin = [margins(region, d_crit[:, region.index(p["phi"])], p["d"], p["phi"])
                   for p in candidates]  # candidates sit on grid phases: exact columns
    rows = evaluated_rows(evaluate, perturbed_points, candidates, screen, cand_margin,
                          lambda: names, target, s, (n, screen_n, robust_n), ref, progress)
    progress("margins and Floquet multipliers of the target")
    missing = sorted({r["point"]["phi"] for r in rows if "margin" not in r})
    if missing:
        names_x, columns = critical_columns(system, values, left, missing)
        assert names_x == names  # the same catalogue: names come out in the same order
    for r in rows:
        if "margin" not in r:
            column = columns[:, missing.index(r["point"]["phi"])]
            r["margin"] = margins(region, column, r["point"]["d"], r["point"]["phi"])
        if r["role"] != "screened":
            r["exists"], r["multipliers"] = target_multipliers(system, values, left, target,
                                                               r["point"])
    return design_dataset(rows, region, s, n, screen_n, robust_n)


def evaluated_rows(evaluate, perturb, candidates: list[dict], screen: np.ndarray,
                   cand_margin: list[dict], label_names, target: str, s,
                   sizes: tuple[int, int, int], ref: dict | None, progress) -> list[dict]:
    """The design's stages after the screening, shared by a pair's and a chain's: rank the
    screened ``candidates`` (label codes ``screen``, margins ``cand_margin``), verify the
    best ``s.refine`` on n samples, rank them again, perturb the pick (robustness on
    robust_n samples) and evaluate the ``ref`` point; ``sizes = (n, screen_n, robust_n)``,
    ``label_names()`` the names of the codes so far. Returns one row per evaluated point
    (role, codes; margins of the candidates; the caller adds the others' margins), best
    first. ``perturb(pick, relative, steps)``: the perturbed points, (axis, step, point)
    each (:func:`perturbed_points` for a pair)."""
    n, screen_n, robust_n = sizes
    margin_of = [m["relative"] for m in cand_margin]
    order = rank_codes(screen, label_names(), target, margin_of)
    finalists = [int(i) for i in order[: s.refine]]
    progress(f"verifying the best {len(finalists)} on {n} samples")
    rest = evaluate([candidates[i] for i in finalists], screen_n, n)
    full = np.concatenate([screen[finalists], rest], axis=1)
    final = rank_codes(full, label_names(), target, [margin_of[i] for i in finalists])
    finalists = [finalists[int(k)] for k in final]
    full = full[final]
    perturbed = perturb(candidates[finalists[0]], s.perturbation, s.perturbation_steps)
    progress(f"robustness: {len(perturbed)} perturbed points on {robust_n} samples"
             + (f"; reference on {n}" if ref else ""))
    robust = evaluate([p for _, _, p in perturbed], 0, robust_n)
    ref_codes = evaluate([ref], 0, n) if ref else None

    rows: list[dict] = []  # one per evaluated point: its role, codes and margins
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
    return rows


def rank_codes(codes: np.ndarray, names: tuple[str, ...], target: str, margin) -> np.ndarray:
    """Indices of the points (rows of label ``codes``) from best to worst: score, then
    margin among the tied (:func:`ranking`)."""
    group, counts = group_counts(codes, names)
    n = codes.shape[1]
    score = scores(group, counts, target, n)
    return ranking(score, counts[:, group.index(target)], n, np.asarray(margin, dtype=float))


def design_dataset(rows: list[dict], region: Region, s, n: int, screen_n: int,
                   robust_n: int) -> xr.Dataset:
    """The design as a Dataset: dim ``design_point`` (every evaluated point, the pick first, then
    runners-up, reference, perturbed and screened points), ``group`` (shares), and the
    critical-distance curves and region on ``dcrit_phi``."""
    group_names: list[str] = []
    per_row = []
    for r in rows:
        g, c = group_counts(r["codes"][None, :], region.names)
        per_row.append(dict(zip(g, c[0].tolist(), strict=True)))
        group_names += [x for x in g if x not in group_names]
    counts = np.array([[pr.get(g, 0) for g in group_names] for pr in per_row], dtype=np.int64)
    n_samples = np.array([r["codes"].size for r in rows], dtype=np.int64)
    share = counts / n_samples[:, None]
    lo, hi = zip(*(wilson_interval(counts[i], int(n_samples[i])) for i in range(len(rows))),
                 strict=True)
    mult = np.array([r.get("multipliers", np.full(4, np.nan + 0j)) for r in rows])
    unitless = {"units": "1"}
    data = {
        **{f"point_{a}": (("design_point",), [float(r["point"][a]) for r in rows],
                          {"units": "rad" if a == "phi" else "1"}) for a in AXES},
        "role": (("design_point",), np.array([r["role"] for r in rows], dtype=object)),
        "rank": (("design_point",), [r.get("rank", -1) for r in rows],
                 {"long_name": "rank after verification (0: the pick; -1: not ranked)"}),
        "perturbed_axis": (("design_point",), np.array([r.get("axis", "") for r in rows],
                                                dtype=object)),
        "perturbed_step": (("design_point",), [r.get("step", 0) for r in rows],
                           {"long_name": "steps of the perturbation (signed)"}),
        "n_samples": (("design_point",), n_samples),
        "count": (("design_point", "group"), counts),
        "share": (("design_point", "group"), share, {"long_name": "basin stability", **unitless}),
        "ci_low": (("design_point", "group"), np.array(lo), {"long_name": "95% Wilson, low"}),
        "ci_high": (("design_point", "group"), np.array(hi), {"long_name": "95% Wilson, high"}),
        "score": (("design_point",), scores(group_names, counts, s.target, n_samples),
                  {"long_name": "target share minus impacting, unresolved and diverged "
                                "shares", **unitless}),
        **{f"margin_{k}": (("design_point",), [r["margin"][k] for r in rows], unitless)
           for k in ("relative", "d_to_target", "d_to_boundary", "phi_to_boundary")},
        "target_exists": (("design_point",), [int(r["exists"]) if "exists" in r else -1
                                       for r in rows],
                          {"long_name": "target orbit clear of the stop (1), not (0), "
                                        "not computed (-1)"}),
        "multiplier_re": (("design_point", "target_multiplier"), mult.real,
                          {"long_name": "target's Floquet multipliers (coupled pair), real"}),
        "multiplier_im": (("design_point", "target_multiplier"), mult.imag,
                          {"long_name": "target's Floquet multipliers, imaginary"}),
        "critical_distance": (("dcrit_combination", "dcrit_phi"), region.d_crit,
                              {"long_name": "d_crit: max of x1 - x2 on the uncoupled joint "
                                            "orbit", **unitless}),
        "dcrit_name": (("dcrit_combination",), np.array(region.names, dtype=object)),
        "region_low": (("dcrit_phi",), region.low,
                       {"long_name": "target's d_crit (lower edge of the region)"}),
        "region_high": (("dcrit_phi",), region.high,
                        {"long_name": "smallest d_crit of the others (upper edge)"}),
    }
    coords = {"design_point": np.arange(len(rows)), "group": np.array(group_names, dtype=object),
              "target_multiplier": np.arange(4),
              "dcrit_phi": ("dcrit_phi", region.phi, {"units": "rad"}),
              "dcrit_combination": np.arange(len(region.names))}
    attrs = {"analysis": "design", "target": s.target, "n": n, "screen_n": screen_n,
             "robust_n": robust_n, "candidates": s.candidates, "refine": s.refine,
             "perturbation": s.perturbation, "perturbation_steps": s.perturbation_steps,
             "min_margin": s.min_margin, "design_seed": s.seed, "phi_points": s.phi_points,
             **{f"bounds_{a}": np.array(s.bounds[a], dtype=float) for a in AXES},
             "interval": "95% Wilson score"}
    return xr.Dataset(data, coords=coords, attrs=attrs)
