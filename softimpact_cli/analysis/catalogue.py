"""The one-body attractor catalogue, the right body's attractors, and their combinations.

1. Many initial conditions (a grid plus random samples over a box of (x, v)) are
   integrated and classified; converged orbits are deduplicated as cyclic sets of
   section points.
2. Each orbit is refined by Newton shooting on the p-th iterate of the stroboscopic map,
   with the monodromy matrix from the variational equations; its eigenvalues are the
   Floquet multipliers.
3. Attractors are numbered by (period, amplitude) ascending and their points put in
   canonical order (see :mod:`softimpact_cli.analysis.labels`).
4. The right body's attractors follow from the left body's without a search:
   ``x_R(t) = sign * x_L(t + (phi - phase) / w)`` (time shift for the Duffing pair,
   mirror plus half-period shift for the bilinear pair).
5. Every combination L R with every shift s gets its exact joint orbit.
"""

from __future__ import annotations

import functools
import hashlib
import itertools
from dataclasses import asdict, dataclass
from math import gcd, lcm
from typing import NamedTuple

import numpy as np

from ..config import ConfigError, IntegratorSettings
from ..kernels import numba_cache
from ..kernels.codes import CONVERGED, OK, outcome
from ..systems import System, get_system
from ..systems.base import check_bodies
from ..systems.variational import initial_variational_state, variational_system
from .engine import Problem, classify_state, flow, record_trajectory
from .labels import BodyToken, Label, all_shifts, bodies_label, shifts

SHOOTING = IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13)


@dataclass(frozen=True)
class Attractor:
    """A periodic attractor of one body.

    points : (period, 2) section points (x, v) at t = nT, canonical order
    multipliers : (2,) complex Floquet multipliers (eigenvalues of the monodromy matrix)
    amplitude : max |x| over the orbit
    share : fraction of the search's initial conditions (one body) that reached it; not
        a basin share (see SEARCH_SHARE)
    residual : |P^p(x0) - x0|_inf after Newton refinement
    """

    number: int
    period: int
    points: np.ndarray
    amplitude: float
    multipliers: np.ndarray
    share: float
    residual: float

    @property
    def stable(self) -> bool:
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    @property
    def name(self) -> str:
        return Label("body", self.period, self.number).name


@dataclass(frozen=True)
class Combination:
    """Left attractor, right attractor and shift; ``orbit`` (lcm, 4) joint section points."""

    left: Attractor
    right: Attractor
    shift: int
    orbit: np.ndarray

    @property
    def label(self) -> Label:
        return Label("pair", self.left.period, self.left.number, self.right.period,
                     self.shift, self.right.number)

    @property
    def name(self) -> str:
        return self.label.name


