"""The catalogue of a chain: its bodies' attractors, their products, and which survive.

While no stop engages, the bodies of a chain (``systems/chain.py``) are independent forced
oscillators (each with its own kinks): every non-impacting solution of the chain is a
*product* of one periodic attractor per body with shifts (``chain_dcrit``), and every
product is a solution of the chain exactly when no stop touches it: each stop's critical
value on the product (``chain_dcrit.critical_values``) lies short of the stop (between
bodies ``d > d_crit``; a wall on the right ``wall > max x_i``, on the left
``wall < min x_i``).

1. Each body is searched alone (the [catalogue] states, (N, 2), through ``search``: the
   store passes the catalogue cache), its attractors refined and numbered by (period,
   amplitude) as one body's are (``catalogue.body_catalogue``).
2. The products are every combination of one attractor per body with every canonical
   shift tuple, in code order (``catalogue.combination_names``: the first body's
   attractors slowest, shifts lexicographic), named with the n-body names
   (``labels.bodies_label``: ``L1^1 R1-0^2`` for two bodies, ``B1:P2^1 B2:P1-0^2 ...``
   for more) and matched by ``catalogue.label_orbit`` (each body's section point).
3. Each product's critical value per stop, and whether it survives at the chain's values.

:class:`ChainCatalogue` offers what the sweep and the labels read of a preset's
``Catalogue`` (``per_body``, ``names``, ``orbits``, ``attractors``, ``counts``,
``n_samples``, ``source``); :func:`chain_catalogue_dataset` is its result form.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from ..config import IntegratorSettings
from ..systems import System
from ..systems.base import forcing_period_of
from .catalogue import (
    CURVE_SAMPLES,
    SHOOTING,
    Attractor,
    BodySearch,
    attractor_variables,
    body_catalogue,
)
from .chain_dcrit import (
    Product,
    body_problem,
    chain_model,
    critical_values,
    products,
    stop_coefficients,
    uncoupled_values,
)
from .engine import Problem, record_trajectory

# one body's search: (its one-body problem, states (N, 2), t0, match_tol, progress) ->
# BodySearch (``store.catalogues.cached_body_search`` reads it from the cache)
Search = Callable[..., BodySearch]


def computed_search(problem: Problem, states: np.ndarray, t0: float = 0.0,
                    match_tol: float = 1e-3, progress=None) -> BodySearch:
    """One body's search computed here (no cache)."""
    found, counts = body_catalogue(problem, states, t0, match_tol, progress)
    return BodySearch(found, counts, len(states), "computed")


@dataclass(frozen=True)
class ChainCatalogue:
    """A chain's catalogue at one parameter point ``values`` (the chain's names).

    per_body : n tuples, body i's attractors (numbered 1, 2, ... in its own search)
    products : the products in code order (``names``), each with its joint orbit
        (q, 2n) at t = 0 mod T
    critical : (n_products, n_stops) float64, each stop's critical value on each
        product (``chain_dcrit``: between bodies the gap below which it touches, for a
        wall the critical wall position)
    survives : (n_products,) bool, no stop touches the product at ``values``
    body_counts : per body, its search's outcomes ('converged', 'unresolved', 'diverged')
    n_samples : initial conditions per body's search
    """

    model: str
    values: dict
    per_body: tuple[tuple[Attractor, ...], ...]
    products: tuple[Product, ...]
    critical: np.ndarray
    survives: np.ndarray
    body_counts: tuple[dict[str, int], ...]
    n_samples: int
    source: str = "computed"

    @property
    def bodies(self) -> int:
        return len(self.per_body)

    @property
    def attractors(self) -> tuple[Attractor, ...]:
        """Every body's attractors, body after body (empty when some body has none: then
        the chain has no non-impacting solution)."""
        if not all(self.per_body):
            return ()
        return tuple(a for atts in self.per_body for a in atts)

    @property
    def names(self) -> tuple[str, ...]:
        """The products' names in code order (label codes 0, 1, ...)."""
        return tuple(p.name for p in self.products)

    @property
    def orbits(self) -> dict[str, np.ndarray]:
        """{name: joint section points (q, 2n)} of every product, in code order."""
        return {p.name: p.orbit for p in self.products}

    @property
    def counts(self) -> dict[str, int]:
        """The outcomes of every body's search, summed."""
        out: dict[str, int] = {}
        for counts in self.body_counts:
            for k, v in counts.items():
                out[k] = out.get(k, 0) + v
        return out

    @property
    def surviving(self) -> tuple[Product, ...]:
        """The products that are solutions of the chain at ``values``."""
        return tuple(p for p, ok in zip(self.products, self.survives, strict=True) if ok)

    def product(self, name: str) -> Product:
        for p in self.products:
            if p.name == name:
                return p
        raise KeyError(name)


