"""The variational extension of a system: state and fundamental matrix together.

``variational_system(system)`` returns a :class:`System` of dimension ``n + n*n`` whose
state is ``(y, vec(Phi))`` with ``Phi' = J(t, y, mode) Phi`` (row-major ``Phi``). Its
switching surfaces are the base system's (they ignore ``Phi``), so every kernel runs it
unchanged. No saltation matrix is applied at a switch: exact where the vector field is
continuous across the surface (the bilinear springs, the no-tension stop, every orbit
without contact), not across the paper-law stop's onset, where callers must not use it
as it is: ``kernels/lyapunov.py`` stops at every switch and applies the saltation matrix
(``kernels/saltation.py``), which makes it right there too.

Each registered system has a module-level, disk-cached right-hand side here (a thin
wrapper binding its ``rhs`` and ``jacobian`` to :func:`extend`), so that the kernels it is
passed to keep one cache entry across processes (``kernels.numba_cache``). A closure built
per process would be recompiled in every process and, its type being new each time, would
add a new entry to every kernel's on-disk index in every run. A system added elsewhere
needs a wrapper in ``_KERNELS`` below; without one it gets such a closure (correct, but
compiled in every process).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numba import njit

from . import bilinear, chain, duffing
from .base import Surfaces, System


@njit(cache=True)
def extend(rhs, jac, n, t, z, p, mode, out):
    """``out = (f(t, y), J(t, y) Phi)`` for ``z = (y, vec(Phi))``; ``n`` = dim of ``y``.

    z, out : (n + n*n,) float64; ``rhs`` and ``jac`` follow the system contract.
    """
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


@njit(cache=True)
def duffing_body_rhs(t, z, p, mode, out):
    extend(duffing.body_rhs, duffing.body_jacobian, 2, t, z, p, mode, out)


@njit(cache=True)
def duffing_pair_rhs(t, z, p, mode, out):
    extend(duffing.pair_rhs, duffing.pair_jacobian, 4, t, z, p, mode, out)


@njit(cache=True)
def bilinear_body_rhs(t, z, p, mode, out):
    extend(bilinear.body_rhs, bilinear.body_jacobian, 2, t, z, p, mode, out)


@njit(cache=True)
def bilinear_pair_rhs(t, z, p, mode, out):
    extend(bilinear.pair_rhs, bilinear.pair_jacobian, 4, t, z, p, mode, out)


@njit(cache=True)
def chain_variational_rhs(t, z, p, mode, out):
    """Every chain's (the state's dimension is read from the packed parameters)."""
    extend(chain.chain_rhs, chain.chain_jacobian, 2 * int(p[chain.N]), t, z, p, mode, out)


# (base rhs, base jacobian, variational rhs) of every registered system
_KERNELS = (
    (duffing.body_rhs, duffing.body_jacobian, duffing_body_rhs),
    (duffing.pair_rhs, duffing.pair_jacobian, duffing_pair_rhs),
    (bilinear.body_rhs, bilinear.body_jacobian, bilinear_body_rhs),
    (bilinear.pair_rhs, bilinear.pair_jacobian, bilinear_pair_rhs),
    (chain.chain_rhs, chain.chain_jacobian, chain_variational_rhs),
)

_BUILT: dict[tuple, System] = {}


def variational_system(system: System) -> System:
    key = (system.model, system.bodies, system.extra.get("chain"))
    if key not in _BUILT:
        _BUILT[key] = _build(system)
    return _BUILT[key]


def variational_rhs(system: System):
    """The jitted variational right-hand side of ``system`` (module-level when registered)."""
    for rhs, jac, var_rhs in _KERNELS:
        if system.rhs is rhs and system.jacobian is jac:
            return var_rhs
    return _closure(system.rhs, system.jacobian, system.dim)


def _closure(rhs, jac, n):
    @njit
    def var_rhs(t, z, p, mode, out):
        extend(rhs, jac, n, t, z, p, mode, out)

    return var_rhs


def _build(system: System) -> System:
    n = system.dim

    def surfaces(p: np.ndarray) -> Surfaces:
        base = system.surfaces(p)
        A = np.zeros((base.A.shape[0], n + n * n))
        A[:, :n] = base.A
        return replace(base, A=A)

    names = system.state_names + tuple(f"Phi{i}{j}" for i in range(n) for j in range(n))
    return replace(system, state_names=names, rhs=variational_rhs(system), surfaces=surfaces,
                   piecewise_linear=False, variational=True,
                   description=system.description + " (with variational equations)")


def initial_variational_state(y: np.ndarray) -> np.ndarray:
    """``(y, vec(I))``: the start of a fundamental matrix solution."""
    n = y.shape[0]
    return np.concatenate([y, np.eye(n).ravel()])