@dataclass(frozen=True)
class Catalogue:
    """Attractors of the left body (and, for a pair, of the right body and combinations).

    counts : outcome of every sampled initial condition ('converged', 'unresolved',
    'diverged') for the one-body search. source: where that search came from
    ("computed", or "cache <key prefix>" when read from the catalogue cache).
    """

    model: str
    values: dict
    attractors: tuple[Attractor, ...]
    right: tuple[Attractor, ...]
    combinations: tuple[Combination, ...]
    counts: dict[str, int]
    n_samples: int
    source: str = "computed"
    more: tuple[tuple[Attractor, ...], ...] = ()  # bodies 3, 4, ...: each its attractors

    @property
    def per_body(self) -> tuple[tuple[Attractor, ...], ...]:
        """Each body's attractors, in body order (one body, a pair, or more)."""
        if not self.right:
            return (self.attractors,)
        return (self.attractors, self.right, *self.more)

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the catalogue's solutions in code order: combinations for a pair,
        attractors for one body, every combination (:func:`combination_names`) for more."""
        if self.more:
            return combination_names(self.per_body)
        if self.right:
            return tuple(c.name for c in self.combinations)
        return tuple(a.name for a in self.attractors)

    @property
    def orbits(self) -> dict[str, np.ndarray]:
        """{name: section points at t = 0 mod T} of the solutions, in code order (a pair's
        joint (q, 4) orbits, one body's (q, 2))."""
        if self.right:
            return {c.name: c.orbit for c in self.combinations}
        return {a.name: a.points for a in self.attractors}

    def combination(self, name: str) -> Combination:
        for combo in self.combinations:
            if combo.name == name:
                return combo
        raise KeyError(name)


def require_attractors(catalogue: Catalogue, kind: str, source: str) -> None:
    """Stop (ConfigError, one line) when the search found no attractor: ``kind`` (dcrit,
    bifurcation, map) has nothing to follow or count without one."""
    if catalogue.attractors:
        return
    counts = catalogue.counts
    raise ConfigError(f"{source}: catalogue: no attractor found ({catalogue.n_samples} samples: "
                      f"{counts.get('diverged', 0)} diverged, {counts.get('unresolved', 0)} "
                      f"unresolved); {kind} needs at least one")


def catalogue_states(scene) -> np.ndarray:
    """The initial conditions of a scene's [catalogue] search, (n, 2)."""
    c = scene.catalogue
    return sample_states(c.box, c.grid, c.random, c.seed)


def body_problem(system: System, values: dict, integrator: IntegratorSettings) -> Problem:
    """The one-body problem with the body parameters of ``values``."""
    body = get_system(system.model, 1)
    return Problem(body, {k: values[k] for k in body.parameter_names}, integrator)


def sample_states(box: dict, grid: int, n_random: int, seed: int) -> np.ndarray:
    """(N, 2) initial (x, v): a grid x grid lattice plus n_random uniform samples."""
    (x0, x1), (v0, v1) = box["x"], box["v"]
    parts = []
    if grid > 0:
        xs = np.linspace(x0, x1, grid)
        vs = np.linspace(v0, v1, grid)
        parts.append(np.array(np.meshgrid(xs, vs, indexing="ij")).reshape(2, -1).T)
    if n_random > 0:
        rng = np.random.default_rng(seed)
        parts.append(np.column_stack([rng.uniform(x0, x1, n_random),
                                      rng.uniform(v0, v1, n_random)]))
    return np.concatenate(parts) if parts else np.zeros((0, 2))


def same_cycle(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """Whether two cyclic point sequences (p, dim) are the same orbit up to rotation."""
    if a.shape != b.shape:
        return False
    return any(np.max(np.abs(np.roll(a, k, axis=0) - b)) <= tol for k in range(a.shape[0]))


def canonical(points: np.ndarray) -> np.ndarray:
    """Rotate time-ordered section points so that point 0 has the largest displacement."""
    return np.roll(points, -int(np.argmax(points[:, 0])), axis=0)


def refine_orbit(problem: Problem, x0: np.ndarray, period: int, tol: float = 1e-10,
                 max_iter: int = 30) -> tuple[np.ndarray, np.ndarray, float]:
    """Newton shooting on P^p(x) - x = 0 with the monodromy from the variational equations.

    Returns (x, monodromy (dim, dim), residual |P^p(x) - x|_inf at the returned x).
    """
    var = Problem(variational_system(problem.system), problem.values, SHOOTING)
    T = problem.period
    n = problem.system.dim
    x = np.array(x0, dtype=float)
    residual = np.inf
    monodromy = np.full((n, n), np.nan)
    for _ in range(max_iter):
        status, z, _ = flow(var, initial_variational_state(x), 0.0, period * T)
        if status != OK:
            break
        monodromy = z[n:].reshape(n, n)
        r = z[:n] - x
        residual = float(np.max(np.abs(r)))
        if residual <= tol:
            break
        x = x - np.linalg.solve(monodromy - np.eye(n), r)
    return x, monodromy, residual


def orbit_points(problem: Problem, x0: np.ndarray, period: int) -> np.ndarray:
    """The p section points of the orbit through x0 at t = 0, in time order."""
    T = problem.period
    pts = [np.asarray(x0, dtype=float)]
    for i in range(1, period):
        _, y, _ = flow(problem, pts[-1], (i - 1) * T, i * T)
        pts.append(y)
    return np.array(pts)


def amplitude(problem: Problem, x0: np.ndarray, period: int, samples: int = 2048) -> float:
    """max |x| over the orbit through x0, from dense samples."""
    return orbit_shape(problem, x0, period, samples)[0]


def orbit_shape(problem: Problem, x0: np.ndarray, period: int, samples: int = 2048
                ) -> tuple[float, float, float]:
    """(max |x|, mean x, max x) over the orbit through x0, from dense samples: what does
    not depend on where the orbit is cut (a time shift, another body's phase), up to
    the sampling (relative ~1e-5 for the maxima, rounding for the mean)."""
    x = record_trajectory(problem, x0, 0.0, period, samples).y[:, 0]
    one_lap = x[: period * samples]  # the last sample closes the orbit: counted once
    return float(np.max(np.abs(x))), float(np.mean(one_lap)), float(np.max(x))


def orbit_order(tol: float):
    """A sort key of (period, orbit_shape) entries: by period, then amplitude, mean x and
    max x, each equal within ``tol`` relative (the sampling's noise must not decide the
    order of two mirror-image orbits of one amplitude: their mean x tells them apart)."""
    def compare(a, b) -> int:
        if a[0] != b[0]:
            return -1 if a[0] < b[0] else 1
        for u, v in zip(a[1], b[1], strict=True):
            if abs(u - v) > tol * max(1.0, abs(u), abs(v)):
                return -1 if u < v else 1
        return 0
    return functools.cmp_to_key(compare)


def find_attractors(problem: Problem, states: np.ndarray, t0: float = 0.0,
                    match_tol: float = 1e-3, progress=None):
    """Classify every state; return (distinct orbits with hit counts, outcome counts)."""
    orbits: list[list] = []  # [points (p, dim), hits]
    counts = {"converged": 0, "unresolved": 0, "diverged": 0}
    for y0 in states:
        cls = classify_state(problem, y0, t0)
        counts[outcome(cls.status)] += 1
        if progress is not None:
            progress(1)
        if cls.status != CONVERGED:
            continue
        pts = cls.orbit
        tol = match_tol * max(1.0, float(np.max(np.abs(pts))))
        for entry in orbits:
            if same_cycle(entry[0], pts, tol):
                entry[1] += 1
                break
        else:
            orbits.append([pts, 1])
    return orbits, counts


def body_catalogue(problem: Problem, states: np.ndarray, t0: float = 0.0,
                   match_tol: float = 1e-3, progress=None) -> tuple[list[Attractor], dict]:
    """Attractors of one body, refined, numbered by (period, amplitude, mean x, max x):
    ``orbit_order``."""
    orbits, counts = find_attractors(problem, states, t0, match_tol, progress)
    tight = Problem(problem.system, problem.values, SHOOTING)
    found = []
    for pts, hits in orbits:
        period = pts.shape[0]
        x, monodromy, residual = refine_orbit(problem, canonical(pts)[0], period)
        points = canonical(orbit_points(tight, x, period))
        shape = orbit_shape(tight, points[0], period)
        found.append((period, shape[0], points, np.linalg.eigvals(monodromy),
                      hits / len(states), residual, shape))
    # numbered by the orbit itself, not by the search's order: identical bodies at other
    # phases number one orbit alike
    order = orbit_order(match_tol)
    found.sort(key=lambda f: order((f[0], f[6])))
    attractors = []
    for f in found:
        # Newton may land two samples' orbits on one (a slow transient mistaken for an orbit).
        if any(a.period == f[0] and same_cycle(a.points, f[2], match_tol) for a in attractors):
            continue
        attractors.append(Attractor(len(attractors) + 1, f[0], f[2], f[1], f[3], f[4], f[5]))
    return attractors, counts


def right_attractors(problem: Problem, left: list[Attractor], phi: float, sign: float,
                     phase: float) -> list[Attractor]:
    """The right body's attractors: x_R(t) = sign * x_L(t + (phi - phase)/w), canonical."""
    T = problem.period
    lag = ((phi - phase) / (2.0 * np.pi) * T) % T
    tight = Problem(problem.system, problem.values, SHOOTING)
    out = []
    for att in left:
        pts = np.array([sign * flow(tight, p, 0.0, lag)[1] for p in att.points])
        out.append(Attractor(att.number, att.period, canonical(pts), att.amplitude,
                             att.multipliers, att.share, att.residual))
    return out


def combinations(left: list[Attractor], right: list[Attractor]) -> list[Combination]:
    """Every (left, right, s) with s in 0 .. gcd(pl, pr) - 1, with its joint orbit.

    At section 0 the left body sits at index 0 and the right body at index s; both advance
    one index per forcing period.
    """
    out = []
    for a in left:
        for b in right:
            g = gcd(a.period, b.period)
            n = a.period * b.period // g
            for s in range(g):
                orbit = np.array([np.concatenate([a.points[i % a.period],
                                                  b.points[(s + i) % b.period]])
                                  for i in range(n)])
                out.append(Combination(a, b, s, orbit))
    return out


def joint_orbit(chosen, shifts_) -> np.ndarray:
    """(lcm of the periods, 2n) section points of bodies on attractors ``chosen`` (one per
    body, canonical order) with shifts ``shifts_`` (``labels.all_shifts``), in time
    order from the section where each body i sits at its index s_i. For a pair, the
    orbit :func:`combinations` gives."""
    q = lcm(*(a.period for a in chosen))
    return np.array([np.concatenate([a.points[(s + i) % a.period]
                                     for a, s in zip(chosen, shifts_, strict=True)])
                     for i in range(q)])


def combination_names(per_body) -> tuple[str, ...]:
    """The name of every combination of one attractor per body with every canonical
    shift tuple (``labels.all_shifts``): attractors in each body's order (the first body's
    slowest), shifts in lexicographic order. For a pair, the order of
    :func:`combinations`."""
    names = []
    for chosen in itertools.product(*per_body):
        for s in all_shifts([a.period for a in chosen]):
            names.append(bodies_label([BodyToken(a.period, a.number, k)
                                       for a, k in zip(chosen, s, strict=True)]).name)
    return tuple(names)


def match_point(attractors, point: np.ndarray, tol: float):
    """(attractor, index) whose section point is within tol of ``point``, else (None, -1)."""
    best = (None, -1, np.inf)
    for att in attractors:
        dist = np.max(np.abs(att.points - point), axis=1)
        i = int(np.argmin(dist))
        if dist[i] < best[2]:
            best = (att, i, dist[i])
    if best[2] <= tol * max(1.0, float(np.max(np.abs(point)))):
        return best[0], best[1]
    return None, -1


def label_orbit(catalogue: Catalogue, orbit: np.ndarray, impacting: bool,
                tol: float = 1e-3) -> Label:
    """Name a converged orbit (q, 2n) of n bodies (time order; body i is x_i = column 2i,
    v_i = column 2i + 1): each body's last section point is matched to one of its
    attractors (:func:`match_point`), and the joint period must be the lcm of theirs."""
    q = orbit.shape[0]
    if impacting:
        return Label("impacting", q)
    per_body = catalogue.per_body
    if orbit.shape[1] != 2 * len(per_body):
        raise ValueError(f"label_orbit: an orbit of {orbit.shape[1]} state variables, a "
                         f"catalogue of {len(per_body)} bodies")
    last = orbit[-1]
    found = [match_point(atts, last[2 * i: 2 * i + 2], tol) for i, atts in enumerate(per_body)]
    if any(a is None for a, _ in found):
        return Label("unmatched", q)
    periods = [a.period for a, _ in found]
    if q != lcm(*periods):
        return Label("unmatched", q)
    s = shifts([j for _, j in found], periods)
    return bodies_label([BodyToken(a.period, a.number, k)
                         for (a, _), k in zip(found, s, strict=True)])


def extend_catalogue(system: System, values: dict, integrator: IntegratorSettings,
                     left: list, counts: dict, n_states: int, source: str = "computed"
                     ) -> Catalogue:
    """The catalogue at the parameter point ``values`` from the left body's attractors:
    for a pair, the right body's (at ``values["phi"]``) and the combinations. ``source``:
    where the left body's search came from (:class:`BodySearch`)."""
    check_bodies(system.bodies, "extend_catalogue (left and right attractors)")
    right: list[Attractor] = []
    combos: list[Combination] = []
    if system.bodies == 2:
        right = right_attractors(body_problem(system, values, integrator), left,
                                 float(values["phi"]), system.extra["right_sign"],
                                 system.extra["right_phase"])
        combos = combinations(left, right)
    return Catalogue(system.model, dict(values), tuple(left), tuple(right), tuple(combos),
                     counts, n_states, source)


# ------------------------------------------------------------------ cached search

SEARCH_SOURCES = ("kernels", "systems", "analysis")  # the folders that compute a search


class BodySearch(NamedTuple):
    """The one-body search: attractors (numbered), outcome counts, samples searched, and
    where it came from ("computed", or "cache <key prefix>" from the catalogue cache)."""

    attractors: list[Attractor]
    counts: dict[str, int]
    n_states: int
    source: str


def search_key_material(problem: Problem, states: np.ndarray, t0: float, match_tol: float
                        ) -> dict:
    """Everything a one-body search depends on, JSON-able: the body's model and parameters
    (not d, phi, k_c, c_c: a body has none), the integrator settings, the initial states
    (n, 2), t0, match_tol, and the sources and library versions that compute it."""
    import numba

    states = np.ascontiguousarray(states, dtype=np.float64)
    return {
        "search": "one-body attractors", "model": problem.system.model,
        "bodies": problem.system.bodies,
        "parameters": {k: v if isinstance(v, str) else float(v)
                       for k, v in sorted(problem.values.items())},
        "packed": problem.params.tolist(), "integrator": asdict(problem.integrator),
        "states": {"shape": list(states.shape),
                   "sha256": hashlib.sha256(states.tobytes()).hexdigest()},
        "t0": float(t0), "match_tol": float(match_tol),
        "sources": numba_cache.source_hash(folders=SEARCH_SOURCES),
        "numpy": np.__version__, "numba": numba.__version__,
    }


def search_arrays(search: BodySearch) -> dict[str, np.ndarray]:
    """A search as plain arrays: per attractor its fields, points and multipliers
    concatenated (split by period and multiplier count), and the outcome counts."""
    atts = search.attractors
    dim = atts[0].points.shape[1] if atts else 2
    return {
        "number": np.array([a.number for a in atts], dtype=np.int64),
        "period": np.array([a.period for a in atts], dtype=np.int64),
        "amplitude": np.array([a.amplitude for a in atts], dtype=np.float64),
        "share": np.array([a.share for a in atts], dtype=np.float64),
        "residual": np.array([a.residual for a in atts], dtype=np.float64),
        "points": np.concatenate([a.points for a in atts]) if atts else np.zeros((0, dim)),
        "multipliers": np.concatenate([np.asarray(a.multipliers, dtype=np.complex128)
                                       for a in atts]) if atts else np.zeros(0, complex),
        "multiplier_count": np.array([a.multipliers.size for a in atts], dtype=np.int64),
        "multipliers_real": np.array([not np.iscomplexobj(a.multipliers) for a in atts],
                                     dtype=bool),
        "count_names": np.array(list(search.counts), dtype=str),
        "count_values": np.array(list(search.counts.values()), dtype=np.int64),
        "n_states": np.array(search.n_states, dtype=np.int64),
    }


def search_from_arrays(arrays: dict[str, np.ndarray], source: str) -> BodySearch:
    """The :class:`BodySearch` of :func:`search_arrays` (same values, bit for bit, and
    the multipliers' dtype: eigvals gives float64 when every eigenvalue is real)."""
    point_end = np.cumsum(arrays["period"])
    mult_end = np.cumsum(arrays["multiplier_count"])
    attractors = []
    for i, number in enumerate(arrays["number"]):
        p, m = int(arrays["period"][i]), int(arrays["multiplier_count"][i])
        mult = arrays["multipliers"][mult_end[i] - m: mult_end[i]]
        attractors.append(Attractor(
            int(number), p, arrays["points"][point_end[i] - p: point_end[i]],
            float(arrays["amplitude"][i]), mult.real if arrays["multipliers_real"][i]
            else mult, float(arrays["share"][i]), float(arrays["residual"][i])))
    counts = {str(k): int(v) for k, v in zip(arrays["count_names"], arrays["count_values"],
                                             strict=True)}
    return BodySearch(attractors, counts, int(arrays["n_states"]), source)


# ------------------------------------------------------------------ dataset form

CURVE_SAMPLES = 256  # dense samples per forcing period of each stored orbit curve
# Each attractor's share of the one-body search's starts. Not a basin share: the search
# samples one body alone over the [catalogue] box, while a pair's basins are shares of
# its own starts (figure 6(d): 0.47 / 0.53 here against basin shares 0.92 / 0.08). Named
# "attractor_share" in results written before 2026-11-27; search_shares reads both.
SEARCH_SHARE = "attractor_search_share"
OLD_SEARCH_SHARE = "attractor_share"
SEARCH_SHARE_TEXT = ("share of the attractor search's starts (one body alone, [catalogue] "
                     "grid and random) that reached it; not a basin share")


def _curve(problem: Problem, start: np.ndarray, t0: float, period: int, sign: float
           ) -> np.ndarray:
    """(period * CURVE_SAMPLES, 2) dense orbit from ``start`` at t0, times sign."""
    traj = record_trajectory(problem, sign * start, t0, period, CURVE_SAMPLES)
    return sign * traj.y[: period * CURVE_SAMPLES]


def attractor_variables(attractors, pts: np.ndarray, curves: np.ndarray,
                        mult: np.ndarray) -> dict:
    """The per-attractor variables of a catalogue's Dataset (one body's attractors, or a
    chain's bodies' in a row): period, amplitude, search share, residual, section points
    ``pts`` (attractor, point, 2), dense curves ``curves`` (attractor, sample, 2) and the
    Floquet multipliers ``mult`` (attractor, 2), complex."""
    return {
        "attractor_period": (("attractor",), [a.period for a in attractors],
                             {"long_name": "period", "units": "forcing periods"}),
        "attractor_amplitude": (("attractor",), [a.amplitude for a in attractors],
                                {"long_name": "max |x| over the orbit", "units": "1"}),
        SEARCH_SHARE: (("attractor",), [a.share for a in attractors],
                       {"long_name": SEARCH_SHARE_TEXT, "units": "1"}),
        "attractor_residual": (("attractor",), [a.residual for a in attractors],
                               {"long_name": "|P^p(x) - x| after Newton", "units": "1"}),
        "attractor_points": (("attractor", "point", "body_variable"), pts,
                             {"long_name": "section points at t = nT, canonical order",
                              "units": "1"}),
        "attractor_curve": (("attractor", "curve_sample", "body_variable"), curves,
                            {"long_name": "dense orbit from point 0 at t = 0", "units": "1"}),
        "multiplier_re": (("attractor", "multiplier"), mult.real,
                          {"long_name": "Floquet multiplier, real part", "units": "1"}),
        "multiplier_im": (("attractor", "multiplier"), mult.imag,
                          {"long_name": "Floquet multiplier, imaginary part", "units": "1"}),
    }


def catalogue_dataset(cat: Catalogue, system: System, integrator: IntegratorSettings):
    """The catalogue as an xarray Dataset (attractors, right body, combinations, curves)."""
    import xarray as xr

    check_bodies(system.bodies, "catalogue_dataset (left and right attractors)")
    problem = body_problem(system, cat.values, SHOOTING)
    T = problem.period
    n = len(cat.attractors)
    max_p = max((a.period for a in cat.attractors), default=1)
    pts = np.full((n, max_p, 2), np.nan)
    curves = np.full((n, max_p * CURVE_SAMPLES, 2), np.nan)
    mult = np.full((n, 2), np.nan + 0j)
    for i, a in enumerate(cat.attractors):
        pts[i, : a.period] = a.points
        curves[i, : a.period * CURVE_SAMPLES] = _curve(problem, a.points[0], 0.0, a.period, 1.0)
        mult[i, : a.multipliers.size] = a.multipliers
    data = {
        "attractor_name": (("attractor",), [a.name for a in cat.attractors]),
        **attractor_variables(cat.attractors, pts, curves, mult),
    }
    coords = {
        "attractor": np.array([a.number for a in cat.attractors], dtype=np.int64),
        "body_variable": ["x", "v"],
        "point": np.arange(max_p),
        "curve_sample": np.arange(max_p * CURVE_SAMPLES),
        "multiplier": [0, 1],
    }
    attrs = {"analysis": "catalogue", "n_samples": cat.n_samples, "forcing_period": T,
             "catalogue_source": cat.source,
             "curve_samples_per_period": CURVE_SAMPLES,
             **{f"count_{k}": v for k, v in cat.counts.items()}}
    if system.bodies == 2:
        sign = system.extra["right_sign"]
        lag = ((cat.values["phi"] - system.extra["right_phase"]) / (2 * np.pi) * T) % T
        rpts = np.full((n, max_p, 2), np.nan)
        rcurves = np.full((n, max_p * CURVE_SAMPLES, 2), np.nan)
        for i, b in enumerate(cat.right):
            rpts[i, : b.period] = b.points
            rcurves[i, : b.period * CURVE_SAMPLES] = _curve(problem, b.points[0], lag,
                                                            b.period, sign)
        data["right_points"] = (("attractor", "point", "body_variable"), rpts,
                                {"long_name": "right body's section points, canonical order",
                                 "units": "1"})
        data["right_curve"] = (("attractor", "curve_sample", "body_variable"), rcurves,
                               {"long_name": "right body's dense orbit from point 0 at t = 0",
                                "units": "1"})
        m = len(cat.combinations)
        max_q = max((c.orbit.shape[0] for c in cat.combinations), default=1)
        orbits = np.full((m, max_q, 4), np.nan)
        for i, c in enumerate(cat.combinations):
            orbits[i, : c.orbit.shape[0]] = c.orbit
        data.update({
            "combination_name": (("combination",), [c.name for c in cat.combinations]),
            "combination_left": (("combination",), [c.left.number for c in cat.combinations]),
            "combination_right": (("combination",), [c.right.number for c in cat.combinations]),
            "combination_shift": (("combination",), [c.shift for c in cat.combinations],
                                  {"long_name": "shift s = (k - j) mod gcd(pl, pr)"}),
            "combination_period": (("combination",), [c.orbit.shape[0]
                                                      for c in cat.combinations],
                                   {"units": "forcing periods"}),
            "combination_orbit": (("combination", "joint_point", "variable"), orbits,
                                  {"long_name": "joint section points (x1, v1, x2, v2)",
                                   "units": "1"}),
        })
        coords.update({"combination": np.arange(m), "joint_point": np.arange(max_q),
                       "variable": ["x1", "v1", "x2", "v2"]})
        attrs["phi"] = float(cat.values["phi"])
    return xr.Dataset(data, coords=coords, attrs=attrs)


def search_shares(ds) -> np.ndarray:
    """(attractor,) each attractor's share of the one-body search (SEARCH_SHARE), from a
    result of any date (OLD_SEARCH_SHARE before the rename)."""
    return ds[SEARCH_SHARE if SEARCH_SHARE in ds else OLD_SEARCH_SHARE].values


def catalogue_from_dataset(ds, model: str = "", values: dict | None = None) -> Catalogue:
    """Rebuild a :class:`Catalogue` from its dataset (for labelling later runs)."""
    attractors = []
    right = []
    for i, number in enumerate(ds["attractor"].values):
        p = int(ds["attractor_period"].values[i])
        mult = ds["multiplier_re"].values[i] + 1j * ds["multiplier_im"].values[i]
        common = dict(number=int(number), period=p,
                      amplitude=float(ds["attractor_amplitude"].values[i]),
                      multipliers=mult[np.isfinite(mult)],
                      share=float(search_shares(ds)[i]),
                      residual=float(ds["attractor_residual"].values[i]))
        attractors.append(Attractor(points=ds["attractor_points"].values[i, :p], **common))
        if "right_points" in ds:
            right.append(Attractor(points=ds["right_points"].values[i, :p], **common))
    by_number_l = {a.number: a for a in attractors}
    by_number_r = {a.number: a for a in right}
    combos = []
    if "combination_name" in ds:
        for i in range(ds.sizes["combination"]):
            q = int(ds["combination_period"].values[i])
            combos.append(Combination(by_number_l[int(ds["combination_left"].values[i])],
                                      by_number_r[int(ds["combination_right"].values[i])],
                                      int(ds["combination_shift"].values[i]),
                                      ds["combination_orbit"].values[i, :q]))
    counts = {k[len("count_"):]: int(v) for k, v in ds.attrs.items() if k.startswith("count_")}
    return Catalogue(model, dict(values or {}), tuple(attractors), tuple(right), tuple(combos),
                     counts, int(ds.attrs.get("n_samples", 0)))