def stop_values(system: System, values: dict) -> np.ndarray:
    """(n_stops,) each stop's own value at ``values``: its gap, or its wall's position."""
    return np.array([float(values[f"stop.{s}.{'wall' if stop.wall else 'd'}"])
                     for s, stop in enumerate(chain_model(system).stops, 1)])


def survival(system: System, values: dict, critical: np.ndarray) -> np.ndarray:
    """(n_products,) bool: every stop lies beyond the product's critical value
    (``critical`` (n_products, n_stops)): ``sign * (stop - critical) > 0`` with the stop's
    sign (+1 between bodies and a right wall, -1 a left wall)."""
    n_stops = len(chain_model(system).stops)
    if n_stops == 0:
        return np.ones(critical.shape[0], dtype=bool)
    signs = np.array([stop_coefficients(system, s)[1] for s in range(1, n_stops + 1)])
    return np.all(signs * (stop_values(system, values) - critical) > 0.0, axis=1)


def build_chain_catalogue(system: System, values: dict, integrator: IntegratorSettings,
                          states: np.ndarray, t0: float = 0.0, match_tol: float = 1e-3,
                          progress=None, search: Search = computed_search,
                          samples: int = 512) -> ChainCatalogue:
    """The catalogue of the chain ``system`` at ``values`` (its parameter names).

    states : (N, 2) initial (x, v) of each body's search, imposed at ``t0``;
    ``progress`` gets one tick per state and body (N * n in all); ``search`` runs one
    body's search (default: computed here); ``samples`` per forcing period of the joint
    orbits where the critical values are bracketed.
    """
    found = [search(body_problem(system, values, i, integrator), states, t0, match_tol,
                    progress) for i in range(1, system.bodies + 1)]
    return extend_chain_catalogue(system, values, found, samples)


def extend_chain_catalogue(system: System, values: dict, found: list[BodySearch],
                           samples: int = 512) -> ChainCatalogue:
    """The catalogue from each body's search (``found``, in body order): the products,
    their critical values and which survive at ``values``."""
    per_body = tuple(tuple(f.attractors) for f in found)
    found_products = tuple(products(per_body))
    n_stops = len(chain_model(system).stops)
    critical = np.zeros((len(found_products), n_stops))
    if found_products and n_stops:
        problem = Problem(system, uncoupled_values(system, values), SHOOTING)
        critical = np.array([critical_values(problem, p, samples) for p in found_products])
    sources = {f.source for f in found}
    source = sources.pop() if len(sources) == 1 else ", ".join(f.source for f in found)
    return ChainCatalogue("chain", dict(values), per_body, found_products, critical,
                          survival(system, values, critical),
                          tuple(dict(f.counts) for f in found),
                          found[0].n_states if found else 0, source)


def at_values(catalogue: ChainCatalogue, system: System, values: dict) -> ChainCatalogue:
    """The same catalogue at other stop values (the bodies' parameters unchanged): the
    products' critical values stay, which survive follows the stops at ``values``."""
    return replace(catalogue, values=dict(values),
                   survives=survival(system, values, catalogue.critical))


# ------------------------------------------------------------------ dataset form

def body_attractor_name(body: int, attractor: Attractor) -> str:
    """``B<body>:P<period>^<number>``: one body's attractor, as its token in a name."""
    return f"B{body}:P{attractor.period}^{attractor.number}"


