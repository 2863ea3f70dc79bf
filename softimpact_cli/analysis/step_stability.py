"""Is a fixed RK4 step stable in every contact mode? Checked before a run starts.

For each mode the Jacobian at the rest state (y = 0) gives eigenvalues lambda; RK4 is
stable for a step h when |R(h lambda)| <= 1 with R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24.
The stiffest mode is the stop engaged with large k_c or c_c. At rest a hardening spring
is at its softest, so the limit found is optimistic for large amplitudes.
"""

from __future__ import annotations

import math

import numpy as np

from .engine import Problem


def rk4_amplification(z: np.ndarray) -> np.ndarray:
    return np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)


def mode_eigenvalues(problem: Problem) -> np.ndarray:
    """Eigenvalues of the Jacobian at rest in every mode, concatenated."""
    n = problem.system.dim
    n_modes = 2 ** problem.surfaces.A.shape[0]
    out = []
    jac = np.zeros((n, n))
    dfdt = np.zeros(n)
    for mode in range(n_modes):
        problem.system.jacobian(0.0, np.zeros(n), problem.params, mode, jac, dfdt)
        out.append(np.linalg.eigvals(jac))
    return np.concatenate(out)


def largest_stable_step(eigenvalues: np.ndarray) -> float:
    """Largest h with |R(h lambda)| <= 1 for every eigenvalue (bisection on h)."""
    lam = eigenvalues[np.abs(eigenvalues) > 0]
    if lam.size == 0:
        return math.inf
    if np.any(lam.real > 0):  # a growing mode: no step makes it decay; judge the others
        lam = lam[lam.real <= 0]
        if lam.size == 0:
            return math.inf
    lo, hi = 0.0, 2.9 / float(np.max(np.abs(lam)))
    while np.all(rk4_amplification(hi * lam) <= 1 + 1e-12) and hi < 1e6:
        lo, hi = hi, 2 * hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if np.all(rk4_amplification(mid * lam) <= 1 + 1e-12):
            lo = mid
        else:
            hi = mid
    return lo


def rk4_step_warning(problem: Problem) -> str | None:
    """A one-line warning when the scene's fixed RK4 step is unstable, else None."""
    s = problem.integrator
    if not s.traits.fixed_step:  # (RK4's stability polynomial: the one fixed-step method)
        return None
    h = problem.period / s.steps_per_period
    h_max = largest_stable_step(mode_eigenvalues(problem))
    if h <= h_max:
        return None
    need = math.ceil(problem.period / h_max)
    return (f"[integrator] steps_per_period = {s.steps_per_period}: the RK4 step T/"
            f"{s.steps_per_period} = {h:.3g} exceeds the stability limit {h_max:.3g} of the "
            f"stiffest contact mode (k_c = {problem.values.get('k_c')}, c_c = "
            f"{problem.values.get('c_c')}); stable from steps_per_period >= {need} (accurate only "
            f"well above it), or use method 'stiff'")
