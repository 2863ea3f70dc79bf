"""What a worker runs: one chunk of a sweep, from a shared context. No I/O.

The context (grid, initial states, catalogues, integrator settings) is sent to each
worker once; a chunk is then only its flat index range.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analysis.catalogue import Catalogue, label_orbit
from ..config import GRID_AXES, Grid, IntegratorSettings
from ..engine import Problem, classify_state
from ..kernels.status import outcome
from ..labels import DIVERGED_CODE, UNRESOLVED_CODE, code_of
from ..systems import get_system

RESULT_FIELDS = {  # name -> dtype of the per-trajectory arrays a chunk returns
    "label": np.int32,
    "status": np.int8,
    "period": np.int16,
    "periods_used": np.int32,
    "contacts": np.int32,
    "max_penetration": np.float32,
}


@dataclass(frozen=True)
class SweepContext:
    """Everything a worker needs, shared by all chunks.

    states : (n_ic, dim) initial states; t0 : (n_ic,) start times per sample, or None to
    take them from the grid's t0 axis; catalogues : one per phi value of the grid.
    """

    model: str
    bodies: int
    values: dict
    integrator: IntegratorSettings
    grid: Grid
    states: np.ndarray
    t0: np.ndarray | None
    catalogues: dict
    names: tuple[str, ...]
    label_tol: float

    def point_values(self, point: int) -> tuple[dict, float]:
        """(parameter values, grid t0) of grid point number ``point``."""
        axes = self.grid.point(point)
        values = dict(self.values)
        for axis in GRID_AXES[:4]:
            if axis in self.grid.swept:
                values[axis] = axes[axis]
        return values, axes["t0"]


def run_chunk(ctx: SweepContext, start: int, stop: int) -> dict:
    """Classify and label flat indices [start, stop).

    Returns per-trajectory arrays (RESULT_FIELDS) and ``orbits``: for each (grid point,
    label code) first seen in this chunk, (flat index, section points (q, dim)).
    """
    n = stop - start
    out = {k: np.zeros(n, dtype=t) for k, t in RESULT_FIELDS.items()}
    orbits: dict[tuple[int, int], tuple[int, np.ndarray]] = {}
    system = get_system(ctx.model, ctx.bodies)
    n_ic = ctx.states.shape[0]
    problem = None
    current = -1
    catalogue: Catalogue | None = None
    for k in range(n):
        flat = start + k
        point, ic = divmod(flat, n_ic)
        if point != current:
            values, grid_t0 = ctx.point_values(point)
            problem = Problem(system, values, ctx.integrator)
            catalogue = ctx.catalogues[float(values.get("phi", 0.0))]
            current = point
        t0 = grid_t0 if ctx.t0 is None else float(ctx.t0[ic])
        cls = classify_state(problem, ctx.states[ic], t0)
        if cls.status == 0:
            label = label_orbit(catalogue, cls.orbit, cls.impacting, ctx.label_tol)
            code = code_of(label, ctx.names)
            if (point, code) not in orbits:
                orbits[(point, code)] = (flat, cls.orbit)
        else:
            code = UNRESOLVED_CODE if outcome(cls.status) == "unresolved" else DIVERGED_CODE
        out["label"][k] = code
        out["status"][k] = cls.status
        out["period"][k] = cls.period
        out["periods_used"][k] = cls.periods_used
        out["contacts"][k] = cls.contacts
        out["max_penetration"][k] = cls.max_penetration
    out["orbits"] = orbits
    return out
