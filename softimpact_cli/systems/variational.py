"""The variational extension of a system: state and fundamental matrix together.

``variational_system(system)`` returns a :class:`System` of dimension ``n + n*n`` whose
state is ``(y, vec(Phi))`` with ``Phi' = J(t, y, mode) Phi`` (row-major ``Phi``). Its
switching surfaces are the base system's (they ignore ``Phi``), so every kernel runs it
unchanged. No saltation matrix is applied at a switch: exact where the vector field is
continuous across the surface (the bilinear springs, the no-tension stop, every orbit
without contact), not across the paper-law stop's onset, where callers must not use it.

The right-hand side is a closure over the base system's jitted functions, so it is
compiled once per process rather than cached on disk.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numba import njit

from .base import Surfaces, System

_BUILT: dict[tuple[str, int], System] = {}


def variational_system(system: System) -> System:
    key = (system.model, system.bodies)
    if key not in _BUILT:
        _BUILT[key] = _build(system)
    return _BUILT[key]


def _build(system: System) -> System:
    rhs = system.rhs
    jac = system.jacobian
    n = system.dim

    @njit
    def var_rhs(t, z, p, mode, out):
        rhs(t, z[:n], p, mode, out[:n])
        J = np.empty((n, n))
        dfdt = np.empty(n)
        jac(t, z[:n], p, mode, J, dfdt)
        for i in range(n):
            for j in range(n):
                acc = 0.0
                for k in range(n):
                    acc += J[i, k] * z[n + k * n + j]
                out[n + i * n + j] = acc

    def surfaces(p: np.ndarray) -> Surfaces:
        base = system.surfaces(p)
        A = np.zeros((base.A.shape[0], n + n * n))
        A[:, :n] = base.A
        return replace(base, A=A)

    names = system.state_names + tuple(f"Phi{i}{j}" for i in range(n) for j in range(n))
    return replace(system, state_names=names, rhs=var_rhs, surfaces=surfaces,
                   description=system.description + " (with variational equations)")


def initial_variational_state(y: np.ndarray) -> np.ndarray:
    """``(y, vec(I))``: the start of a fundamental matrix solution."""
    n = y.shape[0]
    return np.concatenate([y, np.eye(n).ravel()])
