"""Lyapunov exponents of the piecewise-smooth flow: a state in, the spectrum out.

:func:`lyapunov_spectrum` runs Benettin's method (``kernels/lyapunov.py``) on the
variational equations (``systems/variational.py``), applying the saltation matrix at
every switch (``kernels/saltation.py``): contact onset and release of the stop, the
bilinear springs' gaps, the no-tension law's force surface. ``dim`` exponents come out
(4 for a pair, 2 for one body), in units of 1/time (dimensionless time; multiply by T
for "per forcing period"), largest first, with the phase of the forcing left out (the
flow is non-autonomous: the time direction's exponent 0 is not one of them).

**Confidence.** After ``transient`` forcing periods (discarded: the state settles on
its attractor and the tangent vectors align with the Lyapunov directions) the next
``periods`` are cut into ``segments`` segments of equal length; each gives its own
estimate, and the result is their mean with the standard error ``std / sqrt(K)``
(``ddof = 1``). The segments are treated as independent, which they are not quite
(tangent vectors carry over): on chaotic attractors the error is underestimated by a
factor of order 1 when segments are shorter than a few decorrelation times.

**Invariants.** The exponents sum to the average of ``trace J`` plus the average of
``ln |det S|`` per unit time. For one Duffing body, trace J = -c: the sum is -c up to
the integration error, interval by interval. For the paper's stop, det S = 1 and trace
J drops by 2 c_c in contact: the sum is ``-2 c - 2 c_c`` x (share of time in contact).
With a rigid wall (one body) each impact adds ``ln det S = 2 ln r`` (the impact loop,
``kernels/impacts.py``, carries the tangents across its reset; the kernel counts each
impact as a switch, ``salted`` stays 0); an orbit that sticks on a wall forgets every
perturbation (S = 0 entering it): its exponents are -inf.

**Periodic orbits.** On a stable period-q orbit the exponents are ``ln|mu_j| / (q T)``
of its Floquet multipliers: :func:`floquet_exponents`, and the monodromy matrix by
central differences of the flow map, :func:`finite_difference_monodromy` (the referee
for impacting orbits, whose variational monodromy needs the saltation matrices).

Cost: the variational system has n + n^2 variables (20 for a pair), integrated with
dopri5 at the scene's tolerances; about 5 times a plain trajectory per period.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ..kernels import lyapunov as kernel
from ..kernels.codes import OK
from ..systems.variational import initial_variational_state, variational_system
from .engine import Problem, counter_dict, flow

PER_PERIOD = 8  # re-orthonormalisations per forcing period (default)
EXPLICIT = ("dopri5",)  # the variational systems have no Jacobian of their own


@dataclass(frozen=True)
class Spectrum:
    """The Lyapunov spectrum of one trajectory.

    exponents, stderr : (dim,) mean over segments and its standard error, 1/time,
        largest first (NaN after a failed integration)
    segments : (K, dim) each segment's estimate
    sections : (periods, dim) the state at t0 + (transient + m) T, m = 1 .. periods
    state, t_end : the state where it ended and the time (for continuing along a grid)
    status : kernel status (0 ok); switches : switches crossed; salted : saltation
        matrices applied; counters : the integrator's counters; wall : seconds
    """

    exponents: np.ndarray
    stderr: np.ndarray
    segments: np.ndarray
    sections: np.ndarray
    state: np.ndarray
    t_end: float
    status: int
    switches: int
    salted: int
    counters: dict
    wall: float
    period: float

    @property
    def ok(self) -> bool:
        return self.status == OK

    @property
    def sum(self) -> float:
        return float(np.sum(self.exponents))


def variational_problem(problem: Problem) -> Problem:
    """The problem's variational system, integrated explicitly (dopri5) at its tolerances."""
    integ = problem.integrator
    if integ.resolved_method not in EXPLICIT:
        integ = replace(integ, method="dopri5")
    return Problem(variational_system(problem.system), problem.values, integ)


