"""What a worker runs: one chunk of a sweep, from a shared context. No I/O.

The context (grid, initial states, catalogues, integrator settings) is sent to each
worker once; a chunk is then only its flat index range.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analysis.catalogue import Catalogue, label_orbit
from ..analysis.chain_catalogue import stop_values
from ..analysis.chain_dcrit import stop_coefficients
from ..analysis.engine import KnownOrbits, Problem, RecurrenceCells, classify_state
from ..analysis.impacting import ImpactingOrbits
from ..analysis.labels import code_of
from ..analysis.section_follow import FAILED, PERIODIC, RECURRENT, KnownSets, follow_section
from ..config import Grid, IntegratorSettings
from ..config.axes import catalogue_key
from ..kernels.codes import (
    BY_CELLS,
    BY_KNOWN_ORBIT,
    BY_OWN_REPEAT,
    BY_SECTION,
    CONVERGED,
    MIXED_CELL,
    NO_ORBIT,
    UNRESOLVED,
    label_code_of_status,
)
from ..systems import System, get_system
from ..systems.chain import ChainModel, chain_system
from .second_stage import pack

CAPTURE_MARGIN = 10.0  # d - d_crit must exceed this many capture radii
# Recurrence cells start an empty table at every grid point and every CELL_BLOCK flat
# indices, and chunks hold whole blocks (plan.chunk_size_for): labels do not depend on how a
# run is cut into chunks. 256: the table sizes bench_settings.py measured the cells with.
CELL_BLOCK = 256

RESULT_FIELDS = {  # name -> dtype of the per-trajectory arrays a chunk returns
    "label": np.int32,
    "status": np.int8,
    "period": np.int16,
    "periods_used": np.int32,
    "contacts": np.int32,
    "max_penetration": np.float32,
    "captured": np.int8,
    "steps": np.int32,
    "stiff_steps": np.int32,
}


@dataclass(frozen=True)
class SweepContext:
    """Everything a worker needs, shared by all chunks.

    states : (n_ic, dim) initial states; t0 : (n_ic,) start times per sample, or None to
    take them from the grid's t0 axis; catalogues : one per distinct value of the
    catalogue's parameters over the grid (``config.axes.catalogue_key``: phi, and the
    body's parameters when they are swept); known : per catalogue key, the stable
    non-impacting orbits a trajectory may be captured by, as (section points (q, dim) in
    time order, d_crit) pairs, a chain's (points, each stop's critical value (n_stops,))
    (None: no capture); chain : the structure of a chain
    (``model = "chain"``: its system is built from it), None for a preset.
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
    known: dict | None = None
    chain: ChainModel | None = None

    def system(self) -> System:
        """The model: a preset from the registry, or the chain of ``chain``."""
        if self.chain is not None:
            return chain_system(self.chain)
        return get_system(self.model, self.bodies)

    def known_orbits(self, values: dict) -> KnownOrbits | None:
        """The known orbits that exist at these parameter values, safely clear of contact:
        d_crit below d by CAPTURE_MARGIN times the capture radius (a captured trajectory
        must not touch the stop while it settles)."""
        s = self.integrator
        if self.known is None or s.capture_tol <= 0.0:
            return None
        if self.chain is not None:
            keep = self._chain_known(values)
        else:
            d = float(values.get("d", np.inf))
            keep = []
            for points, d_crit in self.known.get(self.catalogue_key(values), ()):
                radius = s.capture_tol * max(1.0, float(np.max(np.abs(points))))
                if d_crit + CAPTURE_MARGIN * radius < d:
                    keep.append((points, d_crit - d))
        return KnownOrbits.from_orbits([o for o, _ in keep], [g for _, g in keep],
                                       s.capture_tol, s.capture_hits, self.states.shape[1])

    def _chain_known(self, values: dict) -> list[tuple[np.ndarray, float]]:
        """A chain's known orbits at ``values``: (points, max of the contact functions)
        of the products every stop clears by CAPTURE_MARGIN capture radii (each stop's
        contact function peaks at ``sign * (critical - stop)``, ``chain_dcrit``)."""
        system = self.system()
        stops = stop_values(system, values)
        signs = np.array([stop_coefficients(system, i)[1] for i in range(1, stops.size + 1)])
        keep = []
        for points, critical in self.known.get(self.catalogue_key(values), ()):
            radius = self.integrator.capture_tol * max(1.0, float(np.max(np.abs(points))))
            clearance = signs * (stops - critical)  # > 0: the stop is not reached
            if np.all(clearance > CAPTURE_MARGIN * radius):
                keep.append((points, -float(np.min(clearance, initial=np.inf))))
        return keep

    def catalogue_key(self, values: dict) -> tuple[float, ...]:
        """The key of ``catalogues`` and ``known`` that serves these parameter values."""
        return catalogue_key(self.system(), values)

    def point_values(self, point: int) -> tuple[dict, float]:
        """(parameter values, grid t0) of grid point number ``point``."""
        axes = self.grid.point(point)
        values = dict(self.values)
        for axis in self.grid.swept:
            if axis != "t0":
                values[axis] = axes[axis]
        return values, axes["t0"]


def _orbit_code(orbit: np.ndarray, is_impacting: bool, point: int, catalogue: Catalogue,
                impacting: ImpactingOrbits, names: dict[str, int], label_tol: float) -> int:
    """The label code of a periodic ``orbit`` (section points (q, dim)) found at grid
    ``point``, by either stage: its catalogue label, or for an impacting orbit its number
    among this chunk's distinct impacting orbits of that period."""
    label = label_orbit(catalogue, orbit, is_impacting, label_tol)
    if is_impacting:
        label = impacting.label(point, orbit)
    return code_of(label, names)


