"""Piecewise-linear systems: each mode's flow in closed form (``kernels/exact.py``).

A system is piecewise linear when, in every mode, its right-hand side is affine in the
state with forcing at the one frequency w:

    f(t, y) = M_m y + b_m + u_m sin(w t) + v_m cos(w t).

The matrices are read off the system's own ``rhs`` (a column of M per unit state, the
forcing from three times), then checked on random states and times, so a model or stop
law that is not linear in some mode (Duffing's cubic spring, the Hunt-Crossley law) is
refused with the mode named rather than integrated wrongly. With the augmented state
``Y = (y, sin w t, cos w t, 1)``, ``Y' = G_m Y``.
"""

from __future__ import annotations

from functools import lru_cache
from math import ceil

import numpy as np

from ..kernels.exact import HEADER, STEP_PHASE, expm
from .base import System, forcing_period_of

LINEARITY_TOL = 1e-9  # relative: the check on random states and times
MIN_STEPS = 4  # steps per period at least (what STEP_PHASE gives the forcing itself)


def _rhs(system: System, params: np.ndarray, t: float, y: np.ndarray, mode: int) -> np.ndarray:
    out = np.zeros(system.dim)
    system.rhs(float(t), np.ascontiguousarray(y, dtype=np.float64), params, mode, out)
    return out


def mode_generator(system: System, params: np.ndarray, mode: int) -> np.ndarray:
    """``G_m`` ((dim + 3, dim + 3)) of ``mode``; a ValueError when the mode's right-hand
    side is not affine in the state with forcing at w."""
    dim = system.dim
    w = float(params[system.forcing_frequency_index])
    T = forcing_period_of(w)
    zero = np.zeros(dim)
    times = np.array([0.0, 0.25 * T, 0.5 * T])
    free = np.array([_rhs(system, params, t, zero, mode) for t in times])  # (3, dim)
    basis = np.column_stack([np.ones(3), np.sin(w * times), np.cos(w * times)])
    b, u, v = np.linalg.solve(basis, free)
    M = np.column_stack([_rhs(system, params, 0.0, e, mode) - free[0]
                         for e in np.eye(dim)])
    for y, t in probe_states(system, params, mode):
        want = _rhs(system, params, t, y, mode)
        got = M @ y + b + u * np.sin(w * t) + v * np.cos(w * t)
        if np.max(np.abs(got - want)) > LINEARITY_TOL * (1.0 + np.max(np.abs(want))):
            raise ValueError(
                f"{_what(system)}: mode {mode}'s "
                "right-hand side is not linear in the state (a nonlinear spring or stop "
                "law); method 'exact' needs a piecewise-linear system")
    G = np.zeros((dim + 3, dim + 3))
    G[:dim, :dim] = M
    G[:dim, dim], G[:dim, dim + 1], G[:dim, dim + 2] = u, v, b
    G[dim, dim + 1] = w  # (sin w t)' = w cos w t
    G[dim + 1, dim] = -w  # (cos w t)' = -w sin w t
    return G


def _what(system: System) -> str:
    if system.model == "chain":
        return f"chain of {system.bodies}"
    return f"{system.model} {'pair' if system.bodies == 2 else 'body'}"


def probe_states(system: System, params: np.ndarray, mode: int):
    """(state, time) pairs the linearity check reads: random states, and states moved
    onto either side of each switching surface (a stop law acts only in contact, at
    penetrations the random states may never reach)."""
    surfaces = system.surfaces(params)
    T = system.period(params)
    rng = np.random.default_rng(mode)
    for _ in range(4):
        yield rng.uniform(-3.0, 3.0, system.dim), rng.uniform(0.0, T)
    for a, b in zip(surfaces.A, surfaces.b, strict=True):
        for target in (-0.7, 0.3, 1.3):
            y = rng.uniform(-3.0, 3.0, system.dim)
            y += (target - (a @ y + b)) * a / (a @ a)  # now a @ y + b == target
            yield y, rng.uniform(0.0, T)


def mode_step(G: np.ndarray, period: float) -> float:
    """The mode's step: its fastest mode turns at most STEP_PHASE rad, and a whole number
    of steps per period (a period without switches lands exactly). The forcing is one of
    G's modes (eigenvalues +-i w), so a step is at most T / 4 (a quarter step turns the
    forcing by at most pi / 8 rad)."""
    rho = float(np.max(np.abs(np.linalg.eigvals(G))))
    return period / max(MIN_STEPS, ceil(period * rho / STEP_PHASE))


def exact_block(system: System, params: np.ndarray) -> np.ndarray:
    """The data ``kernels.exact`` reads behind the parameters (see its docstring):
    ``[n_modes, aug, w, n_surfaces, (h_m, G_m, exp(G_m h_m / 4), A G_m) per mode]`` (a copy: one per
    parameter point is built once, ~2 ms for the pair's 16 modes)."""
    if system.variational:
        raise ValueError("the variational equations have no exact flow here")
    key = (system.model, system.bodies, system.extra.get("chain"))
    _SYSTEMS.setdefault(key, system)
    return _cached_block(key, params.tobytes()).copy()


_SYSTEMS: dict[tuple, System] = {}  # the systems _cached_block has seen, by identity key


@lru_cache(maxsize=256)
def _cached_block(key: tuple, packed: bytes) -> np.ndarray:
    system = _SYSTEMS[key]
    params = np.frombuffer(packed, dtype=np.float64)
    dim = system.dim
    aug = dim + 3
    w = float(params[system.forcing_frequency_index])
    period = forcing_period_of(w)
    A = system.surfaces(params).A
    n_modes = 1 << A.shape[0]
    parts = [np.array([n_modes, aug, w, A.shape[0]], dtype=np.float64)]
    assert parts[0].size == HEADER
    a, b = np.empty((aug, aug)), np.empty((aug, aug))
    for mode in range(n_modes):
        G = mode_generator(system, params, mode)
        h = mode_step(G, period)
        quarter = np.empty((aug, aug))
        expm(G, 0.25 * h, quarter, a, b)
        # kernels.exact skips these in its products (forcing_columns): exact zeros
        assert not G[dim:, :dim].any() and not quarter[dim:, :dim].any()
        rates = A @ G[:dim, :]  # g' = A y' = (A G) Y
        parts += [np.array([h]), G.ravel(), quarter.ravel(), rates.ravel()]
    return np.concatenate(parts)


def with_exact_block(system: System, params: np.ndarray) -> np.ndarray:
    """``params`` followed by the exact flow's block and, last, where the block starts."""
    return np.concatenate([params, exact_block(system, params), [float(params.size)]])


def exact_refusal(system: System, params: np.ndarray) -> str | None:
    """Why method 'exact' cannot integrate ``system`` at ``params`` (None: it can)."""
    try:
        exact_block(system, params)
    except ValueError as err:
        return str(err)
    return None