def lyapunov_spectrum(problem: Problem, state, t0: float = 0.0, *, periods: int = 500,
                      transient: int = 50, segments: int = 10, per_period: int = PER_PERIOD,
                      saltation: bool = True, tangents: np.ndarray | None = None
                      ) -> Spectrum:
    """Lyapunov spectrum of the trajectory through ``state`` (dim,) at time ``t0``.

    periods : forcing periods averaged (after ``transient`` discarded ones), split into
        ``segments`` segments (periods must be a multiple of segments)
    per_period : Gram-Schmidt re-orthonormalisations per forcing period
    saltation : False leaves the tangent vectors unchanged at switches (wrong where the
        field jumps; for comparison only)
    tangents : (dim, dim) initial orthonormal tangent vectors as columns (default I)
    """
    if periods % segments:
        raise ValueError(f"periods ({periods}) must be a multiple of segments ({segments})")
    y0 = np.asarray(state, dtype=np.float64)
    n = y0.shape[0]
    var = variational_problem(problem)
    T = problem.period
    z0 = initial_variational_state(y0)
    if tangents is not None:
        z0[n:] = np.asarray(tangents, dtype=np.float64).ravel()
    total = (transient + periods) * per_period
    started = time.perf_counter()
    (status, done, salted, switches), (logs, sections), z, istate = kernel.benettin(
        var.advance, var.system.rhs, var.params, z0, n,
        (float(t0), T / per_period, total, per_period), var.kernel_args(), var.options(),
        bool(saltation))
    wall = time.perf_counter() - started
    kept = logs[transient * per_period:]
    seg = kept.reshape(segments, -1, n).sum(axis=1) / (periods // segments * T)
    mean = seg.mean(axis=0)
    err = seg.std(axis=0, ddof=1) / np.sqrt(segments) if segments > 1 else np.full(n, np.nan)
    order = np.argsort(-mean) if np.all(np.isfinite(mean)) else np.arange(n)
    return Spectrum(mean[order], err[order], seg[:, order], sections[transient:], z[:n].copy(),
                    float(t0) + done / per_period * T, int(status), int(switches),
                    int(salted), counter_dict(istate), wall, T)


def floquet_exponents(multipliers, periods: int, T: float) -> np.ndarray:
    """``ln|mu| / (periods T)``, largest first: the exponents of a period-``periods`` orbit."""
    mu = np.abs(np.asarray(multipliers))
    with np.errstate(divide="ignore"):
        return np.sort(np.log(mu) / (periods * T))[::-1]


def finite_difference_monodromy(problem: Problem, state, t0: float, periods: int,
                                step: float = 1e-6) -> np.ndarray:
    """(dim, dim) derivative of the flow map over ``periods`` forcing periods at ``state``
    (t0), by central differences of the flow with switches located; ``step`` relative to
    max(1, |state|)."""
    y = np.asarray(state, dtype=np.float64)
    n = y.shape[0]
    h = step * max(1.0, float(np.max(np.abs(y))))
    t1 = t0 + periods * problem.period
    M = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        plus = flow(problem, y + e, t0, t1)
        minus = flow(problem, y - e, t0, t1)
        if plus[0] != OK or minus[0] != OK:
            return np.full((n, n), np.nan)
        M[:, j] = (plus[1] - minus[1]) / (2.0 * h)
    return M


def refine_periodic(problem: Problem, state, t0: float, periods: int, tol: float = 1e-11,
                    max_iter: int = 20) -> tuple[np.ndarray, np.ndarray, float]:
    """Newton on ``P^q(y) = y`` with the finite-difference monodromy (valid across impacts:
    the flow map is smooth near an orbit that crosses its surfaces transversally).
    Returns (state, monodromy, residual |P^q(y) - y|_inf)."""
    y = np.asarray(state, dtype=np.float64).copy()
    t1 = t0 + periods * problem.period
    M = np.full((y.size, y.size), np.nan)
    residual = np.inf
    for _ in range(max_iter):
        status, end, _ = flow(problem, y, t0, t1)
        if status != OK:
            break
        r = end - y
        residual = float(np.max(np.abs(r)))
        M = finite_difference_monodromy(problem, y, t0, periods)
        if residual <= tol:
            break
        y = y - np.linalg.solve(M - np.eye(y.size), r)
    return y, M, residual
