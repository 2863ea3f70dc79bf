"""Stop laws: the force of a pair's soft stop, its slopes and its switching surfaces.

The stop acts on the compression ``delta = x1 - x2 - d`` and its rate
``delta' = v1 - v2``; its force ``F_C`` pushes the left body back (``x1'' = ... - F_C``)
and the right body on (``x2'' = ... + F_C``). Contact is ``delta >= 0``; outside it
``F_C = 0`` for every law. The registered laws (``LAWS``):

- ``paper`` (the study's): ``F_C = k_c delta + c_c delta'``; the damper may pull.
- ``no-tension``: the same, clipped at 0 (the stop never pulls). It adds a switching
  surface, the force ``k_c delta + c_c delta' = 0``, watched only in contact.
- ``hunt-crossley`` (Hertzian contact with Hunt and Crossley's damping):
  ``F_C = k_c delta^n + c_c delta^n delta'`` with ``n = [coupling] exponent`` (default
  3/2, allowed 1 <= n <= 10). It is continuous at contact onset (no force jump) and may
  pull while ``delta' < -k_c / c_c``, as the formula says; n >= 1 keeps its Jacobian
  finite at onset.
- ``rigid`` (a chain's stops only): no force and no penetration; an impact reverses the
  relative normal velocity scaled by the coefficient of restitution ``r`` in [0, 1]
  (Newton's law, momentum of the two bodies kept; a wall takes the body's velocity
  alone), chattering passes to sticking. The reset is the kernels' (``kernels/impacts.py``);
  while the stop's contact bit is set the bodies are stuck (``chain.py``).

How a restoring force and a stop law combine: a pair's module (``duffing.py``,
``bilinear.py``) packs its body block and then this module's coupling block
(:func:`pack_coupling`) starting at index ``at``; its surfaces come from
:func:`pair_surfaces` (contact first, so the contact bit is 1; then the model's own;
then the law's, whose first bit the module passes as ``law_bit``); its ``rhs`` adds
:func:`stop_force`, its ``jacobian`` :func:`stop_slopes`, ``(k, c) = (dF_C/d delta,
dF_C/d delta')``, as rows ``d x1''/d(x1, v1, x2, v2) = (-k, -c, k, c)`` and
``d x2''/d(...) = (k, c, -k, -c)``. The model never reads the law.

Adding a stop law is this module alone: a law code, its jitted force and slopes (and a
branch for the code in :func:`stop_force` and :func:`stop_slopes`), its extra surfaces
if any, and its :class:`StopLaw` entry in ``LAWS`` (name, formula, its own ``[coupling]``
keys). The scene reader, ``softimpact example`` and ``info`` read ``LAWS``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
from numba import njit

from .base import Surfaces, relevance_table

# The coupling block (offsets from its start ``at`` in the packed parameters). cos and sin
# of phi are precomputed so a pair's rhs needs one sine and one cosine per evaluation.
D, KC, CC, COS_PHI, SIN_PHI, LAW, PHI, EXPONENT, RESTITUTION = range(9)
COUPLING_SIZE = 9

CONTACT_BIT = 1  # surface 0 of every pair: delta = x1 - x2 - d >= 0

# Law codes, packed as float64 at LAW.
PAPER = 0.0
NO_TENSION = 1.0
HUNT_CROSSLEY = 2.0
RIGID = 3.0  # no force: impacts are velocity resets (kernels/impacts.py), a chain's only


# ---------------------------------------------------------------- the laws, jitted


@njit(cache=True)
def linear_force(p, at, delta, rate):
    """``k_c delta + c_c delta'`` (paper; no-tension while pushing)."""
    return p[at + KC] * delta + p[at + CC] * rate


@njit(cache=True)
def hunt_crossley_force(p, at, delta, rate):
    """``(k_c + c_c delta') delta^n`` while ``delta >= 0``; 0 past the surface (reached in
    the engaged mode only by a step's trial stages before the crossing is located)."""
    if delta < 0.0:
        return 0.0
    power = delta ** p[at + EXPONENT]
    return p[at + KC] * power + p[at + CC] * power * rate


@njit(cache=True)
def hunt_crossley_slopes(p, at, delta, rate):
    """``(dF/d delta, dF/d delta') = (n delta^(n-1) (k_c + c_c delta'), c_c delta^n)``,
    finite at ``delta = 0`` because ``n >= 1`` (there ``k_c + c_c delta'`` for n = 1, the
    derivative from inside the contact; 0 for n > 1); 0 past the surface."""
    if delta < 0.0:
        return 0.0, 0.0
    n = p[at + EXPONENT]
    below = delta ** (n - 1.0)
    return n * below * (p[at + KC] + p[at + CC] * rate), p[at + CC] * below * delta


@njit(cache=True)
def stop_force(p, at, mode, law_bit, delta, rate):
    """``F_C`` in ``mode`` at compression ``delta`` and rate ``delta'``.

    p : packed parameters, the coupling block at ``at``; law_bit : mode bit of the law's
    first extra surface (the no-tension force surface). The linear laws come first, in
    one expression: with another law's branch before them, dopri5 ran ~11 % slower on a
    Duffing pair trajectory (CPU time, same machine); in this order, as fast as before."""
    if not (mode & CONTACT_BIT):
        return 0.0
    law = p[at + LAW]
    if law == PAPER or (law == NO_TENSION and (mode & law_bit) != 0):
        return linear_force(p, at, delta, rate)
    if law == HUNT_CROSSLEY:
        return hunt_crossley_force(p, at, delta, rate)
    return 0.0


