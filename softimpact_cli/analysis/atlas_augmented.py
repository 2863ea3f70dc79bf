"""Codimension-one points as the solutions of an augmented system in two parameters.

A curve of the atlas is a curve of (y, a, b) in R^(n+2), ``a`` and ``b`` the scene's two
parameters (any of ``system.parameter_names``), solving the n + 1 equations

    F(y, a, b) = ( P^p_(a,b)(y) - y ,  g(y, a, b) ) = 0,

``P`` the stroboscopic map (``analysis/shooting.py``) and ``g`` the defining function of
the bifurcation, chosen **minimally augmented** (one scalar equation added, Govaerts'
bordered test functions; not the standard augmentation by eigenvectors):

- fold (a multiplier +1): ``A = M - I``; period doubling (-1): ``A = M + I``;
  Neimark-Sacker: ``A = M(2) - I``, ``M(2)`` the second compound matrix of M (its
  eigenvalues are the products mu_i mu_j, i < j), singular where a complex pair lies on the
  unit circle, and also at a "neutral saddle" (two real multipliers of product 1): the
  points of an NS curve say which (``Curve.resonance`` in ``atlas_curves``). For each,
  ``g`` solves the bordered system ``[[A, B], [C^T, 0]] [v; g] = [0; 1]``; it vanishes
  exactly where A is singular, and is regular there as long as the borders B, C are not
  orthogonal to A's left and right null vectors: they are the left and right singular
  vectors of A's smallest singular value at the last accepted point of the curve
  (:meth:`AugmentedMap.refresh`), fixed during one Newton correction.
- grazing: ``g = max over the orbit of x1 - x2 - d``, the maximum located on the flow to
  1e-12 in time (``critical_distance.critical_distance``, as the dcrit kind does), so the
  curve equals the critical distances to the integration tolerance. On the curve the orbit
  touches the stop without penetrating it (g = 0 is its largest contact), so it is the
  orbit of the pair with the stop out of reach (d = ``NO_CONTACT_D``, as dcrit integrates
  it): P, M and the parameter derivatives are taken there, the one-sided limit from the
  non-impacting side (from the impacting side dP/dd grows like the inverse square root of
  the penetration, and no smooth augmented system exists across it); d only enters g.

**Jacobian.** The first n rows are ``[M - I | dG/da | dG/db]``: M exact (variational
equations, with the saltation matrices on an impacting orbit), the parameter derivatives by
central differences of the flow (``OrbitMap.parameter_derivative``). The row of ``g``:
forward differences of g in each of the n + 2 unknowns (borders fixed) for the bordered
tests; for grazing, by the envelope theorem, the derivative of x1 - x2 at the fixed time
of the maximum, by central differences of the flow to that time. Newton converges on the
exact residual whatever the accuracy (~1e-6) of these derivatives.

The unknowns are ordered ``u = (y, a, b)``: ``b`` is the "parameter" of the one-parameter
machinery (``analysis/continuation.py`` follows the curve as it follows a branch, the last
component of u playing lam), ``(y, a)`` its "state".
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..kernels.codes import OK
from ..systems import System
from .critical_distance import NO_CONTACT_D, critical_distance
from .engine import Problem, flow
from .shooting import SHOOTING, KernelValue, MapValue, OrbitMap

CURVE_KINDS = ("fold", "period doubling", "Neimark-Sacker", "grazing")
FD_STEP = 1e-6  # relative forward-difference step of the test function's derivatives


def compound(M: np.ndarray) -> np.ndarray:
    """(m, m) second compound matrix of M (n, n), m = n (n - 1) / 2: the 2 x 2 minors over
    index pairs (i < j); its eigenvalues are mu_i mu_j for i < j."""
    n = M.shape[0]
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    out = np.empty((len(pairs), len(pairs)))
    for r, (i, j) in enumerate(pairs):
        for c, (k, m) in enumerate(pairs):
            out[r, c] = M[i, k] * M[j, m] - M[i, m] * M[j, k]
    return out


def critical_matrix(kind: str, M: np.ndarray) -> np.ndarray:
    """The matrix that is singular on a curve of ``kind`` (fold, PD, NS)."""
    if kind == "fold":
        return M - np.eye(M.shape[0])
    if kind == "period doubling":
        return M + np.eye(M.shape[0])
    C = compound(M)
    return C - np.eye(C.shape[0])


def borders(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(B, C): the left and right singular vectors of A's smallest singular value."""
    U, _, Vt = np.linalg.svd(A)
    return U[:, -1].copy(), Vt[-1].copy()


