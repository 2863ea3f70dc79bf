"""Critical gaps of a chain's non-impacting solutions, per stop.

While no stop engages, the bodies of a chain (``systems/chain.py``) are independent
forced oscillators, each with its own kinks: a non-impacting solution is a *product* of
one periodic attractor per body, body k's shifted by ``s_k`` forcing periods against body
1's, of joint period the lcm of the bodies' periods. For stop s its *critical value* is
the largest, over one joint period, of the stop's compression without its gap:

- between bodies i and j: ``d_crit = max (x_i - x_j)``; the product stays a solution of
  the chain (never touching stop s) iff the gap ``d > d_crit``;
- a wall on the right of body i: ``max x_i``, a wall on the left: ``min x_i``; the
  product survives iff the wall lies beyond it (right: ``wall > ...``; left:
  ``wall < ...``).

The maximum is bracketed on dense samples, then located as a root of the compression's
rate by the Illinois method on the flow itself (to 1e-12 in time), as
``critical_distance`` does for a pair.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..config import IntegratorSettings
from ..systems import System
from ..systems.chain import ChainModel, Kink, chain_system
from .catalogue import Attractor, body_catalogue, joint_orbit
from .critical_distance import NO_CONTACT_D, TIGHT, zero_of_rate
from .engine import Problem, flow, record_trajectory
from .labels import BodyToken, all_shifts, bodies_label

BODY_KEYS = ("m", "c", "k1", "k2", "F", "phi")


def chain_model(system: System) -> ChainModel:
    """The structure of a chain system (``System.extra["chain"]``)."""
    return system.extra["chain"]


def body_problem(system: System, values: dict, body: int,
                 integrator: IntegratorSettings) -> Problem:
    """Body ``body`` (1-based) of a chain alone, with its own kinks: a one-body chain."""
    model = chain_model(system)
    kinks = [(k, kink) for k, kink in enumerate(model.kinks, 1) if kink.body == body]
    alone = ChainModel(1, model.powers, tuple(Kink(1, kink.side) for _, kink in kinks), ())
    out = {"w": values["w"]}
    out.update({f"{key}.1": values[f"{key}.{body}"]
                for key in BODY_KEYS + tuple(f"k_x{p}" for p in model.powers)})
    for new, (k, _) in enumerate(kinks, 1):
        out[f"kink.{new}.x"] = values[f"kink.{k}.x"]
        out[f"kink.{new}.k"] = values[f"kink.{k}.k"]
    return Problem(chain_system(alone), out, integrator)


def uncoupled_values(system: System, values: dict) -> dict:
    """The chain's values with every stop out of reach (gaps and walls at 1e12)."""
    out = dict(values)
    for s, stop in enumerate(chain_model(system).stops, 1):
        if stop.wall:
            out[f"stop.{s}.wall"] = NO_CONTACT_D if stop.side == "right" else -NO_CONTACT_D
        else:
            out[f"stop.{s}.d"] = NO_CONTACT_D
    return out


@dataclass(frozen=True)
class Product:
    """A non-impacting solution: one attractor per body, body k at index ``shifts[k]`` of
    its orbit at section 0 (body 1 at 0); ``orbit`` (lcm, 2n) joint section points."""

    attractors: tuple[Attractor, ...]
    shifts: tuple[int, ...]
    orbit: np.ndarray

    @property
    def name(self) -> str:
        """The n-body name (``labels.bodies_label``): ``L1^1 R1-0^2`` for two bodies,
        ``B1:P2^1 B2:P1-0^2 B3:P2-1^1`` for three or more; one body: ``L1^1``."""
        return bodies_label([BodyToken(a.period, a.number, s)
                             for a, s in zip(self.attractors, self.shifts, strict=True)]).name


def products(per_body) -> list[Product]:
    """Every product of one attractor per body (``per_body``: each body's attractors) with
    every canonical shift tuple (``labels.all_shifts``: the joint orbits equal up to a time
    shift of whole periods counted once), in code order: that of
    ``catalogue.combination_names`` (the first body's attractors slowest, shifts
    lexicographic)."""
    return [Product(tuple(chosen), tuple(s), joint_orbit(chosen, s))
            for chosen in itertools.product(*per_body)
            for s in all_shifts([a.period for a in chosen])]


def stop_coefficients(system: System, stop_number: int) -> tuple[np.ndarray, float]:
    """(c, sign): the stop's compression without its gap is ``c . y`` (y the state, x at
    even indices); ``sign`` turns its maximum into the critical value (-1: a left wall,
    whose critical position is min x_i = -max(-x_i))."""
    model = chain_model(system)
    stop = model.stops[stop_number - 1]
    c = np.zeros(system.dim)
    if stop.wall:
        sign = 1.0 if stop.side == "right" else -1.0
        c[2 * (stop.body - 1)] = sign
        return c, sign
    c[2 * (stop.body - 1)] = 1.0
    c[2 * (stop.other - 1)] = -1.0
    return c, 1.0


