"""The chain family: n forced oscillators with kinks and stops, the model as data.

Body ``i`` (1..n) of mass ``m_i``:

    m_i x_i'' + c_i x_i' + r_i(x_i) + sum of its kinks' forces + sum of its stops' forces
        = F_i sin(w t + phi_i)

    r_i(x) = k1 x + k2 x^3 + sum_p k_xp x^p     (p = 2, 4, 5, ..., MAX_POWER)

A *kink* is a one-sided linear spring of stiffness ``k`` on one body engaging past a
position ``x_k``: on the right side (``x - x_k >= 0``) or on the left (``x_k - x >= 0``);
its force is ``k (x - x_k)`` while engaged (the bilinear body is one such spring). A
*stop* acts on the compression ``delta``: between bodies ``i`` and ``j``
``delta = x_i - x_j - d`` (in contact while ``x_i - x_j >= d``), its force ``F_C``
pushing ``i`` back and ``j`` on; with a wall at ``X`` on the right of body ``i``
``delta = x_i - X``, on its left ``delta = X - x_i``, the wall pushing the body back.
``F_C`` is a stop law of ``stops.py`` with the stop's own ``k_c``, ``c_c`` (and law keys).

The model reaches the kernels as data: :func:`pack` writes one float64 array
(header, then a block per body, per kink and per stop; the layout below), and ONE jitted
:func:`chain_rhs`, ONE :func:`chain_jacobian` (and one variational wrapper in
``variational.py``) read it: a new chain, of any size, runs with no new compilation.

Switching surfaces, in order: each stop's contact (``delta >= 0``; the contact mask
holds them), each kink's (engaged side), then the laws' extra surfaces (the no-tension
force surface of each such stop, watched only in that stop's contact). The relevance
table has ``2**n_surfaces`` entries: at most ``base.MAX_SURFACES`` surfaces.

Parameter names (``System.parameters``, the names ``pack`` reads): ``w``; per body
``m.i, c.i, k1.i, k2.i, F.i, phi.i`` and ``k_xp.i`` for each extra power p the model
declares; per kink ``kink.k.x`` (its position) and ``kink.k.k`` (stiffness); per stop
``stop.s.d`` (between bodies) or ``stop.s.wall`` (a wall's position), ``stop.s.k_c``,
``stop.s.c_c`` and its law keys (``stop.s.exponent``); a rigid stop has no ``k_c``,
``c_c`` but its coefficient of restitution ``stop.s.r``.

Rigid stops (law ``rigid``): no force while free, impacts are velocity resets made by the
kernels' impact loop (``kernels/impacts.py``), which reads the impact table ``pack``
appends (its layout there: per rigid stop its contact surface, ``r`` and the direction
``M^-1 a / (a^T M^-1 a)`` of the impulse, ``a`` the surface's row). The stop's contact
bit set means *stuck*: the body rests on its wall (acceleration 0) or the two bodies move
together (one acceleration, the momentum-weighted mean of their free accelerations); the
surface is not watched while stuck (the impact loop releases it when the contact force
would pull). Two stuck stops sharing a body are each imposed in turn (exact only when
they share none).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from math import cos, sin

import numpy as np
from numba import njit

from ..kernels import impacts
from . import stops
from .base import MAX_SURFACES, Parameter, Surfaces, System, relevance_table

MAX_BODIES = 8
MAX_POWER = 9  # highest power of the polynomial restoring force
EXTRA_POWERS = tuple(p for p in range(2, MAX_POWER + 1) if p != 3)  # keys k_x2, k_x4, ...

# ---------------------------------------------------------------- packed layout
# header
W, N, P, NK, NS, BODY_AT, KINK_AT, STOP_AT = range(8)
HEADER = 8
# a body's block: mass, damping, forcing, cos and sin of its phase, phase, then the
# polynomial's coefficients a_1 .. a_P (of x^1 .. x^P)
B_M, B_C, B_F, B_COS, B_SIN, B_PHI, B_POLY = range(7)
# a kink's block: body index (0-based), position, side (+1 right, -1 left), stiffness,
# its surface's mode bit
K_BODY, K_X, K_SIDE, K_K, K_BIT = range(5)
KINK_SIZE = 5
# a stop's block: bodies i, j (0-based; j = -1: a wall), sign s (delta = s (x_i - x_j) - D;
# s = -1 only for a wall on the left), mode bits of its contact and of its law's surface
# (0: none), then the coupling block of stops.py (D, k_c, c_c, ..., law code, exponent)
S_I, S_J, S_SIGN, S_CONTACT_BIT, S_LAW_BIT, S_COUPLING = range(6)
STOP_SIZE = S_COUPLING + stops.COUPLING_SIZE

SIDES = {"right": 1.0, "left": -1.0}


def has_law_surface(law: str) -> bool:
    """Whether the stop law adds a switching surface (the no-tension force surface; a
    law with more than one is not supported here)."""
    return stops.LAWS[law].surfaces is not stops.LAWS["paper"].surfaces


@dataclass(frozen=True)
class Kink:
    """A one-sided spring on ``body`` (1-based) engaging on ``side`` of its position."""

    body: int
    side: str


@dataclass(frozen=True)
class Stop:
    """A stop between ``body`` and ``other`` (1-based; ``other = 0``: a wall on ``side``)
    with its law."""

    body: int
    other: int = 0
    side: str = ""
    law: str = "paper"

    @property
    def wall(self) -> bool:
        return self.other == 0


@dataclass(frozen=True)
class ChainModel:
    """The structure of a chain (what changes the equations' shape): bodies, the extra
    powers of the restoring force, the kinks and the stops. Values are parameters."""

    bodies: int
    powers: tuple[int, ...] = ()  # extra powers (keys k_xp): some of EXTRA_POWERS
    kinks: tuple[Kink, ...] = ()
    stops: tuple[Stop, ...] = ()

    def value_problems(self, values: Mapping[str, float]) -> list[str]:
        """What is wrong with the values of a well-formed structure: overlapping kinks (two
        on one body and side at the same position)."""
        seen: dict[tuple[int, str, float], int] = {}
        out = []
        for k, kink in enumerate(self.kinks, 1):
            key = (kink.body, kink.side, float(values[f"kink.{k}.x"]))
            if key in seen:
                out.append(f"kinks {seen[key]} and {k} overlap: body {kink.body}, side "
                           f"{kink.side!r}, position {key[2]:g}")
            seen.setdefault(key, k)
        return out

    def problems(self) -> list[str]:
        """What is wrong with the structure (empty when nothing)."""
        out = []
        if not 1 <= self.bodies <= MAX_BODIES:
            out.append(f"bodies must be in 1..{MAX_BODIES}, got {self.bodies}")
            return out
        for k, kink in enumerate(self.kinks, 1):
            if not 1 <= kink.body <= self.bodies:
                out.append(f"kink {k}: body {kink.body} does not exist (bodies 1..{self.bodies})")
            if kink.side not in SIDES:
                out.append(f"kink {k}: side must be \"left\" or \"right\", got {kink.side!r}")
        for s, stop in enumerate(self.stops, 1):
            for b in (stop.body,) + (() if stop.wall else (stop.other,)):
                if not 1 <= b <= self.bodies:
                    out.append(f"stop {s}: body {b} does not exist (bodies 1..{self.bodies})")
            if not stop.wall and stop.body == stop.other:
                out.append(f"stop {s}: between a body and itself ({stop.body})")
            if stop.wall and stop.side not in SIDES:
                out.append(f"stop {s}: a wall needs side = \"left\" or \"right\"")
            if stop.law not in stops.LAWS:
                out.append(f"stop {s}: unknown law {stop.law!r}; laws: {', '.join(stops.LAWS)}")
        if not out and self.n_surfaces > MAX_SURFACES:
            out.append(f"{self.n_surfaces} switching surfaces (stops, kinks, no-tension "
                       f"force surfaces): at most {MAX_SURFACES}")
        return out

    @property
    def n_surfaces(self) -> int:
        return len(self.stops) + len(self.kinks) + sum(
            has_law_surface(stop.law) for stop in self.stops)

    @property
    def rigid(self) -> tuple[int, ...]:
        """Indices (0-based) of the rigid stops."""
        return tuple(s for s, stop in enumerate(self.stops) if not stops.LAWS[stop.law].soft)

    @property
    def max_power(self) -> int:
        return max((3,) + self.powers)

    @property
    def polynomial_only_linear(self) -> bool:
        return not self.powers

    def state_names(self) -> tuple[str, ...]:
        return tuple(name for i in range(1, self.bodies + 1) for name in (f"x{i}", f"v{i}"))

    def parameters(self) -> tuple[Parameter, ...]:
        """Every parameter, in pack order (see the module docstring for the names)."""
        out = [Parameter("w", "1", 1.3, "forcing frequency", minimum=0.0, strict=True)]
        for i in range(1, self.bodies + 1):
            out += [
                Parameter(f"m.{i}", "1", 1.0, f"mass of body {i}", minimum=0.0, strict=True),
                Parameter(f"c.{i}", "1", 0.05, f"viscous damping of body {i}", minimum=0.0),
                Parameter(f"k1.{i}", "1", 1.0, f"linear stiffness of body {i}"),
                Parameter(f"k2.{i}", "1", 0.0, f"cubic stiffness of body {i}"),
                Parameter(f"F.{i}", "1", 1.0, f"forcing amplitude of body {i}", minimum=0.0),
                Parameter(f"phi.{i}", "rad", 0.0, f"forcing phase of body {i}"),
            ]
            out += [Parameter(f"k_x{p}.{i}", "1", 0.0, f"coefficient of x^{p} of body {i}")
                    for p in self.powers]
        for k in range(1, len(self.kinks) + 1):
            out += [Parameter(f"kink.{k}.x", "1", None, f"position of kink {k}"),
                    Parameter(f"kink.{k}.k", "1", None, f"stiffness of kink {k}", minimum=0.0)]
        for s, stop in enumerate(self.stops, 1):
            if stop.wall:
                out.append(Parameter(f"stop.{s}.wall", "1", None, f"wall position of stop {s}"))
            else:
                out.append(Parameter(f"stop.{s}.d", "1", None, f"gap of stop {s}"))
            if stops.LAWS[stop.law].soft:
                out += [Parameter(f"stop.{s}.k_c", "1", 8.0, f"stiffness of stop {s}",
                                  minimum=0.0),
                        Parameter(f"stop.{s}.c_c", "1", 10.0, f"damping of stop {s}",
                                  minimum=0.0)]
            out += [Parameter(f"stop.{s}.{key.name}", "1", key.default,
                              f"{key.description} (stop {s})", minimum=key.low)
                    for key in stops.LAWS[stop.law].keys]
        return tuple(out)

    def pack(self, values: Mapping[str, float]) -> np.ndarray:
        """The packed float64 array the kernels read (layout above)."""
        n, top = self.bodies, self.max_power
        body_size = B_POLY + top
        body_at = HEADER
        kink_at = body_at + n * body_size
        stop_at = kink_at + KINK_SIZE * len(self.kinks)
        p = np.zeros(stop_at + STOP_SIZE * len(self.stops))
        p[:HEADER] = [float(values["w"]), n, top, len(self.kinks), len(self.stops),
                      body_at, kink_at, stop_at]
        for i in range(n):
            at, b = body_at + i * body_size, i + 1
            phi = float(values[f"phi.{b}"])
            p[at + B_M] = float(values[f"m.{b}"])
            p[at + B_C] = float(values[f"c.{b}"])
            p[at + B_F] = float(values[f"F.{b}"])
            p[at + B_COS], p[at + B_SIN], p[at + B_PHI] = np.cos(phi), np.sin(phi), phi
            p[at + B_POLY + 0] = float(values[f"k1.{b}"])
            p[at + B_POLY + 2] = float(values[f"k2.{b}"])
            for power in self.powers:
                p[at + B_POLY + power - 1] = float(values[f"k_x{power}.{b}"])
        n_stops = len(self.stops)
        for k, kink in enumerate(self.kinks):
            at = kink_at + KINK_SIZE * k
            p[at + K_BODY] = kink.body - 1
            p[at + K_X] = float(values[f"kink.{k + 1}.x"])
            p[at + K_SIDE] = SIDES[kink.side]
            p[at + K_K] = float(values[f"kink.{k + 1}.k"])
            p[at + K_BIT] = float(1 << (n_stops + k))
        law_surface = n_stops + len(self.kinks)
        for s, stop in enumerate(self.stops):
            at = stop_at + STOP_SIZE * s
            law = stops.LAWS[stop.law]
            sign = SIDES[stop.side] if stop.wall else 1.0
            p[at + S_I] = stop.body - 1
            p[at + S_J] = -1.0 if stop.wall else stop.other - 1
            p[at + S_SIGN] = sign
            p[at + S_CONTACT_BIT] = float(1 << s)
            if has_law_surface(stop.law):
                p[at + S_LAW_BIT] = float(1 << law_surface)
                law_surface += 1
            gap = (sign * float(values[f"stop.{s + 1}.wall"]) if stop.wall
                   else float(values[f"stop.{s + 1}.d"]))
            block = p[at + S_COUPLING: at + STOP_SIZE]
            block[stops.D] = gap
            block[stops.KC] = float(values.get(f"stop.{s + 1}.k_c", 0.0))
            block[stops.CC] = float(values.get(f"stop.{s + 1}.c_c", 0.0))
            block[stops.COS_PHI] = 1.0
            block[stops.LAW] = law.code
            for key in stops.LAW_KEYS.values():
                block[key.slot] = float(values.get(f"stop.{s + 1}.{key.name}", key.default))
        if self.rigid:
            p = np.concatenate([p, self._impact_table(p)])
        return p

    def _impact_table(self, p: np.ndarray) -> np.ndarray:
        """The rigid stops' table ``kernels.impacts`` reads (its layout there), with the
        index where it starts as its last entry (the table follows ``p``)."""
        n = self.bodies
        masses = np.array([p[int(p[BODY_AT]) + i * (B_POLY + int(p[P])) + B_M]
                           for i in range(n)])
        table = [float(len(self.rigid))]
        for s in self.rigid:
            at = int(p[STOP_AT]) + STOP_SIZE * s
            a = self._delta_row(p, at, 2 * n, 0)[0::2]  # d delta / d x_k
            direction = (a / masses) / float(a @ (a / masses))
            block = np.zeros(impacts.DIRECTION + n)
            block[impacts.SURFACE] = s  # stop s's contact surface is surface s
            block[impacts.RESTITUTION] = p[at + S_COUPLING + stops.RESTITUTION]
            block[impacts.DIRECTION:] = direction
            table += list(block)
        return np.array(table + [float(p.shape[0])])

    def surfaces(self, p: np.ndarray) -> Surfaces:
        """Stops' contacts, kinks, then the laws' surfaces (see the module docstring)."""
        dim = 2 * self.bodies
        rows, offsets, names, requires = [], [], [], {}
        stop_at, kink_at = int(p[STOP_AT]), int(p[KINK_AT])
        for s in range(len(self.stops)):
            at = stop_at + STOP_SIZE * s
            rows.append(self._delta_row(p, at, dim, 0))
            offsets.append(-p[at + S_COUPLING + stops.D])
            names.append(f"stop {s + 1}")
        for k in range(len(self.kinks)):
            at = kink_at + KINK_SIZE * k
            row = np.zeros(dim)
            row[2 * int(p[at + K_BODY])] = p[at + K_SIDE]
            rows.append(row)
            offsets.append(-p[at + K_SIDE] * p[at + K_X])
            names.append(f"kink {k + 1}")
        for s in range(len(self.stops)):
            at = stop_at + STOP_SIZE * s
            if p[at + S_LAW_BIT] == 0.0:
                continue
            kc, cc = p[at + S_COUPLING + stops.KC], p[at + S_COUPLING + stops.CC]
            requires[len(rows)] = s
            rows.append(kc * self._delta_row(p, at, dim, 0) + cc * self._delta_row(p, at, dim, 1))
            offsets.append(-kc * p[at + S_COUPLING + stops.D])
            names.append(f"stop {s + 1} force")
        A = np.array(rows, dtype=np.float64).reshape(len(rows), dim)
        relevance = relevance_table(len(rows), requires)
        for s in self.rigid:  # a stuck rigid stop is released by the impact loop
            for mode in range(relevance.shape[0]):
                if mode & (1 << s):
                    relevance[mode] &= ~(1 << s)
        return Surfaces(A, np.array(offsets, dtype=np.float64), relevance,
                        (1 << len(self.stops)) - 1, tuple(names))

    @staticmethod
    def _delta_row(p: np.ndarray, at: int, dim: int, velocity: int) -> np.ndarray:
        """d delta / d y (velocity 0) or d delta' / d y (velocity 1) of the stop at ``at``."""
        row = np.zeros(dim)
        sign, i, j = p[at + S_SIGN], int(p[at + S_I]), int(p[at + S_J])
        row[2 * i + velocity] = sign
        if j >= 0:
            row[2 * j + velocity] = -sign
        return row


# ---------------------------------------------------------------- the jitted family


@njit(cache=True)
def _local_mode(p, at, mode):
    """The stop's mode as ``stops.stop_force`` reads it: contact on bit 1, its law's
    surface on bit 2."""
    local = 0
    if mode & np.int64(p[at + S_CONTACT_BIT]):
        local |= stops.CONTACT_BIT
    if mode & np.int64(p[at + S_LAW_BIT]):
        local |= 2
    return local


@njit(cache=True)
def _stick(p, mode, out, offset):
    """Impose each stuck rigid stop (its contact bit set) on the accelerations
    ``out[2 k + offset]``: 0 for a body on its wall, the momentum-weighted mean of the two
    bodies' free accelerations for a pair, the same float for both (their velocities, equal
    when they stuck, stay equal bit for bit)."""
    body_at, body_size = int(p[BODY_AT]), B_POLY + int(p[P])
    stop_at = int(p[STOP_AT])
    for s_ in range(int(p[NS])):
        at = stop_at + STOP_SIZE * s_
        if p[at + S_COUPLING + stops.LAW] != stops.RIGID:
            continue
        if not mode & np.int64(p[at + S_CONTACT_BIT]):
            continue
        i, j = int(p[at + S_I]), int(p[at + S_J])
        if j < 0:
            out[2 * i + offset] = 0.0
            continue
        m_i = p[body_at + i * body_size + B_M]
        m_j = p[body_at + j * body_size + B_M]
        common = (m_i * out[2 * i + offset] + m_j * out[2 * j + offset]) / (m_i + m_j)
        out[2 * i + offset] = common
        out[2 * j + offset] = common


@njit(cache=True)
def chain_rhs(t, y, p, mode, out):
    """Right-hand side of any chain (``p`` packed by :meth:`ChainModel.pack`)."""
    n, top = int(p[N]), int(p[P])
    body_at, body_size = int(p[BODY_AT]), B_POLY + int(p[P])
    wt = p[W] * t
    s = sin(wt)
    co = cos(wt)
    for i in range(n):  # forces per unit mass of each body on its own
        at = body_at + i * body_size
        x = y[2 * i]
        restoring = 0.0
        for q in range(top - 1, -1, -1):  # Horner: x (a_1 + x (a_2 + ...))
            restoring = restoring * x + p[at + B_POLY + q]
        restoring *= x
        forcing = p[at + B_F] * (s * p[at + B_COS] + co * p[at + B_SIN])
        out[2 * i] = y[2 * i + 1]
        out[2 * i + 1] = forcing - p[at + B_C] * y[2 * i + 1] - restoring
    kink_at = int(p[KINK_AT])
    for k in range(int(p[NK])):
        at = kink_at + KINK_SIZE * k
        if mode & np.int64(p[at + K_BIT]):
            i = int(p[at + K_BODY])
            out[2 * i + 1] -= p[at + K_K] * (y[2 * i] - p[at + K_X])
    stop_at = int(p[STOP_AT])
    for s_ in range(int(p[NS])):
        at = stop_at + STOP_SIZE * s_
        local = _local_mode(p, at, mode)
        if local == 0:
            continue
        sign, i, j = p[at + S_SIGN], int(p[at + S_I]), int(p[at + S_J])
        delta = y[2 * i]
        rate = y[2 * i + 1]
        if j >= 0:
            delta -= y[2 * j]
            rate -= y[2 * j + 1]
        c_at = at + S_COUPLING
        fc = stops.stop_force(p, c_at, local, 2, sign * delta - p[c_at + stops.D], sign * rate)
        out[2 * i + 1] -= sign * fc
        if j >= 0:
            out[2 * j + 1] += sign * fc
    for i in range(n):
        out[2 * i + 1] /= p[body_at + i * body_size + B_M]
    if p[NS] > 0:
        _stick(p, mode, out, 1)


@njit(cache=True)
def chain_jacobian(t, y, p, mode, jac, dfdt):
    """Exact Jacobian and time derivative of :func:`chain_rhs`."""
    n, top = int(p[N]), int(p[P])
    body_at, body_size = int(p[BODY_AT]), B_POLY + int(p[P])
    jac[:, :] = 0.0
    wt = p[W] * t
    s = sin(wt)
    co = cos(wt)
    for i in range(n):
        at = body_at + i * body_size
        x = y[2 * i]
        slope = 0.0
        for q in range(top - 1, 0, -1):  # d/dx sum a_q x^q = sum q a_q x^(q-1)
            slope = slope * x + (q + 1) * p[at + B_POLY + q]
        slope = slope * x + p[at + B_POLY]
        jac[2 * i, 2 * i + 1] = 1.0
        jac[2 * i + 1, 2 * i] = -slope
        jac[2 * i + 1, 2 * i + 1] = -p[at + B_C]
        dfdt[2 * i] = 0.0
        dfdt[2 * i + 1] = p[at + B_F] * p[W] * (co * p[at + B_COS] - s * p[at + B_SIN])
    kink_at = int(p[KINK_AT])
    for k in range(int(p[NK])):
        at = kink_at + KINK_SIZE * k
        if mode & np.int64(p[at + K_BIT]):
            i = int(p[at + K_BODY])
            jac[2 * i + 1, 2 * i] -= p[at + K_K]
    stop_at = int(p[STOP_AT])
    for s_ in range(int(p[NS])):
        at = stop_at + STOP_SIZE * s_
        local = _local_mode(p, at, mode)
        if local == 0:
            continue
        sign, i, j = p[at + S_SIGN], int(p[at + S_I]), int(p[at + S_J])
        delta = y[2 * i]
        rate = y[2 * i + 1]
        if j >= 0:
            delta -= y[2 * j]
            rate -= y[2 * j + 1]
        c_at = at + S_COUPLING
        kc, cc = stops.stop_slopes(p, c_at, local, 2, sign * delta - p[c_at + stops.D],
                                   sign * rate)
        # F_C's slopes along x_i, v_i are sign * (kc, cc); the force on i is -sign F_C
        jac[2 * i + 1, 2 * i] -= kc
        jac[2 * i + 1, 2 * i + 1] -= cc
        if j >= 0:
            jac[2 * i + 1, 2 * j] += kc
            jac[2 * i + 1, 2 * j + 1] += cc
            jac[2 * j + 1, 2 * i] += kc
            jac[2 * j + 1, 2 * i + 1] += cc
            jac[2 * j + 1, 2 * j] -= kc
            jac[2 * j + 1, 2 * j + 1] -= cc
    for i in range(n):
        m = p[body_at + i * body_size + B_M]
        for j in range(2 * n):
            jac[2 * i + 1, j] /= m
        dfdt[2 * i + 1] /= m
    if p[NS] > 0:
        _stick(p, mode, dfdt, 1)
        for j in range(2 * n):  # each column of the Jacobian is stuck as a rate is
            _stick(p, mode, jac[:, j], 1)


# ---------------------------------------------------------------- the System


@dataclass(frozen=True)
class _Packer:
    model: ChainModel

    def __call__(self, values: Mapping[str, float]) -> np.ndarray:
        return self.model.pack(values)


@dataclass(frozen=True)
class _SurfaceBuilder:
    model: ChainModel

    def __call__(self, p: np.ndarray) -> Surfaces:
        return self.model.surfaces(p)


CATALOGUE_BOX = {"x": (-12.0, 12.0), "v": (-12.0, 12.0)}

_BUILT: dict[ChainModel, System] = {}


def chain_system(model: ChainModel) -> System:
    """The :class:`System` of a chain (one per structure, built once); a ValueError naming
    the first problem of the structure."""
    problems = model.problems()
    if problems:
        raise ValueError(problems[0])
    if model not in _BUILT:
        linear_laws = all(stops.LAWS[stop.law].code not in (stops.HUNT_CROSSLEY, stops.RIGID)
                          for stop in model.stops)
        _BUILT[model] = System(
            model="chain",
            bodies=model.bodies,
            description=f"chain of {model.bodies} forced oscillators with "
                        f"{len(model.kinks)} kinks and {len(model.stops)} stops",
            state_names=model.state_names(),
            parameters=model.parameters(),
            rhs=chain_rhs,
            jacobian=chain_jacobian,
            pack=_Packer(model),
            surfaces=_SurfaceBuilder(model),
            forcing_frequency_index=W,
            piecewise_linear=linear_laws and not model.powers,
            extra={"catalogue_box": CATALOGUE_BOX, "chain": model,
                   "rigid": bool(model.rigid)},
        )
    return _BUILT[model]


BODY_KEYS = ("m", "c", "k1", "k2", "F", "phi")  # per-body keys, besides k_xp


def chain_values(model: ChainModel, w: float, bodies: Mapping[str, object],
                 kinks: Sequence[Mapping[str, float]] = (),
                 stop_values: Sequence[Mapping[str, float]] = ()) -> dict[str, float]:
    """The parameter values of ``model`` by name (``System.pack`` reads them).

    bodies : per-body key (``m``, ``c``, ``k1``, ``k2``, ``F``, ``phi``, ``k_xp``) -> one
        number (every body) or a sequence of one per body; missing keys take the defaults.
    kinks : per kink ``{"x": position, "k": stiffness}``; stop_values : per stop ``d`` (or
        ``wall``), ``k_c``, ``c_c`` and its law keys. A ValueError names a list of the
        wrong length or a missing value.
    """
    values: dict[str, float] = {"w": float(w)}
    defaults = {p.name: p.default for p in model.parameters()}
    known = BODY_KEYS + tuple(f"k_x{p}" for p in model.powers)
    for key in bodies:
        if key not in known:
            raise ValueError(f"{key!r} is not a per-body key; keys: {', '.join(known)}")
    for key in known:
        given = bodies.get(key)
        if isinstance(given, Sequence) and not isinstance(given, str):
            if len(given) != model.bodies:
                raise ValueError(f"{key}: {len(given)} values for {model.bodies} bodies; give "
                                 "one number or one per body")
            per_body = [float(v) for v in given]
        elif given is None:
            per_body = [defaults[f"{key}.{i}"] for i in range(1, model.bodies + 1)]
        else:
            per_body = [float(given)] * model.bodies
        values.update({f"{key}.{i}": v for i, v in enumerate(per_body, 1)})
    for prefix, given_list, count in (("kink", kinks, len(model.kinks)),
                                      ("stop", stop_values, len(model.stops))):
        if len(given_list) != count:
            raise ValueError(f"{len(given_list)} {prefix} value tables for {count} {prefix}s")
        for k, given in enumerate(given_list, 1):
            for name, value in given.items():
                values[f"{prefix}.{k}.{name}"] = float(value)
    for name, default in defaults.items():
        if name not in values:
            if default is None:
                raise ValueError(f"{name} has no default: give it")
            values[name] = float(default)
    return values
