"""Duffing oscillators: one body alone, and the pair coupled by a soft stop.

    x1'' + c x1' + k1 x1 + k2 x1^3 + F_C = F sin(w t)      (the pair: systems/pair.py)
    x2'' + c x2' + k1 x2 + k2 x2^3 - F_C = F sin(w t + phi)
    F_C = the stop law's force (systems/stops.py), 0 while x1 - x2 < d

All quantities are dimensionless (mass 1); time in units of 1/w0.
"""

from __future__ import annotations

from collections.abc import Mapping
from math import cos, sin

import numpy as np
from numba import njit

from . import stops
from .base import (
    COUPLING_PARAMETERS,
    Parameter,
    Surfaces,
    System,
    pack_parameters,
    relevance_table,
)
from .pair import pair_jacobian_with, pair_rhs_with
from .stops import pack_coupling

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
STOP = 5  # start of the coupling block (systems/stops.py), whose entries follow:
D, KC, CC = STOP + stops.D, STOP + stops.KC, STOP + stops.CC
COS_PHI, SIN_PHI, LAW, PHI = STOP + stops.COS_PHI, STOP + stops.SIN_PHI, STOP + stops.LAW, \
    STOP + stops.PHI
EXPONENT = STOP + stops.EXPONENT

# surface 0: contact (x1 - x2 - d >= 0); no surface of its own; then the law's
LAW_BIT = 2


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
def pair_rhs(t, y, p, mode, out):
    pair_rhs_with(t, y, p, mode, STOP, LAW_BIT, p[K2] * y[0] * y[0] * y[0],
                  p[K2] * y[2] * y[2] * y[2], out)


@njit(cache=True)
def pair_jacobian(t, y, p, mode, jac, dfdt):
    pair_jacobian_with(t, y, p, mode, STOP, LAW_BIT, 3.0 * p[K2] * y[0] * y[0],
                       3.0 * p[K2] * y[2] * y[2], jac, dfdt)


def pair_surfaces(p: np.ndarray) -> Surfaces:
    return stops.pair_surfaces(p, STOP, [], [], [])


def body_surfaces(p: np.ndarray) -> Surfaces:
    return Surfaces(np.zeros((0, 2)), np.zeros(0), relevance_table(0, {}), 0, ())


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
    extra={"catalogue_box": CATALOGUE_BOX, "laws": tuple(stops.LAWS), "right_sign": 1.0,
           "right_phase": 0.0},
)