def bordered_test(A: np.ndarray, B: np.ndarray, C: np.ndarray) -> float:
    """g of ``[[A, B], [C^T, 0]] [v; g] = [0; 1]`` (NaN when the bordered matrix is
    singular: borders orthogonal to a null vector)."""
    m = A.shape[0]
    K = np.zeros((m + 1, m + 1))
    K[:m, :m], K[:m, m], K[m, :m] = A, B, C
    rhs = np.zeros(m + 1)
    rhs[m] = 1.0
    try:
        return float(np.linalg.solve(K, rhs)[m])
    except np.linalg.LinAlgError:
        return float("nan")


@dataclass(frozen=True)
class AugmentedValue(KernelValue):
    """F at one u: ``residual`` (n + 1,), ``jacobian`` (n + 1, n + 2) in (y, a, b), the
    orbit's ``monodromy`` (n, n) (the multipliers along the curve), ``max_g``, ``status``
    as in ``KernelValue``. The fields the one-parameter corrector and
    ``continuation.Point`` read."""

    jacobian: np.ndarray


@dataclass
class AugmentedMap:
    """F of the module docstring for one ``kind`` of curve of period-``periods`` orbits of
    ``system``, free in ``parameters = (a, b)``, the other ``values`` fixed."""

    system: System
    values: Mapping[str, Any]
    parameters: tuple[str, str]
    periods: int
    kind: str
    integrator: Any = SHOOTING
    border_b: np.ndarray | None = field(default=None, repr=False)
    border_c: np.ndarray | None = field(default=None, repr=False)

    @property
    def dim(self) -> int:
        return self.system.dim

    def point_values(self, a: float, b: float) -> dict:
        """The model's values at (a, b)."""
        name_a, name_b = self.parameters
        return {**self.values, name_a: float(a), name_b: float(b)}

    def flow_values(self, a: float, b: float) -> dict:
        """The values the orbit is integrated at: the point's, and for a grazing curve with
        the stop out of reach (see the module docstring)."""
        values = self.point_values(a, b)
        if self.kind == "grazing":
            values["d"] = NO_CONTACT_D
        return values

    def orbit_map(self, a: float, b: float, free: int = 1) -> OrbitMap:
        """The one-parameter map at (a, b) with parameter ``free`` (0: a, 1: b) free."""
        return OrbitMap(self.system, self.flow_values(a, b), self.parameters[free],
                        self.periods, self.integrator)

    def problem(self, a: float, b: float) -> Problem:
        return Problem(self.system, self.flow_values(a, b), self.integrator)

    def _moves_orbit(self, which: int) -> bool:
        """Whether parameter ``which`` changes the orbit (not d on a grazing curve)."""
        return not (self.kind == "grazing" and self.parameters[which] == "d")

    def map_value(self, y, a: float, b: float) -> MapValue:
        """P^p - I and the monodromy at (y, a, b), no parameter derivative."""
        free = 1 if self._moves_orbit(1) else 0
        return self.orbit_map(a, b, free).evaluate(y, (a, b)[free], parameter_derivative=False)

    def parameter_derivative(self, y, a: float, b: float, which: int) -> np.ndarray:
        """dG/d(a or b) (n,): central differences of the flow (zero where it does not move
        the orbit)."""
        if not self._moves_orbit(which):
            return np.zeros(self.dim)
        return self.orbit_map(a, b, which).parameter_derivative(y, (a, b)[which])

    def split(self, x, lam: float) -> tuple[np.ndarray, float, float]:
        x = np.asarray(x, dtype=float)
        return x[:-1], float(x[-1]), float(lam)

    def refresh(self, monodromy: np.ndarray) -> None:
        """New borders from the orbit's monodromy at an accepted point (bordered kinds)."""
        if self.kind != "grazing":
            self.border_b, self.border_c = borders(critical_matrix(self.kind, monodromy))

    def test(self, y, a: float, b: float, monodromy: np.ndarray | None = None) -> float:
        """g at (y, a, b) (``monodromy`` given: M there, saves an integration)."""
        if self.kind == "grazing":
            top, _ = critical_distance(self.problem(a, b), np.asarray(y, dtype=float),
                                       self.periods)
            return top - float(self.point_values(a, b)["d"])
        if monodromy is None:
            value = self.map_value(y, a, b)
            if value.status != OK:
                return float("nan")
            monodromy = value.monodromy
        A = critical_matrix(self.kind, monodromy)
        if self.border_b is None:
            self.border_b, self.border_c = borders(A)
        return bordered_test(A, self.border_b, self.border_c)

    def test_gradient(self, y, a: float, b: float, g0: float) -> np.ndarray:
        """(n + 2,) derivative of g in (y, a, b): see the module docstring."""
        u = np.concatenate([np.asarray(y, dtype=float), [a, b]])
        n = self.dim
        if self.kind == "grazing":
            return self._grazing_gradient(u)
        grad = np.empty(n + 2)
        for k in range(n + 2):
            h = FD_STEP * max(1.0, abs(u[k]))
            v = u.copy()
            v[k] += h
            grad[k] = (self.test(v[:n], v[n], v[n + 1]) - g0) / h
        return grad

    def _grazing_gradient(self, u: np.ndarray) -> np.ndarray:
        """d/du of max_t (x1 - x2)(t; u) - d: the derivative at the fixed time t* of the
        maximum (the envelope theorem), by central differences of the flow to t*."""
        n = self.dim
        y, a, b = u[:n], u[n], u[n + 1]
        _, t_star = critical_distance(self.problem(a, b), y, self.periods)
        grad = np.empty(n + 2)
        for k in range(n + 2):
            if k >= n and self.parameters[k - n] == "d":
                grad[k] = -1.0  # the orbit does not move with d (see flow_values)
                continue
            h = FD_STEP * max(1.0, abs(u[k]))
            sides = []
            for sign in (1.0, -1.0):
                v = u.copy()
                v[k] += sign * h
                status, z, _ = flow(self.problem(v[n], v[n + 1]), v[:n], 0.0, t_star)
                sides.append(z[0] - z[2] if status == OK else np.nan)
            grad[k] = (sides[0] - sides[1]) / (2.0 * h)
        return grad

    def evaluate(self, x, lam: float) -> AugmentedValue:
        """F, its Jacobian and the monodromy at u = (x, lam) = (y, a, b)."""
        y, a, b = self.split(x, lam)
        n = self.dim
        value = self.map_value(y, a, b)
        bad = AugmentedValue(value.status or (0 if value.ok else -1), np.full(n + 1, np.nan),
                             value.monodromy, value.max_g,
                             jacobian=np.full((n + 1, n + 2), np.nan))
        if not value.ok:
            return bad
        d_da = self.parameter_derivative(y, a, b, 0)
        d_db = self.parameter_derivative(y, a, b, 1)
        g0 = self.test(y, a, b, value.monodromy)
        if not np.isfinite(g0):
            return bad
        jac = np.zeros((n + 1, n + 2))
        jac[:n, :n] = value.monodromy - np.eye(n)
        jac[:n, n], jac[:n, n + 1] = d_da, d_db
        jac[n] = self.test_gradient(y, a, b, g0)
        residual = np.append(value.residual, g0)
        max_g = value.max_g
        if self.kind == "grazing":  # the contact function at the point's own d
            max_g = g0
        return AugmentedValue(OK, residual, value.monodromy, max_g, jacobian=jac)
