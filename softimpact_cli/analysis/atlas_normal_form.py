"""Criticality of period-doubling and Neimark-Sacker points: normal-form coefficients.

For the map P = P^p (``analysis/shooting.py``) at a fixed point y, write
``P(y + z) = y + A z + B(z, z) / 2 + C(z, z, z) / 6 + ...`` with A = M the monodromy.
The coefficients (Kuznetsov, *Elements of Applied Bifurcation Theory*, 3rd ed., sections
5.4 and 5.7, the multidimensional flip and Neimark-Sacker of maps):

- period doubling, ``A q = -q``, ``A^T p = -p``, ``p . q = 1``:
  ``c = p . C(q,q,q) / 6 - p . B(q, (A - I)^-1 B(q,q)) / 2``; c > 0: the period-two orbit
  born is stable where the fixed point is not (**supercritical**), c < 0 subcritical;
- Neimark-Sacker, ``A q = e^(i theta) q``, ``A^T p = e^(-i theta) p``, ``<p, q> = 1``
  (``<p, x> = conj(p) . x``):
  ``d = Re{ e^(-i theta) [<p, C(q,q,qbar)> + 2 <p, B(q, (I - A)^-1 B(q,qbar))>
  + <p, B(qbar, (e^(2 i theta) I - A)^-1 B(q,q))>] } / 2``; d < 0: a stable invariant
  curve is born (**supercritical**), d > 0 subcritical.

The multilinear forms come from central differences of the flow (no derivatives of the
kernels): ``B(z,z) = [P(y + hz) - 2 P(y) + P(y - hz)] / h^2``, ``C(z,z,z) = [P(y + 2hz)
- 2 P(y + hz) + 2 P(y - hz) - P(y - 2hz)] / (2 h^3)`` for unit z, the mixed and complex
arguments by polarization. Steps H2, H3 (state units) are small beside the distance to
grazing on the shipped cases (an impacting orbit's map is smooth only while its contacts
stay transversal), large enough for the integrator's noise (rtol 1e-12) to stay ~1e-5 of
the coefficients there; the tests check the signs against brute force (figure 14(c)).
"""

from __future__ import annotations

import numpy as np

from .shooting import OrbitMap

H2 = 1e-3  # step of the second differences
H3 = 2e-3  # step of the third differences


class _Forms:
    """B and C of P^p at y by central differences (see the module docstring)."""

    def __init__(self, orbit_map: OrbitMap, y: np.ndarray):
        self.orbit_map = orbit_map
        self.lam = float(orbit_map.values[orbit_map.parameter])
        self.y = np.asarray(y, dtype=float)
        self.centre = self.image(self.y)

    def image(self, z: np.ndarray) -> np.ndarray:
        status, out, _ = self.orbit_map.image(z, self.lam)
        return out if status == 0 else np.full(z.size, np.nan)

    def _along(self, z: np.ndarray, order: int) -> np.ndarray:
        """The ``order``-th (2 or 3) directional derivative of the map at y along real z,
        by central differences along the unit vector z / |z| (steps H2, H3), scaled back
        by |z| ** order."""
        size = float(np.linalg.norm(z))
        if size == 0.0:
            return np.zeros_like(z)
        u = z / size
        if order == 2:
            h = H2
            difference = (self.image(self.y + h * u) - 2 * self.centre
                          + self.image(self.y - h * u))
            scale = h ** 2
        else:
            h = H3
            difference = (self.image(self.y + 2 * h * u) - 2 * self.image(self.y + h * u)
                          + 2 * self.image(self.y - h * u)
                          - self.image(self.y - 2 * h * u))
            scale = 2 * h ** 3
        return size ** order * difference / scale

    def quadratic(self, z: np.ndarray) -> np.ndarray:
        """B(z, z) for real z."""
        return self._along(z, 2)

    def cubic(self, z: np.ndarray) -> np.ndarray:
        """C(z, z, z) for real z."""
        return self._along(z, 3)

    def bilinear_real(self, x: np.ndarray, w: np.ndarray) -> np.ndarray:
        return (self.quadratic(x + w) - self.quadratic(x - w)) / 4.0

    def bilinear(self, x: np.ndarray, w: np.ndarray) -> np.ndarray:
        """B(x, w) for complex x, w (extended bilinearly)."""
        x, w = np.asarray(x, dtype=complex), np.asarray(w, dtype=complex)
        B = self.bilinear_real
        return (B(x.real, w.real) - B(x.imag, w.imag)
                + 1j * (B(x.real, w.imag) + B(x.imag, w.real)))

    def cubic_q_q_qbar(self, q: np.ndarray) -> np.ndarray:
        """C(q, q, conj q) = C(u,u,u) + C(u,v,v) + i [C(u,u,v) + C(v,v,v)], q = u + i v,
        with C(x,x,y) = [c(x + y) - c(x - y) - 2 c(y)] / 6, c(z) = C(z,z,z)."""
        u, v = q.real, q.imag
        cu, cv = self.cubic(u), self.cubic(v)
        cp, cm = self.cubic(u + v), self.cubic(u - v)
        uuv = (cp - cm - 2 * cv) / 6.0
        vvu = (cp + cm - 2 * cu) / 6.0  # c(v + u) - c(v - u) = c(u + v) + c(u - v)
        return cu + vvu + 1j * (uuv + cv)