def run_chunk(ctx: SweepContext, start: int, stop: int) -> dict:
    """Classify and label flat indices [start, stop).

    Returns per-trajectory arrays (RESULT_FIELDS) and ``orbits``: for each (grid point,
    label code) first seen in this chunk, (flat index, section points (q, dim)). Distinct
    impacting orbits of one period at one point take distinct codes, numbered in this
    chunk's order (``analysis.impacting``; the parent renumbers them over the result). With
    recurrence cells (``cell_size > 0``) each grid point and each CELL_BLOCK of flat
    indices starts an empty table, so a result does not depend on the chunk boundaries
    as long as they fall on blocks.

    A trajectory the first pass leaves ``UNRESOLVED`` goes on to the second stage
    (``analysis.section_follow``, when ``section_periods > 0``): a periodic orbit it
    finds is labelled here; a recurrent set keeps ``UNRESOLVED_LABEL`` and is returned
    in the ``second_stage.SECTION_ARRAYS`` for the parent to name. With recurrence cells,
    the recurrent sets found earlier in the same table's block are known
    (``section_follow.KnownSets``): a trajectory whose section points land in one's
    cells stops there. ``periods_used`` counts both stages; ``steps`` the first pass's
    only.
    """
    n = stop - start
    out = {k: np.zeros(n, dtype=t) for k, t in RESULT_FIELDS.items()}
    orbits: dict[tuple[int, int], tuple[int, np.ndarray]] = {}
    system = ctx.system()
    n_ic = ctx.states.shape[0]
    s = ctx.integrator
    problem = None
    known = None
    cells = None
    summary: dict[int, tuple[int, int, float]] = {}  # code -> (period, contacts, max_pen)
    recurrent = []  # (flat, grid point, SectionFollow) of the second stage's recurrent ones
    sets = None  # recurrent sets found earlier in the block (with the cells only: the
    # verification, which turns cells off, follows every trajectory in full)
    current = -1
    catalogue: Catalogue | None = None
    names = {name: i for i, name in enumerate(ctx.names)}  # code_of looks names up here:
    # many bodies' catalogues name thousands of combinations
    impacting = ImpactingOrbits(lambda at: Problem(system, ctx.point_values(at)[0], s),
                                ctx.label_tol)  # numbered in this chunk's order
    for k in range(n):
        flat = start + k
        point, ic = divmod(flat, n_ic)
        if point != current:
            values, grid_t0 = ctx.point_values(point)
            problem = Problem(system, values, s)
            catalogue = ctx.catalogues[ctx.catalogue_key(values)]
            known = ctx.known_orbits(values)
            current = point
        if s.cell_size > 0.0 and (k == 0 or ic == 0 or flat % CELL_BLOCK == 0):
            cells = RecurrenceCells(s.cell_size, s.cell_hits, s.max_periods)
            summary = {}  # what cells name comes from this table's trajectories only
            sets = KnownSets()  # the recurrent sets of this block, as the cells
        t0 = grid_t0 if ctx.t0 is None else float(ctx.t0[ic])
        cls = classify_state(problem, ctx.states[ic], t0, known, cells)
        how = BY_KNOWN_ORBIT if cls.captured != NO_ORBIT else BY_OWN_REPEAT
        if cls.status == CONVERGED and cls.cell_code != MIXED_CELL:
            code = cls.cell_code
            how = BY_CELLS
            period, contacts, max_pen = summary[code]
        elif cls.status == CONVERGED:
            code = _orbit_code(cls.orbit, cls.impacting, point, catalogue, impacting, names,
                               ctx.label_tol)
            orbits.setdefault((point, code), (flat, cls.orbit))
            period, contacts, max_pen = cls.period, cls.contacts, cls.max_penetration
            summary.setdefault(code, (period, contacts, max_pen))
        else:
            code = label_code_of_status(cls.status)
            period, contacts, max_pen = cls.period, cls.contacts, cls.max_penetration
        status, used = cls.status, cls.periods_used
        if cls.status == UNRESOLVED and s.section_periods > 0:  # the second stage
            follow = follow_section(problem, ctx.states[ic], t0, cls.periods_used, sets)
            used += follow.periods
            if follow.outcome == FAILED:
                status = follow.status
                code = label_code_of_status(status)
            elif follow.outcome == PERIODIC:
                status, how = CONVERGED, BY_SECTION
                code = _orbit_code(follow.orbit, follow.impacting, point, catalogue, impacting,
                                   names, ctx.label_tol)
                orbits.setdefault((point, code), (flat, follow.orbit))
                period, contacts, max_pen = len(follow.orbit), follow.contacts, follow.max_g
            elif follow.outcome == RECURRENT:  # named by the parent (second_stage.relabel)
                how = BY_SECTION
                contacts, max_pen = follow.contacts, follow.max_g
                recurrent.append((flat, point, follow))
                if sets is not None:
                    sets.learn(follow)
        if cells is not None and cls.status == CONVERGED:
            cells.remember(cls, code)
        out["label"][k] = code
        out["status"][k] = status
        out["period"][k] = period
        out["periods_used"][k] = used
        out["contacts"][k] = contacts
        out["max_penetration"][k] = max_pen
        out["captured"][k] = how
        out["steps"][k] = cls.counters["steps"]
        out["stiff_steps"][k] = cls.counters["stiff_steps"]
    out["orbits"] = orbits
    out.update(pack(recurrent, ctx.states.shape[1]))
    return out
