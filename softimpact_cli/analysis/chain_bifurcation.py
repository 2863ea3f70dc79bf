"""Bifurcation diagrams of a chain: each non-impacting product followed along any parameter.

The branches start on the chain's non-impacting solutions at the scene's values: the
products of the bodies' attractors (``chain_dcrit``; named there, one token per body).
The parameter (any name of ``System.parameters``: ``stop.2.d``, ``phi.3``, ``F.1``,
``w``...) takes its values in turn, each step from the previous step's end state, and the
trajectory is classified. A branch lives while the state stays on a non-impacting orbit of
its period; along a stop's own parameter (its gap, wall, ``k_c``, ``c_c``...) the orbit
cannot move, so it must also stay the product's own orbit.

Destruction: along a stop's gap or wall it is located at grazing, the stop's critical
value on the product's refined orbit (``chain_dcrit.critical_values``); along any other
parameter, to the step (the first step without it).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config import IntegratorSettings
from ..kernels.codes import (
    CONVERGED,
    IMPACTING_BASE,
    UNMATCHED_BASE,
    label_code_of_status,
)
from .bifurcation import UNRESOLVED_POINTS, orbit_distance
from .chain_dcrit import TIGHT, Product, chain_model, critical_values, uncoupled_values
from .engine import Problem, classify_state, record_trajectory

SAME_ORBIT = 1e-6  # section points of a product's orbit, relative to its size


def stop_of(parameter: str) -> tuple[int, str] | None:
    """(stop number, key) of a stop's parameter ``stop.s.key``, else None."""
    parts = parameter.split(".")
    if len(parts) == 3 and parts[0] == "stop":
        return int(parts[1]), parts[2]
    return None


def follow_product(system, values: dict, integrator: IntegratorSettings, product: Product,
                   parameter: str, steps: np.ndarray) -> tuple[list[dict], float]:
    """One branch along ``parameter``: per-step records (points (q, 2n), impacting,
    period, alive) and where it is destroyed (NaN: never)."""
    orbit = product.orbit
    q = orbit.shape[0]
    own_stop = stop_of(parameter)
    state = orbit[0].copy()
    alive, destroyed_at, records = True, np.nan, []
    for value in steps:
        problem = Problem(system, {**values, parameter: float(value)}, integrator)
        cls = classify_state(problem, state, 0.0)
        impacting = bool(cls.status == CONVERGED and (cls.contacts > 0 or cls.impacting))
        if cls.status == CONVERGED:
            points = cls.orbit
            state = cls.orbit[-1].copy()
        else:
            points = record_trajectory(problem, state, 0.0, UNRESOLVED_POINTS, 1).section_y[1:]
            if np.all(np.isfinite(points[-1])):
                state = points[-1].copy()
        on_branch = cls.status == CONVERGED and cls.period == q and not impacting
        if on_branch and own_stop is not None:  # a stop's parameter cannot move the orbit
            on_branch = orbit_distance(orbit, points) <= SAME_ORBIT * max(
                1.0, float(np.max(np.abs(orbit))))
        if alive and not on_branch:
            alive = False
            if own_stop is not None and own_stop[1] in ("d", "wall") and records:
                grazing = Problem(system, uncoupled_values(system, values), TIGHT)
                destroyed_at = float(critical_values(grazing, product)[own_stop[0] - 1])
            elif records:
                destroyed_at = float(value)
        records.append({"points": points, "impacting": impacting, "period": cls.period,
                        "alive": alive, "status": cls.status})
    return records, destroyed_at


def step_code(record: dict, own: int) -> int:
    """The label code of a step: ``own`` (the branch's index) while on it, then impacting
    P{q} or unmatched P{q} (a chain's other solutions are not named yet), unresolved or
    diverged."""
    if record["alive"]:
        return own
    if record["status"] != CONVERGED:
        return label_code_of_status(record["status"])
    return (IMPACTING_BASE if record["impacting"] else UNMATCHED_BASE) + record["period"]