@njit(cache=True)
def stop_slopes(p, at, mode, law_bit, delta, rate):
    """``(dF_C/d delta, dF_C/d delta')`` in ``mode`` (arguments as :func:`stop_force`;
    the linear laws first, for the same reason)."""
    law = p[at + LAW]
    if law != HUNT_CROSSLEY:
        engaged = (mode & CONTACT_BIT) != 0 and (law == PAPER or (mode & law_bit) != 0)
        a = 1.0 if engaged else 0.0
        return a * p[at + KC], a * p[at + CC]
    if not (mode & CONTACT_BIT):
        return 0.0, 0.0
    return hunt_crossley_slopes(p, at, delta, rate)


# ---------------------------------------------------------------- registry


@dataclass(frozen=True)
class LawKey:
    """A ``[coupling]`` key only some laws use, packed at ``slot`` of the coupling block
    (its default there for the laws that do not use it)."""

    name: str
    default: float
    low: float
    high: float
    slot: int
    description: str

    def check(self, value: float) -> str | None:
        """What is wrong with ``value``, or None."""
        if not self.low <= value <= self.high:
            return f"must be in [{self.low:g}, {self.high:g}]"
        return None


def _no_surfaces(p: np.ndarray, at: int):
    return [], [], []


def _force_surface(p: np.ndarray, at: int):
    """The no-tension law's surface ``k_c delta + c_c delta' = 0`` (watched in contact)."""
    kc, cc = p[at + KC], p[at + CC]
    return [[kc, cc, -kc, -cc]], [-kc * p[at + D]], ["stop force"]


@dataclass(frozen=True)
class StopLaw:
    """One registered law: ``code`` is packed at LAW; ``surfaces(p, at)`` gives its extra
    surfaces as (rows of A, entries of b, names), each watched only in contact."""

    name: str
    code: float
    formula: str
    keys: tuple[LawKey, ...] = ()
    surfaces: Callable[[np.ndarray, int], tuple[list, list, list]] = _no_surfaces
    soft: bool = True  # False: no k_c, c_c (the rigid law); a chain's stops only


EXPONENT_KEY = LawKey(
    "exponent", 1.5, 1.0, 10.0, EXPONENT,
    "exponent n of the Hertzian stop (3/2: Hertz; n >= 1 keeps dF/d delta finite at onset)")

RESTITUTION_KEY = LawKey(
    "r", 0.8, 0.0, 1.0, RESTITUTION,
    "coefficient of restitution r of the rigid stop: v_rel+ = -r v_rel- (0 plastic, 1 elastic)")

LAWS: dict[str, StopLaw] = {
    law.name: law for law in (
        StopLaw("paper", PAPER, "k_c delta + c_c delta' (the damper may pull)"),
        StopLaw("no-tension", NO_TENSION, "max(k_c delta + c_c delta', 0) (never pulls)",
                surfaces=_force_surface),
        StopLaw("hunt-crossley", HUNT_CROSSLEY, "k_c delta^n + c_c delta^n delta' (Hertzian)",
                keys=(EXPONENT_KEY,)),
        StopLaw("rigid", RIGID, "impacts: v_rel+ = -r v_rel- (Newton), momentum kept",
                keys=(RESTITUTION_KEY,), soft=False),
    )
}

LAW_KEYS: dict[str, LawKey] = {key.name: key for law in LAWS.values() for key in law.keys}


def get_law(name: str) -> StopLaw:
    """The registered law called ``name``; a ValueError naming the laws otherwise."""
    try:
        return LAWS[name]
    except KeyError:
        raise ValueError(f"unknown stop law {name!r}; laws: {', '.join(LAWS)}") from None


# ---------------------------------------------------------------- packing and surfaces


def pack_coupling(values: Mapping[str, float]) -> np.ndarray:
    """The coupling block every pair appends to its body block:
    ``d, k_c, c_c, cos phi, sin phi, law code, phi, exponent``."""
    phi = float(values["phi"])
    block = np.array([float(values["d"]), float(values["k_c"]), float(values["c_c"]),
                      np.cos(phi), np.sin(phi),
                      get_law(values.get("law", "paper")).code, phi, 0.0, 0.0])
    for key in LAW_KEYS.values():
        block[key.slot] = float(values.get(key.name, key.default))
    return block


def pair_surfaces(p: np.ndarray, at: int, own_rows: list, own_b: list,
                  own_names: list) -> Surfaces:
    """A pair's surfaces: contact first, then the model's own, then the law's (each law
    surface watched only in contact)."""
    law = next(law for law in LAWS.values() if law.code == p[at + LAW])
    rows, b, names = law.surfaces(p, at)
    A = [[1.0, 0.0, -1.0, 0.0]] + own_rows + rows
    offsets = [-p[at + D]] + own_b + b
    first = 1 + len(own_rows)
    requires = {first + i: 0 for i in range(len(rows))}
    return Surfaces(np.array(A, dtype=np.float64), np.array(offsets, dtype=np.float64),
                    relevance_table(len(A), requires), 1,
                    tuple(["contact"] + own_names + names))
