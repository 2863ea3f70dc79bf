"""Grazing of each stop of a chain along a continued branch: one test function per stop.

A chain (``systems/chain.py``) has its stops' contact surfaces first among its switching
surfaces: stop s (1-based) is surface ``s - 1``, ``g_s(y) = A[s-1] . y + b[s-1]``, its
compression (``x_i - x_j - d`` between bodies, ``x_i - X`` at a wall on the right of body
i, ``X - x_i`` on its left). Its grazing test along a branch is

    psi_G,s = max over the orbit's p periods of g_s:

below 0 the orbit never touches stop s, at 0 it grazes it, above 0 it is in contact. A
stop's parameters (its gap, wall, ``k_c``, ``c_c``) do not move a non-impacting orbit, so
along a stop's gap the grazing lies exactly at the critical value ``chain_dcrit`` gives
(the largest compression without the gap on the uncoupled product).

As for a pair (``continuation_events``): signs are compared on the kernels' located
maximum of that surface alone (``engine.flow`` with the contact mask ``1 << (s - 1)``; the
integration itself watches every surface as always), and the zero is located on the
maximum refined by ``chain_dcrit.locate_maximum`` (a root of the compression's rate on
the flow, to 1e-12 in time), so the grazing parameter is exact to the integration
tolerance. The presets keep their one test (``continuation_events.gap``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kernels.codes import OK
from ..systems import System
from .chain_dcrit import locate_maximum
from .continuation import Point
from .engine import flow, record_trajectory
from .shooting import OrbitMap

SAMPLES = 512  # dense samples per period bracketing a refined maximum (as chain_dcrit)


@dataclass(frozen=True)
class StopGrazing:
    """The grazing test of one stop of a chain: its contact surface's index (stop - 1)."""

    surface: int

    @property
    def stop(self) -> int:
        """The stop's number (1-based, as the scene's [[stop]] tables)."""
        return self.surface + 1


def is_chain(system: System) -> bool:
    """Whether ``system`` is a chain (``[system] model = "chain"``)."""
    return system.extra.get("chain") is not None


def stop_tests(orbit_map: OrbitMap, lam: float) -> tuple[StopGrazing, ...]:
    """One grazing test per stop of a chain (empty for a preset)."""
    if not is_chain(orbit_map.system):
        return ()
    return tuple(StopGrazing(s) for s in orbit_map.problem(lam).surfaces.contact_indices)


def kernel_gaps(orbit_map: OrbitMap, point: Point) -> np.ndarray:
    """(n_stops,) psi_G,s of every stop at ``point``: the kernels' maximum of its
    compression along the orbit (NaN where the flow fails); kept on the point, since
    each point is the right end of one step and the left end of the next."""
    if point.stop_gaps is None:
        problem = orbit_map.problem(point.parameter)
        span = orbit_map.periods * problem.period
        out = []
        for s in problem.surfaces.contact_indices:
            status, _, top = flow(problem, point.state, 0.0, span, 1 << s)
            out.append(top if status == OK else np.nan)
        point.stop_gaps = np.array(out, dtype=float)
    return point.stop_gaps


def precise_gap(orbit_map: OrbitMap, point: Point, test: StopGrazing) -> float:
    """psi_G,s refined: the maximum of the stop's compression located on the flow (a root
    of its rate, to 1e-12 in time), bracketed on SAMPLES dense samples per period."""
    problem = orbit_map.problem(point.parameter)
    traj = record_trajectory(problem, point.state, 0.0, orbit_map.periods, SAMPLES)
    t, y = traj.t[:-1], traj.y[:-1]  # the last sample repeats the first
    row = problem.surfaces.A[test.surface]
    offset = float(problem.surfaces.b[test.surface])
    k = int(np.argmax(y @ row))
    return locate_maximum(problem, t, y, k, row) + offset
