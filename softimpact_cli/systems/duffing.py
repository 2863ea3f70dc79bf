"""Duffing oscillators: one body alone, and the pair coupled by a soft stop.

    x1'' + c x1' + k1 x1 + k2 x1^3 + F_C = F sin(w t)
    x2'' + c x2' + k1 x2 + k2 x2^3 - F_C = F sin(w t + phi)
    F_C = k_c (x1 - x2 - d) + c_c (x1' - x2')   while x1 - x2 >= d, else 0

With the "no-tension" law F_C is clipped at zero (the stop pushes, never pulls).
All quantities are dimensionless (mass 1); time in units of 1/w0.
"""

from __future__ import annotations

from collections.abc import Mapping
from math import cos, sin

import numpy as np
from numba import njit

from .base import (
    COUPLING_PARAMETERS,
    LAWS,
    Parameter,
    Surfaces,
    System,
    pack_coupling,
    pack_parameters,
    relevance_table,
)

BODY_PARAMETERS = (
    Parameter("c", "1", 0.05, "viscous damping of each body", minimum=0.0),
    Parameter("k1", "1", 1.0, "linear stiffness", minimum=0.0),
    Parameter("k2", "1", 0.01, "cubic stiffness (hardening > 0)", minimum=-np.inf),
    Parameter("F", "1", 1.0, "forcing amplitude", minimum=0.0),
    Parameter("w", "1", 1.3, "forcing frequency", minimum=0.0, strict=True),
)

# Default box of (x, v) the catalogue samples: wide enough for every attractor.
CATALOGUE_BOX = {"x": (-12.0, 12.0), "v": (-12.0, 12.0)}

# Packed parameter layout (indices into the float64 array the kernels receive).
C, K1, K2, F, W = 0, 1, 2, 3, 4
D, KC, CC, COS_PHI, SIN_PHI, NO_TENSION, PHI = 5, 6, 7, 8, 9, 10, 11

CONTACT_BIT = 1  # surface 0: x1 - x2 - d >= 0
FORCE_BIT = 2  # surface 1 (no-tension law only): k_c delta + c_c delta' >= 0


def pack_body(values: Mapping[str, float]) -> np.ndarray:
    """Body parameters as the float64 array ``[c, k1, k2, F, w]``."""
    return pack_parameters(BODY_PARAMETERS, values)


def pack_pair(values: Mapping[str, float]) -> np.ndarray:
    """Pair parameters: the body block, then the coupling block (see ``pack_coupling``)."""
    return np.concatenate([pack_body(values), pack_coupling(values)])


@njit(cache=True)
def body_rhs(t, y, p, mode, out):
    x = y[0]
    v = y[1]
    out[0] = v
    out[1] = p[F] * sin(p[W] * t) - p[C] * v - p[K1] * x - p[K2] * x * x * x


@njit(cache=True)
def body_jacobian(t, y, p, mode, jac, dfdt):
    x = y[0]
    jac[0, 0] = 0.0
    jac[0, 1] = 1.0
    jac[1, 0] = -p[K1] - 3.0 * p[K2] * x * x
    jac[1, 1] = -p[C]
    dfdt[0] = 0.0
    dfdt[1] = p[F] * p[W] * cos(p[W] * t)


@njit(cache=True)
def contact_active(p, mode):
    """True when the stop exerts force in this mode (engaged, and not clipped)."""
    if not (mode & CONTACT_BIT):
        return False
    return p[NO_TENSION] == 0.0 or (mode & FORCE_BIT) != 0


@njit(cache=True)
def pair_rhs(t, y, p, mode, out):
    # One sine and one cosine serve both bodies: sin(wt + phi) = s cos(phi) + c sin(phi).
    wt = p[W] * t
    s = sin(wt)
    co = cos(wt)
    x1 = y[0]
    v1 = y[1]
    x2 = y[2]
    v2 = y[3]
    fc = 0.0
    if contact_active(p, mode):
        fc = p[KC] * (x1 - x2 - p[D]) + p[CC] * (v1 - v2)
    out[0] = v1
    out[1] = p[F] * s - p[C] * v1 - p[K1] * x1 - p[K2] * x1 * x1 * x1 - fc
    out[2] = v2
    forcing2 = p[F] * (s * p[COS_PHI] + co * p[SIN_PHI])
    out[3] = forcing2 - p[C] * v2 - p[K1] * x2 - p[K2] * x2 * x2 * x2 + fc


@njit(cache=True)
def pair_jacobian(t, y, p, mode, jac, dfdt):
    a = 1.0 if contact_active(p, mode) else 0.0
    kc = a * p[KC]
    cc = a * p[CC]
    jac[:, :] = 0.0
    jac[0, 1] = 1.0
    jac[2, 3] = 1.0
    jac[1, 0] = -p[K1] - 3.0 * p[K2] * y[0] * y[0] - kc
    jac[1, 1] = -p[C] - cc
    jac[1, 2] = kc
    jac[1, 3] = cc
    jac[3, 0] = kc
    jac[3, 1] = cc
    jac[3, 2] = -p[K1] - 3.0 * p[K2] * y[2] * y[2] - kc
    jac[3, 3] = -p[C] - cc
    wt = p[W] * t
    fw = p[F] * p[W]
    dfdt[0] = 0.0
    dfdt[1] = fw * cos(wt)
    dfdt[2] = 0.0
    dfdt[3] = fw * (cos(wt) * p[COS_PHI] - sin(wt) * p[SIN_PHI])


def contact_surfaces(p: np.ndarray, d_index: int, kc_index: int, cc_index: int,
                     nt_index: int, extra_rows: list, extra_b: list, extra_names: list):
    """Surfaces of a pair: contact first, then the model's own, then the force surface."""
    A = [[1.0, 0.0, -1.0, 0.0]] + extra_rows
    b = [-p[d_index]] + extra_b
    names = ["contact"] + extra_names
    requires = {}
    if p[nt_index] != 0.0:
        kc, cc = p[kc_index], p[cc_index]
        requires[len(A)] = 0
        A.append([kc, cc, -kc, -cc])
        b.append(-kc * p[d_index])
        names.append("stop force")
    n = len(A)
    return Surfaces(np.array(A, dtype=np.float64), np.array(b, dtype=np.float64),
                    relevance_table(n, requires), 0, tuple(names))


def pair_surfaces(p: np.ndarray) -> Surfaces:
    return contact_surfaces(p, D, KC, CC, NO_TENSION, [], [], [])


def body_surfaces(p: np.ndarray) -> Surfaces:
    return Surfaces(np.zeros((0, 2)), np.zeros(0), relevance_table(0, {}), -1, ())


DUFFING_BODY = System(
    model="duffing",
    bodies=1,
    description="forced Duffing oscillator",
    state_names=("x", "v"),
    parameters=BODY_PARAMETERS,
    rhs=body_rhs,
    jacobian=body_jacobian,
    pack=pack_body,
    surfaces=body_surfaces,
    extra={"catalogue_box": CATALOGUE_BOX},
)

DUFFING_PAIR = System(
    model="duffing",
    bodies=2,
    description="two forced Duffing oscillators coupled by a spring-damper stop",
    state_names=("x1", "v1", "x2", "v2"),
    parameters=BODY_PARAMETERS + COUPLING_PARAMETERS,
    rhs=pair_rhs,
    jacobian=pair_jacobian,
    pack=pack_pair,
    surfaces=pair_surfaces,
    extra={"catalogue_box": CATALOGUE_BOX, "laws": LAWS, "right_sign": 1.0, "right_phase": 0.0},
)
