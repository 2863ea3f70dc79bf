"""The brute-force reference a continuation is drawn against: sweep the parameter up and
down, each step starting from the previous step's end state.

This is the method of the ``bifurcation`` kind (``analysis/bifurcation.py``, there along d
only) for any continued parameter: at each value the trajectory is integrated until
classified (``engine.classify_state``) and its section points at t = 0 (mod T) recorded
(the orbit's q points, or the last UNRESOLVED_POINTS section points when no period was
found). It sees stable orbits only, and jumps where a stable orbit ends: at a fold of
the continued branch, the classic hysteresis of a forced Duffing oscillator.
"""

from __future__ import annotations

import numpy as np

from ..config import IntegratorSettings
from ..kernels.codes import CONVERGED
from ..systems import System
from .engine import Problem, classify_state, record_trajectory

UNRESOLVED_POINTS = 30


def sweep_values(low: float, high: float, start: float, step: float, rising: bool
                 ) -> np.ndarray:
    """Parameter values from ``start`` to ``high`` (rising) or ``low`` (falling) by ``step``,
    the bound itself included."""
    end = high if rising else low
    n = int(np.floor(abs(end - start) / step + 1e-9))
    values = start + (1.0 if rising else -1.0) * step * np.arange(n + 1)
    return values if values[-1] == end else np.append(values, end)


def sweep(system: System, values: dict, integrator: IntegratorSettings, parameter: str,
          lams: np.ndarray, state: np.ndarray) -> list[dict]:
    """Follow ``state`` (at t = 0) along ``lams``; per value: {"parameter", "points" (q,
    n) section points, "period" (0: unresolved or diverged), "impacting"}."""
    records = []
    state = np.array(state, dtype=float)
    for lam in lams:
        problem = Problem(system, {**values, parameter: float(lam)}, integrator)
        cls = classify_state(problem, state, 0.0)
        if cls.status == CONVERGED:
            points, period = cls.orbit, cls.period
        else:
            points = record_trajectory(problem, state, 0.0, UNRESOLVED_POINTS, 1).section_y[1:]
            period = 0
        if np.all(np.isfinite(points[-1])):
            state = points[-1].copy()  # t = 0 mod T: the next value's start
        records.append({"parameter": float(lam), "points": points, "period": int(period),
                        "impacting": bool(cls.impacting)})
    return records


def sweeps(system: System, values: dict, integrator: IntegratorSettings, parameter: str,
           starts: list[tuple[str, np.ndarray]], lam0: float, bounds: tuple[float, float],
           step: float) -> list[tuple[str, str, list[dict]]]:
    """Each start swept from lam0 up to the high bound and down to the low one:
    [(start name, "up" | "down", records)]."""
    out = []
    for name, state in starts:
        for rising in (True, False):
            lams = sweep_values(bounds[0], bounds[1], lam0, step, rising)
            out.append((name, "up" if rising else "down",
                        sweep(system, values, integrator, parameter, lams, state)))
    return out


def jumps(records: list[dict], tol: float = 1e-3) -> list[tuple[float, float]]:
    """(last value on the followed orbit, first value off it) wherever a sweep's lowest
    section displacement changes by more than ``tol`` times the typical step-to-step change plus
    ``tol``: where a stable orbit ended between two values."""
    first = np.array([np.min(r["points"][:, 0]) for r in records])
    moves = np.abs(np.diff(first))
    scale = np.median(moves) if moves.size else 0.0
    return [(records[i]["parameter"], records[i + 1]["parameter"])
            for i in np.flatnonzero(moves > 20.0 * scale + tol)]