def flip_coefficient(orbit_map: OrbitMap, y, monodromy: np.ndarray) -> float:
    """c of a period-doubling point (> 0 supercritical); see the module docstring."""
    A = np.asarray(monodromy, dtype=float)
    n = A.shape[0]
    mu, right = np.linalg.eig(A)
    k = int(np.argmin(np.abs(mu + 1.0)))
    q = np.real(right[:, k])
    q /= np.linalg.norm(q)
    mu_t, left = np.linalg.eig(A.T)
    p = np.real(left[:, int(np.argmin(np.abs(mu_t + 1.0)))])
    p /= p @ q
    forms = _Forms(orbit_map, y)
    bqq = forms.quadratic(q)
    inner = np.linalg.solve(A - np.eye(n), bqq)
    return float(p @ forms.cubic(q) / 6.0 - p @ forms.bilinear_real(q, inner) / 2.0)


def lyapunov_coefficient(orbit_map: OrbitMap, y, monodromy: np.ndarray) -> float:
    """d of a Neimark-Sacker point (< 0 supercritical); see the module docstring."""
    A = np.asarray(monodromy, dtype=float)
    n = A.shape[0]
    mu, right = np.linalg.eig(A)
    candidates = [k for k in range(n) if mu[k].imag > 0]
    if not candidates:
        return float("nan")  # a neutral saddle: no NS
    k = min(candidates, key=lambda i: abs(abs(mu[i]) - 1.0))
    theta = float(np.angle(mu[k]))
    q = right[:, k] / np.linalg.norm(right[:, k])
    mu_t, left = np.linalg.eig(A.T)
    p = left[:, int(np.argmin(np.abs(mu_t - np.conj(mu[k]))))]
    p = p / np.conj(np.vdot(p, q))  # <p, q> = conj(p) . q = 1
    forms = _Forms(orbit_map, y)
    eye = np.eye(n)
    b_q_qbar = forms.bilinear(q, np.conj(q))
    b_q_q = forms.bilinear(q, q)
    first = np.vdot(p, forms.cubic_q_q_qbar(q))
    second = 2 * np.vdot(p, forms.bilinear(q, np.linalg.solve(eye - A, b_q_qbar)))
    third = np.vdot(p, forms.bilinear(np.conj(q),
                                      np.linalg.solve(np.exp(2j * theta) * eye - A, b_q_q)))
    return float(0.5 * (np.exp(-1j * theta) * (first + second + third)).real)


def criticality(kind: str, orbit_map: OrbitMap, y, monodromy: np.ndarray) -> float:
    """The normal-form coefficient of a point of a curve of ``kind`` (NaN but for PD, NS,
    and where it is undefined: at a strong resonance, I - A or A + I singular)."""
    try:
        if kind == "period doubling":
            return flip_coefficient(orbit_map, y, monodromy)
        if kind == "Neimark-Sacker":
            return lyapunov_coefficient(orbit_map, y, monodromy)
    except np.linalg.LinAlgError:
        pass
    return float("nan")


def supercritical(kind: str, coefficient: float) -> bool | None:
    """Whether a coefficient of ``kind`` means supercritical (None: NaN or not PD/NS)."""
    if not np.isfinite(coefficient):
        return None
    if kind == "period doubling":
        return coefficient > 0
    if kind == "Neimark-Sacker":
        return coefficient < 0
    return None
