"""The p-th stroboscopic map as a function of the state and one parameter, with derivatives.

Continuation (``analysis/continuation.py``) solves ``G(y, lam) = P^p_lam(y) - y = 0``, where
``P_lam`` advances a state at t = 0 (mod T) by one forcing period T = 2 pi / w at the
parameter value ``lam`` of the continued parameter (any model parameter: c, k1, k2, F, w,
d1, exponent, d, phi, k_c, c_c, as ``config.axes`` lists them; the others stay at the
scene's values). :meth:`OrbitMap.evaluate` returns, at one (y, lam):

- the residual ``G`` (n,), the monodromy ``M = dP^p/dy`` (n, n) and ``dG/dlam`` (n,);
- ``max_g``: the maximum of the contact function x1 - x2 - d along the p periods (the
  kernels locate it on the dense output; -inf for one body), so an orbit is impacting
  when it is >= 0.

**Monodromy.** Where the orbit does not touch the stop the vector field is smooth along
it (the bilinear springs are continuous across their gaps) and the variational equations
(``systems/variational.py``) give M exactly, as the catalogue's Newton shooting does. On
an impacting orbit the paper's stop force jumps at contact onset and release, so the
fundamental matrix jumps by the saltation matrix there (``kernels/saltation.py``). The
Benettin kernel of ``kernels/lyapunov.py`` applies it at every switch; run over one
interval of p T from the orthonormal start ``Q0`` whose first column is ``e_j``, its
Gram-Schmidt step leaves ``Q[:, 0] = M e_j / |M e_j|`` and ``logs[0] = ln |M e_j|``:
column j of M, exactly (one variational integration per column). With rigid stops the
advance is the impact loop (``kernels/impacts.py``), which carries the tangents across each
impact's reset by its saltation matrix, into sticking and out of it; an impacting rigid
orbit has ``max_g = 0``, so it takes this path too (the plain variational flow would give
the same M when no soft stop is touched).

**Parameter derivative.** ``dG/dlam`` by central differences of the flow (the kernels take
no parameter derivatives), with step ``PARAMETER_STEP * max(1, |lam|)``: accurate to about
rtol / step ~ 1e-6 relative, enough for the Newton corrector (which converges on the
exact residual) and for the tangent; the bifurcation test functions use M only.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..config import IntegratorSettings
from ..kernels import lyapunov as benettin_kernel
from ..kernels.codes import OK
from ..systems import System
from ..systems.variational import initial_variational_state, variational_system
from .engine import Problem, flow

SHOOTING = IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13)
PARAMETER_STEP = 1e-6


@dataclass(frozen=True)
class KernelValue:
    """What one evaluation of a shooting map returns, whatever its unknowns: ``status``
    kernel status (0 ok), ``residual`` (m,), the orbit's ``monodromy`` (n, n) (its
    multipliers), ``max_g`` the kernels' maximum of the contact function (-inf for one
    body). ``MapValue`` and ``atlas_augmented.AugmentedValue`` add their derivatives."""

    status: int
    residual: np.ndarray
    monodromy: np.ndarray
    max_g: float

    @property
    def ok(self) -> bool:
        return self.status == OK and bool(np.all(np.isfinite(self.residual)))


@dataclass(frozen=True)
class MapValue(KernelValue):
    """``P^p`` at one (y, lam): see the module docstring; ``dlam`` (n,) the parameter
    derivative of G."""

    dlam: np.ndarray

    @property
    def jacobian(self) -> np.ndarray:
        """(n, n + 1): ``[M - I | dG/dlam]``, the derivative of G in (y, lam)."""
        n = self.residual.size
        return np.column_stack([self.monodromy - np.eye(n), self.dlam])


@dataclass(frozen=True)
class OrbitMap:
    """``P^periods`` of ``system`` with ``parameter`` free and the other ``values`` fixed."""

    system: System
    values: Mapping[str, Any]
    parameter: str
    periods: int
    integrator: IntegratorSettings = SHOOTING

    @property
    def dim(self) -> int:
        return self.system.dim

    def problem(self, lam: float) -> Problem:
        return Problem(self.system, {**self.values, self.parameter: float(lam)}, self.integrator)

    def with_periods(self, periods: int) -> OrbitMap:
        return OrbitMap(self.system, self.values, self.parameter, periods, self.integrator)

    def image(self, y, lam: float) -> tuple[int, np.ndarray, float]:
        """(status, P^p(y), max of x1 - x2 - d along the way)."""
        problem = self.problem(lam)
        return flow(problem, y, 0.0, self.periods * problem.period)

    def evaluate(self, y, lam: float, parameter_derivative: bool = True) -> MapValue:
        """Residual, monodromy and parameter derivative at (y, lam) (dlam NaN when not
        asked for or when a flow failed)."""
        y = np.asarray(y, dtype=float)
        n = y.size
        problem = self.problem(lam)
        var = Problem(variational_system(self.system), problem.values, self.integrator)
        status, z, max_g = flow(var, initial_variational_state(y), 0.0,
                                self.periods * problem.period)
        nan = np.full(n, np.nan)
        if status != OK:
            return MapValue(status, nan, np.full((n, n), np.nan), max_g, dlam=nan)
        monodromy = z[n:].reshape(n, n)
        if max_g >= 0.0:
            monodromy = salted_monodromy(problem, y, self.periods)
        dlam = self.parameter_derivative(y, lam) if parameter_derivative else nan
        return MapValue(status, z[:n] - y, monodromy, max_g, dlam=dlam)

    def parameter_derivative(self, y, lam: float) -> np.ndarray:
        """dG/dlam = dP^p/dlam (n,) by central differences (NaN when a flow fails)."""
        h = PARAMETER_STEP * max(1.0, abs(lam))
        plus = self.image(y, lam + h)
        minus = self.image(y, lam - h)
        if plus[0] != OK or minus[0] != OK:
            return np.full(np.asarray(y).size, np.nan)
        return (plus[1] - minus[1]) / (2.0 * h)


def salted_monodromy(problem: Problem, y, periods: int) -> np.ndarray:
    """(n, n) monodromy over ``periods`` forcing periods from y at t = 0, with the saltation
    matrix applied at every switch (one Benettin interval per column; see the module
    docstring). NaN where an integration fails."""
    y = np.asarray(y, dtype=float)
    n = y.size
    var = Problem(variational_system(problem.system), problem.values, problem.integrator)
    span = periods * problem.period
    opts = var.options()
    M = np.empty((n, n))
    for j in range(n):
        start = np.eye(n)[:, np.r_[j, 0:j, j + 1:n]]  # e_j first, then the others
        z0 = initial_variational_state(y)
        z0[n:] = start.ravel()
        (status, *_), (logs, _), z, _ = benettin_kernel.benettin(
            var.advance, var.system.rhs, var.params, z0, n, (0.0, span, 1, 1),
            var.kernel_args(), opts, True)
        if status != OK:
            return np.full((n, n), np.nan)
        M[:, j] = np.exp(logs[0, 0]) * z[n:].reshape(n, n)[:, 0]
    return M
