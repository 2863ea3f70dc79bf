"""The contract every system fulfils, and the data it hands to the kernels.

A system is data plus two small jitted functions. The kernels know nothing else of it:

1. ``state_names``: names of the state variables, in kernel order (``x1, v1, x2, v2``
   for a pair, ``x, v`` for one body). The dimension is ``len(state_names)``.
2. ``parameters``: every parameter with unit, default and allowed range. Values reach
   the kernels as one float64 array built by ``pack`` (so one compilation serves every
   parameter value of a sweep).
3. ``rhs(t, y, p, mode, out)``: the right-hand side in a given contact *mode*, written
   into ``out``. ``mode`` is a bit mask: bit ``i`` is set when switching surface ``i`` is
   on its engaged side (``g_i >= 0``). Within a mode the vector field is smooth.
4. ``jacobian(t, y, p, mode, jac, dfdt)``: exact Jacobian ``d rhs / d y`` (shape
   ``(dim, dim)``) and the explicit time derivative ``d rhs / d t`` (shape ``(dim,)``)
   in a given mode, for the implicit integrators.
5. ``surfaces(p)``: the switching surfaces, each affine in the state,
   ``g_i(y) = A[i] @ y + b[i]``. Affine surfaces make ``g`` along a step's dense output
   a polynomial, so crossings and grazing extrema are located exactly and cheaply.
   A surface may be *relevant* only while another is engaged (the no-tension force
   surface only matters in contact); ``relevance[mode]`` is the mask of surfaces the
   kernel watches in that mode. ``contacts`` is the bit mask of the surfaces whose
   engaged side is a stop in contact (between bodies or with a wall; ``0`` for none):
   contact onsets and the maximum penetration are counted over them.

Adding a restoring force means one module that builds a :class:`System` per body count
(as ``duffing.py`` and ``bilinear.py`` do: a body block of parameters, the stop law's
coupling block from ``stops.py``) and its lines in ``REGISTRY`` (``systems/__init__.py``)
and in ``variational.py``'s ``_KERNELS``. Adding a stop law is ``stops.py`` alone (its
docstring says how). Nothing in the kernels changes for either.

Adding a body: any number of bodies is the chain family (``chain.py``: bodies, kinks and
stops as data, one compiled rhs for every member; ``[system] model = "chain"``). The
presets keep their body counts (``SUPPORTED_BODIES``, :func:`check_bodies`, called at
registration and where the code branches on a preset's body count). Where a chain stands:

1. kernels and ``Surfaces``: done. Several contact surfaces (``contacts``, a bit mask);
   onsets and the maximum penetration are counted over all of them (one running maximum,
   not one per stop).
2. ``config``: done for the scene form (``config/chain_scene.py``); a chain's [grid] axes
   are its parameters by name (``config/axes.py`` ``is_chain``; ``stop.1.d``, ``phi.3``:
   ``config/sweep.py`` ``flat_grid``, ``read_parameter_axis`` for dcrit and bifurcation).
3. Kinds (``kinds/scene.py`` ``CHAIN_KINDS``): trajectory, lyapunov (from a state), dcrit
   per stop (``analysis/chain_dcrit.py``), bifurcation along any parameter
   (``analysis/chain_bifurcation.py``), catalogue (``analysis/chain_catalogue.py``: each
   body's attractors, their products named with the n-body names, each stop's critical
   values deciding which survive), and the sweeps basins, stability, map, tipping,
   fractality and fatal_shock, labelled by that catalogue (``sweep/runner.py``
   ``chain_catalogues``; [grid] axes by the chain's parameter names) run on a chain;
4. design, continuation and atlas refuse it in one line when the scene is read: they
   follow the pair's one stop ``x1 - x2 - d``, as the capture of known orbits in
   ``sweep/runner.py`` does (off on a chain).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Parameter:
    """One scalar model parameter.

    ``minimum`` is the smallest allowed value; ``strict`` excludes it (``w > 0``).
    """

    name: str
    unit: str
    default: float | None
    description: str
    minimum: float = -np.inf
    strict: bool = False

    def check(self, value: float) -> str | None:
        """Return what is wrong with ``value``, or None when it is allowed."""
        if not np.isfinite(value):
            return "must be a finite number"
        if self.strict and value <= self.minimum:
            return f"must be > {self.minimum:g}"
        if value < self.minimum:
            return f"must be >= {self.minimum:g}"
        return None


@dataclass(frozen=True)
class Surfaces:
    """Affine switching surfaces ``g = A @ y + b`` of one parameter point.

    A : (n_surfaces, dim) float64
    b : (n_surfaces,) float64
    relevance : (2**n_surfaces,) int64, mask of watched surfaces per mode
    contacts : bit mask of the contact surfaces (bit i: surface i's engaged side is a stop
        in contact; 0 for none): the kernels count contact onsets and the maximum
        penetration over them
    names : one short name per surface
    """

    A: np.ndarray
    b: np.ndarray
    relevance: np.ndarray
    contacts: int
    names: tuple[str, ...]

    @property
    def contact(self) -> int:
        """Index of the first contact surface, or -1 when there is none."""
        return set_bits(self.contacts)[0] if self.contacts else -1

    @property
    def contact_indices(self) -> tuple[int, ...]:
        """Indices of the contact surfaces, in order."""
        return set_bits(self.contacts)


def set_bits(mask: int) -> tuple[int, ...]:
    """The set bits of ``mask``, lowest first."""
    return tuple(i for i in range(int(mask).bit_length()) if (mask >> i) & 1)


MAX_SURFACES = 16  # relevance holds 2**n_surfaces modes: 65536 entries at most


def relevance_table(n_surfaces: int, requires: Mapping[int, int]) -> np.ndarray:
    """Mask of watched surfaces per mode.

    ``requires[i] = j`` means surface ``i`` is watched only while surface ``j`` is engaged.
    The table has ``2**n_surfaces`` entries: beyond ``MAX_SURFACES`` a ValueError.
    """
    if n_surfaces > MAX_SURFACES:
        raise ValueError(f"{n_surfaces} switching surfaces (stops, kinks and the laws' "
                         f"surfaces): at most {MAX_SURFACES} are allowed")


    table = np.zeros(2**n_surfaces, dtype=np.int64)
    for mode in range(2**n_surfaces):
        mask = 0
        for i in range(n_surfaces):
            j = requires.get(i, -1)
            if j < 0 or mode & (1 << j):
                mask |= 1 << i
        table[mode] = mask
    return table


SUPPORTED_BODIES = (1, 2)  # what config, catalogues, labels, sweeps and cells are written for


def check_bodies(bodies: int, where: str) -> None:
    """Raise NotImplementedError unless ``bodies`` is 1 or 2: ``where`` names the code that
    is written for one body or a pair (see "Adding a body" in this module's docstring)."""
    if bodies not in SUPPORTED_BODIES:
        raise NotImplementedError(
            f"{where}: written for 1 or 2 bodies, not {bodies}; see 'Adding a body' in "
            "softimpact_cli/systems/base.py")


@dataclass(frozen=True)
class System:
    """A registered model: see the module docstring for the contract."""

    model: str
    bodies: int
    description: str
    state_names: tuple[str, ...]
    parameters: tuple[Parameter, ...]
    rhs: Callable
    jacobian: Callable
    pack: Callable[[Mapping[str, float]], np.ndarray]
    surfaces: Callable[[np.ndarray], Surfaces]
    forcing_frequency_index: int = 4
    # affine in the state in every mode for the linear stop laws (method 'exact' can
    # integrate it; systems/piecewise_linear.py checks each mode)
    piecewise_linear: bool = False
    variational: bool = False  # the state and its fundamental matrix (variational.py)
    # For a pair: the right body's solutions are right_sign * x_left(t + (phi - right_phase)/w)
    # (a time shift for identical bodies; a mirror and a half-period shift for mirrored ones).
    extra: Mapping[str, object] = field(default_factory=dict)

    @property
    def dim(self) -> int:
        return len(self.state_names)

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.parameters)

    def defaults(self) -> dict[str, float]:
        return {p.name: p.default for p in self.parameters if p.default is not None}

    def period(self, packed: np.ndarray) -> float:
        """Forcing period ``T = 2 pi / w`` (dimensionless time)."""
        return forcing_period_of(packed[self.forcing_frequency_index])


def forcing_period_of(w: float) -> float:
    """The forcing period ``T = 2 pi / w`` (dimensionless time): the one place it is
    computed (``System.period``, ``config.forcing_period`` of a scene's values)."""
    return 2.0 * np.pi / float(w)


# Coupling parameters shared by every pair (SPEC.md section 2).
COUPLING_PARAMETERS = (
    Parameter("d", "1", 6.0, "rest distance (gap) between the bodies", minimum=-np.inf),
    Parameter("phi", "rad", 0.0, "phase shift of the right body's forcing"),
    Parameter("k_c", "1", 8.0, "stiffness of the soft stop", minimum=0.0),
    Parameter("c_c", "1", 10.0, "damping of the soft stop", minimum=0.0),
)


def pack_parameters(parameters: tuple[Parameter, ...], values: Mapping[str, float]
                    ) -> np.ndarray:
    """Body parameters in declaration order, as float64."""
    return np.array([float(values[p.name]) for p in parameters])