def after_destruction(records: list[dict], steps: np.ndarray, products: list[Product]
                      ) -> tuple[str, list[float]]:
    """(falls_to, impacting_range): the first non-impacting solution a branch reaches after
    its destruction (a product by its orbit, else "unmatched P<q>"; "" none) and the
    [high, low] values of the impacting run right after it (NaN: none)."""
    dead = [j for j, r in enumerate(records) if not r["alive"]]
    run: list[float] = []
    for j in dead:
        r = records[j]
        if r["impacting"] or r["status"] != CONVERGED:
            run.append(float(steps[j]))
            continue
        for p in products:
            if p.orbit.shape == r["points"].shape and orbit_distance(p.orbit, r["points"]) \
                    <= 1e-3 * max(1.0, float(np.max(np.abs(p.orbit)))):
                return p.name, _range(run)
        return f"unmatched P{r['period']}", _range(run)
    return "", _range(run)


def _range(run: list[float]) -> list[float]:
    return [max(run), min(run)] if run else [np.nan, np.nan]


def chain_bifurcation_dataset(system, values: dict, integrator: IntegratorSettings,
                              products: list[Product], parameter: str, steps: np.ndarray,
                              progress=None) -> xr.Dataset:
    """Dims (branch, step, point, body): every body's section displacements per step of
    ``parameter`` and branch; ``label`` (:func:`step_code`), ``alive`` (still the
    product's branch), ``impacting``,
    ``period``, ``destroyed_at`` per branch."""
    n = chain_model(system).bodies
    followed = []
    for product in products:
        followed.append(follow_product(system, values, integrator, product, parameter,
                                       steps))
        if progress is not None:
            progress(1)
    width = max([1] + [r["points"].shape[0] for records, _ in followed for r in records])
    nb, ns = len(products), len(steps)
    x = np.full((nb, ns, width, n), np.nan)
    alive = np.zeros((nb, ns), dtype=np.int8)
    impacting = np.zeros((nb, ns), dtype=np.int8)
    period = np.zeros((nb, ns), dtype=np.int16)
    code = np.zeros((nb, ns), dtype=np.int32)
    for i, (records, _) in enumerate(followed):
        for j, r in enumerate(records):
            code[i, j] = step_code(r, i)
            pts = r["points"]
            x[i, j, : pts.shape[0]] = pts[:, 0::2]
            alive[i, j], impacting[i, j], period[i, j] = r["alive"], r["impacting"], r["period"]
    return xr.Dataset(
        {"section_x": (("branch", "step", "point", "body"), x,
                       {"long_name": "every body's section displacements", "units": "1"}),
         "label": (("branch", "step"), code,
                   {"long_name": "solution reached (code: the branch's index while on it)"}),
         "alive": (("branch", "step"), alive, {"long_name": "1: still on its branch"}),
         "impacting": (("branch", "step"), impacting,
                       {"long_name": "1: contact on the orbit"}),
         "period": (("branch", "step"), period, {"units": "forcing periods"}),
         "branch_name": (("branch",), np.array([p.name for p in products], dtype=object)),
         "falls_to": (("branch",), np.array([after_destruction(r, steps, products)[0]
                                             for r, _ in followed], dtype=object)),
         "impacting_range": (("branch", "bound"),
                             np.array([after_destruction(r, steps, products)[1]
                                       for r, _ in followed], dtype=float).reshape(nb, 2),
                             {"long_name": f"{parameter} range of impacting states right "
                                           "after destruction (high, low)"}),
         "destroyed_at": (("branch",), np.array([d for _, d in followed], dtype=float),
                          {"long_name": f"{parameter} where the product is destroyed "
                                        "(a stop's gap or wall: at grazing; else to the "
                                        "step)"})},
        coords={"branch": np.arange(nb), "step": ("step", np.asarray(steps, dtype=float)),
                "point": np.arange(width), "body": np.arange(1, n + 1),
                "bound": ["high", "low"]},
        attrs={"analysis": "bifurcation", "parameter": parameter},
    )
