"""The axes a scene can sweep, defined once.

Every sweep result has the dims :data:`GRID_AXES` (``d, phi, k_c, c_c, t0``; length 1 where
not swept), so results written before other axes existed keep their shape. Any other
parameter of the model (:func:`parameter_axes`: ``c, k1, k2, F, w``, ``d1`` of the
bilinear models, the stop law's ``exponent``) can be swept as well, and is then a dim of
its own, before those (``F, w, d, phi, ...``, in the model's parameter order).

A swept body parameter changes the one-body attractors, so the catalogue is searched per
distinct value of :func:`catalogue_axes` (and a label name means that point's attractor of
that number). A swept ``w`` changes the forcing period ``2 pi / w`` from point to point;
the section times and the RK4 step follow each point's period (``analysis.engine.Problem``
takes them from the point's parameters).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..systems import COUPLING_PARAMETERS, LAW_KEYS, MODELS, REGISTRY, System

# a pair's coupling (d, phi, k_c, c_c), a dim of every sweep result
COUPLING_AXES = tuple(p.name for p in COUPLING_PARAMETERS)
GRID_AXES = COUPLING_AXES + ("t0",)  # the dims every sweep result has, in this order
GRID_UNITS = {**{p.name: p.unit for p in COUPLING_PARAMETERS}, "t0": "1"}


def axis_units(axis: str) -> str:
    """The units of a grid axis (a model parameter's own; "1" is dimensionless)."""
    if axis in GRID_UNITS:
        return GRID_UNITS[axis]
    units = {p.name: p.unit for system in REGISTRY.values() for p in system.parameters}
    return units.get(axis, "1")


def is_chain(system: System) -> bool:
    """Whether ``system`` is a chain (``model = "chain"``): its parameters have the
    chain's names (``w``, ``F.2``, ``stop.1.d``...) and no pair's coupling."""
    return "chain" in system.extra


def parameter_axes(system: System) -> tuple[str, ...]:
    """The model parameters besides the coupling that can be grid axes: the body's (``c,
    k1, k2, F, w`` and ``d1`` for bilinear) and, for a pair, the stop laws' own keys
    (``exponent``), in the model's order. A chain: every parameter by its name."""
    if is_chain(system):
        return system.parameter_names
    names = tuple(p.name for p in system.parameters if p.name not in COUPLING_AXES)
    return names + (tuple(LAW_KEYS) if system.bodies == 2 else ())


def allowed_axes(system: System) -> tuple[str, ...]:
    """Every [grid] axis of a sweep of ``system``: its parameter axes, the coupling (a
    pair), and t0."""
    coupling = system.bodies == 2 and not is_chain(system)
    return parameter_axes(system) + (COUPLING_AXES if coupling else ()) + ("t0",)


def catalogue_axes(system: System) -> tuple[str, ...]:
    """The parameters a sweep's catalogue depends on: the body's (its one-body search)
    and, for a pair, phi (the right body's phase). Not d, k_c, c_c or the law's keys.
    A chain: every parameter but its stops' (``stop.s.*``)."""
    if is_chain(system):
        return tuple(a for a in system.parameter_names if not a.startswith("stop."))
    body = tuple(p.name for p in system.parameters if p.name not in COUPLING_AXES)
    return body + (("phi",) if system.bodies == 2 else ())


def catalogue_key(system: System, values: Mapping[str, Any]) -> tuple[float, ...]:
    """Which catalogue serves the parameter point ``values``: its values on
    :func:`catalogue_axes`."""
    return tuple(float(values[a]) for a in catalogue_axes(system))


def every_axis() -> tuple[str, ...]:
    """Every axis some sweep can span, over all models (for option choices and the
    README): the parameter axes of each model, then GRID_AXES."""
    names: dict[str, None] = {}
    for model in MODELS:
        names.update(dict.fromkeys(parameter_axes(REGISTRY[(model, 2)])))
    return tuple(names) + GRID_AXES
