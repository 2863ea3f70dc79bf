"""Bilinear oscillators: one body alone, and the mirror-symmetric pair.

Each body has a linear spring k1 and a second spring k2 engaged beyond a gap d1; the
left body's second spring is on its left, the right body's on its right:

    x1'' + c x1' + k1 x1 + k2 (x1 + d1) H(-x1 - d1) + F_C = F sin(w t)
    x2'' + c x2' + k1 x2 + k2 (x2 - d1) H( x2 - d1) - F_C = F sin(w t + phi)

The pair's equations are systems/pair.py's, with these springs. The one-body system is
the left body. Mirror symmetry: if x(t) solves the left body's
equation, -x(t) solves the right body's with forcing shifted by pi. F_C is the stop law's
force (systems/stops.py), 0 while x1 - x2 < d.
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
    Parameter("c", "1", 0.02, "viscous damping of each body", minimum=0.0),
    Parameter("k1", "1", 1.0, "stiffness of the main spring", minimum=0.0),
    Parameter("k2", "1", 29.0, "stiffness of the second spring, engaged beyond d1", minimum=0.0),
    Parameter("F", "1", 0.518, "forcing amplitude", minimum=0.0),
    Parameter("w", "1", 0.86, "forcing frequency", minimum=0.0, strict=True),
    Parameter("d1", "1", 1.26, "gap before the second spring engages", minimum=0.0),
)

# Default box of (x, v) the catalogue samples: wide enough for every attractor.
CATALOGUE_BOX = {"x": (-3.0, 3.0), "v": (-3.0, 3.0)}

C, K1, K2, F, W, D1 = 0, 1, 2, 3, 4, 5
STOP = 6  # start of the coupling block (systems/stops.py), whose entries follow:
D, LAW = STOP + stops.D, STOP + stops.LAW

# surface 0: contact (x1 - x2 - d >= 0); then the springs; then the law's
LEFT_SPRING_BIT = 2  # surface 1: -x1 - d1 >= 0
RIGHT_SPRING_BIT = 4  # surface 2: x2 - d1 >= 0
LAW_BIT = 8  # surface 3: the law's first (no-tension: the stop force)


def pack_body(values: Mapping[str, float]) -> np.ndarray:
    """Body parameters as the float64 array ``[c, k1, k2, F, w, d1]``."""
    return pack_parameters(BODY_PARAMETERS, values)


def pack_pair(values: Mapping[str, float]) -> np.ndarray:
    """Pair parameters: the body block, then the coupling block (see ``pack_coupling``)."""
    return np.concatenate([pack_body(values), pack_coupling(values)])


@njit(cache=True)
def body_rhs(t, y, p, mode, out):
    x = y[0]
    v = y[1]
    spring = 0.0
    if mode & 1:
        spring = p[K2] * (x + p[D1])
    out[0] = v
    out[1] = p[F] * sin(p[W] * t) - p[C] * v - p[K1] * x - spring


@njit(cache=True)
def body_jacobian(t, y, p, mode, jac, dfdt):
    jac[0, 0] = 0.0
    jac[0, 1] = 1.0
    jac[1, 0] = -p[K1] - (p[K2] if mode & 1 else 0.0)
    jac[1, 1] = -p[C]
    dfdt[0] = 0.0
    dfdt[1] = p[F] * p[W] * cos(p[W] * t)


@njit(cache=True)
def pair_rhs(t, y, p, mode, out):
    s1 = p[K2] * (y[0] + p[D1]) if mode & LEFT_SPRING_BIT else 0.0
    s2 = p[K2] * (y[2] - p[D1]) if mode & RIGHT_SPRING_BIT else 0.0
    pair_rhs_with(t, y, p, mode, STOP, LAW_BIT, s1, s2, out)


@njit(cache=True)
def pair_jacobian(t, y, p, mode, jac, dfdt):
    pair_jacobian_with(t, y, p, mode, STOP, LAW_BIT,
                       p[K2] if mode & LEFT_SPRING_BIT else 0.0,
                       p[K2] if mode & RIGHT_SPRING_BIT else 0.0, jac, dfdt)


def pair_surfaces(p: np.ndarray) -> Surfaces:
    return stops.pair_surfaces(
        p, STOP,
        [[-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]],
        [-p[D1], -p[D1]],
        ["left spring", "right spring"],
    )


def body_surfaces(p: np.ndarray) -> Surfaces:
    return Surfaces(np.array([[-1.0, 0.0]]), np.array([-p[D1]]), relevance_table(1, {}), 0,
                    ("spring",))


BILINEAR_BODY = System(
    model="bilinear",
    bodies=1,
    description="forced bilinear oscillator (second spring on the left, beyond d1)",
    state_names=("x", "v"),
    parameters=BODY_PARAMETERS,
    rhs=body_rhs,
    jacobian=body_jacobian,
    pack=pack_body,
    surfaces=body_surfaces,
    extra={"catalogue_box": CATALOGUE_BOX},
    piecewise_linear=True,
)

BILINEAR_PAIR = System(
    model="bilinear",
    bodies=2,
    description="two mirror-symmetric bilinear oscillators coupled by a spring-damper stop",
    state_names=("x1", "v1", "x2", "v2"),
    parameters=BODY_PARAMETERS + COUPLING_PARAMETERS,
    rhs=pair_rhs,
    jacobian=pair_jacobian,
    pack=pack_pair,
    surfaces=pair_surfaces,
    extra={"catalogue_box": CATALOGUE_BOX, "laws": tuple(stops.LAWS), "right_sign": -1.0,
           "right_phase": np.pi},
    piecewise_linear=True,  # with a linear stop law
)