def locate_maximum(problem: Problem, t: np.ndarray, y: np.ndarray, k: int, c: np.ndarray,
                   tol: float = 1e-12) -> float:
    """Refine the sampled maximum of ``c . y`` at index k: its value where its rate (the
    same combination of velocities) vanishes."""
    n = len(t)
    rate_c = np.roll(c, 1)  # x_i at 2i -> v_i at 2i + 1

    def state(time: float) -> np.ndarray:
        i = int(np.clip(np.searchsorted(t, time) - 1, 0, n - 1))
        return flow(problem, y[i], t[i], time)[1]

    lo, hi = max(k - 1, 0), min(k + 1, n - 1)
    a, b = t[lo], t[hi]
    fa, fb = float(rate_c @ y[lo]), float(rate_c @ y[hi])
    if not (fa >= 0.0 >= fb):  # a maximum at a sample (or at a kink): keep the sample
        return float(c @ y[k])
    t_star = zero_of_rate(lambda m: float(rate_c @ state(m)), a, b, fa, fb, tol)
    return float(c @ state(t_star))


def critical_values(problem: Problem, product: Product, samples: int = 512) -> np.ndarray:
    """(n_stops,) each stop's critical value on the product's joint orbit; ``problem`` is
    the uncoupled chain (:func:`uncoupled_values`)."""
    q = product.orbit.shape[0]
    traj = record_trajectory(problem, product.orbit[0], 0.0, q, samples)
    t, y = traj.t[:-1], traj.y[:-1]  # one joint period; the last sample repeats the first
    out = []
    for s in range(1, len(chain_model(problem.system).stops) + 1):
        c, sign = stop_coefficients(problem.system, s)
        k = int(np.argmax(y @ c))
        out.append(sign * locate_maximum(problem, t, y, k, c))
    return np.array(out)


def chain_critical_gaps(system: System, values: dict, states: np.ndarray, axis: str,
                        points, samples: int = 512, progress=None,
                        search: IntegratorSettings = TIGHT,
                        integrator: IntegratorSettings = TIGHT) -> xr.Dataset:
    """Every stop's critical value for every product at each value of ``axis`` (a chain
    parameter; the bodies' attractors are searched again from ``states`` (N, 2) at each;
    ``integrator``: the settings of the critical values' flows, ``softimpact check``
    tightens them).

    Returns d_crit(stop, combination, point) (NaN where that point has no such solution),
    combination_label(combination) and the axis values as coordinate ``point``.
    """
    n_stops = len(chain_model(system).stops)
    names: list[str] = []
    rows: dict[str, np.ndarray] = {}
    for p, value in enumerate(points):
        at = {**values, axis: float(value)}
        per_body = [body_catalogue(body_problem(system, at, i, search), states)[0]
                    for i in range(1, system.bodies + 1)]
        problem = Problem(system, uncoupled_values(system, at), integrator)
        for product in products(per_body):
            if product.name not in rows:
                names.append(product.name)
                rows[product.name] = np.full((n_stops, len(points)), np.nan)
            rows[product.name][:, p] = critical_values(problem, product, samples)
        if progress is not None:
            progress(1)
    d = np.stack([rows[n] for n in names], axis=1) if names else \
        np.zeros((n_stops, 0, len(points)))
    return xr.Dataset(
        {"d_crit": (("stop", "combination", "point"), d,
                    {"long_name": "critical value of each stop: the gap below which the "
                                  "non-impacting solution touches it (between bodies: max "
                                  "x_i - x_j), or for a wall the critical wall position "
                                  "(right: max x_i, left: min x_i)", "units": "1"}),
         "combination_label": (("combination",), np.array(names, dtype=object))},
        coords={"stop": np.arange(1, n_stops + 1), "combination": np.arange(len(names)),
                "point": ("point", np.asarray(points, dtype=float))},
        attrs={"axis": axis},
    )


def chain_products(system: System, values: dict, states: np.ndarray,
                   search: IntegratorSettings = TIGHT) -> list[Product]:
    """The chain's non-impacting solutions at ``values``: the products of its bodies'
    attractors, each body searched alone from ``states`` (N, 2)."""
    return products([body_catalogue(body_problem(system, values, i, search), states)[0]
                     for i in range(1, system.bodies + 1)])