def chain_catalogue_dataset(cat: ChainCatalogue, system: System) -> xr.Dataset:
    """The chain's catalogue as a Dataset.

    Dims: ``attractor`` (every body's attractors, body after body), ``point``,
    ``body_variable`` (x, v), ``curve_sample``, ``multiplier``; ``combination`` (the
    products in code order), ``joint_point``, ``variable`` (the chain's state names),
    ``stop``, ``body``.

    attractor_body, attractor_number, attractor_name (``B2:P1^1``), attractor_period,
    attractor_amplitude, attractor_points (attractor, point, body_variable) at t = 0 mod
    T, attractor_curve (dense, from point 0), multiplier_re / _im, the search share;
    combination_name, combination_period, combination_attractor (combination, body: the
    attractor number of each body), combination_shift (combination, body),
    combination_orbit (combination, joint_point, variable), combination_critical
    (combination, stop), combination_survives and combination_stable (0/1);
    stop_value (stop): each stop's gap or wall at the catalogue's values.
    """
    flat = [(i, a) for i, atts in enumerate(cat.per_body, 1) for a in atts]
    n = len(flat)
    max_p = max((a.period for _, a in flat), default=1)
    pts = np.full((n, max_p, 2), np.nan)
    curves = np.full((n, max_p * CURVE_SAMPLES, 2), np.nan)
    mult = np.full((n, 2), np.nan + 0j)
    for k, (body, a) in enumerate(flat):
        problem = body_problem(system, cat.values, body, SHOOTING)
        pts[k, : a.period] = a.points
        traj = record_trajectory(problem, a.points[0], 0.0, a.period, CURVE_SAMPLES)
        curves[k, : a.period * CURVE_SAMPLES] = traj.y[: a.period * CURVE_SAMPLES]
        mult[k, : a.multipliers.size] = a.multipliers
    m = len(cat.products)
    max_q = max((p.orbit.shape[0] for p in cat.products), default=1)
    orbits = np.full((m, max_q, system.dim), np.nan)
    for k, p in enumerate(cat.products):
        orbits[k, : p.orbit.shape[0]] = p.orbit
    stops = chain_model(system).stops
    data = {
        "attractor_body": (("attractor",), np.array([b for b, _ in flat], dtype=np.int64)),
        "attractor_number": (("attractor",), np.array([a.number for _, a in flat],
                                                      dtype=np.int64)),
        "attractor_name": (("attractor",), [body_attractor_name(b, a) for b, a in flat]),
        **attractor_variables([a for _, a in flat], pts, curves, mult),
        "combination_name": (("combination",), [p.name for p in cat.products]),
        "combination_period": (("combination",), [p.orbit.shape[0] for p in cat.products],
                               {"units": "forcing periods"}),
        "combination_attractor": (("combination", "body"),
                                  np.array([[a.number for a in p.attractors]
                                            for p in cat.products],
                                           dtype=np.int64).reshape(m, cat.bodies),
                                  {"long_name": "each body's attractor number"}),
        "combination_shift": (("combination", "body"),
                              np.array([p.shifts for p in cat.products],
                                       dtype=np.int64).reshape(m, cat.bodies),
                              {"long_name": "each body's index on its attractor at the "
                                            "section where body 1 is at index 0"}),
        "combination_orbit": (("combination", "joint_point", "variable"), orbits,
                              {"long_name": "joint section points", "units": "1"}),
        "combination_critical": (("combination", "stop"), cat.critical.reshape(m, len(stops)),
                                 {"long_name": "each stop's critical value on the product "
                                               "(between bodies: max x_i - x_j; a wall: the "
                                               "critical wall position)", "units": "1"}),
        "combination_survives": (("combination",), cat.survives.astype(np.int8),
                                 {"long_name": "1: no stop touches it at the scene's values"}),
        "combination_stable": (("combination",),
                               np.array([all(a.stable for a in p.attractors)
                                         for p in cat.products], dtype=np.int8),
                               {"long_name": "1: every body's attractor is stable"}),
        "stop_value": (("stop",), stop_values(system, cat.values),
                       {"long_name": "each stop's gap (between bodies) or wall position",
                        "units": "1"}),
    }
    coords = {
        "attractor": np.arange(n), "body_variable": ["x", "v"], "point": np.arange(max_p),
        "curve_sample": np.arange(max_p * CURVE_SAMPLES), "multiplier": [0, 1],
        "combination": np.arange(m), "joint_point": np.arange(max_q),
        "variable": list(system.state_names), "stop": np.arange(1, len(stops) + 1),
        "body": np.arange(1, cat.bodies + 1),
    }
    attrs = {"analysis": "catalogue", "model": "chain", "bodies": cat.bodies,
             "n_samples": cat.n_samples, "catalogue_source": cat.source,
             "forcing_period": forcing_period_of(cat.values["w"]),
             "curve_samples_per_period": CURVE_SAMPLES,
             **{f"count_{k}": v for k, v in cat.counts.items()}}
    return xr.Dataset(data, coords=coords, attrs=attrs)
