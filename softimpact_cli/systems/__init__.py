"""Registered systems. See :mod:`softimpact_cli.systems.base` for the contract.

To add a system, write a module that builds :class:`~.base.System` instances and add
them to ``REGISTRY`` below; nothing in the kernels changes.
"""

from __future__ import annotations

from ..kernels.numba_cache import source_keyed_cache, stabilise

with source_keyed_cache():  # every jitted module of the package, imported here
    from . import bilinear as _bilinear
    from . import chain as _chain
    from . import duffing as _duffing
    from . import stops as _stops
    from . import variational as _variational
from .base import COUPLING_PARAMETERS, Parameter, Surfaces, System, check_bodies
from .bilinear import BILINEAR_BODY, BILINEAR_PAIR
from .duffing import DUFFING_BODY, DUFFING_PAIR

for _module in (_bilinear, _chain, _duffing, _stops, _variational):
    stabilise(_module)

REGISTRY: dict[tuple[str, int], System] = {
    ("duffing", 1): DUFFING_BODY,
    ("duffing", 2): DUFFING_PAIR,
    ("bilinear", 1): BILINEAR_BODY,
    ("bilinear", 2): BILINEAR_PAIR,
}

for (_model, _bodies), _system in REGISTRY.items():  # a third body fails here, loudly
    check_bodies(_system.bodies, f"REGISTRY[{_model!r}, {_bodies}]")
    if (_system.model, _system.bodies) != (_model, _bodies):
        raise ValueError(f"REGISTRY[{_model!r}, {_bodies}] holds {_system.model!r} with "
                         f"{_system.bodies} bodies")

MODELS = tuple(sorted({model for model, _ in REGISTRY}))
# names of the stop laws a preset's [coupling] takes (systems/stops.py); the rigid law is a
# chain's [[stop]] only
LAWS = tuple(name for name, law in _stops.LAWS.items() if law.soft)
STOP_LAWS = _stops.LAWS  # {name: StopLaw}
# {[coupling] key: LawKey} of the keys only some of a preset's laws use
LAW_KEYS = {name: key for name, key in _stops.LAW_KEYS.items()
            if any(key in _stops.LAWS[law].keys for law in LAWS)}
STOP_KEYS = _stops.LAW_KEYS  # {[[stop]] key: LawKey}: a chain's, the rigid law's r too


def get_system(model: str, bodies: int) -> System:
    """The registered system for ``model`` with ``bodies`` bodies (1 or 2)."""
    try:
        return REGISTRY[(model, bodies)]
    except KeyError:
        raise KeyError(
            f"unknown system {model!r} with {bodies} bodies; valid models: {', '.join(MODELS)}, "
            "bodies 1 or 2"
        ) from None


__all__ = ["COUPLING_PARAMETERS", "LAWS", "LAW_KEYS", "MODELS", "REGISTRY", "STOP_KEYS",
           "STOP_LAWS",
           "Parameter", "Surfaces", "System", "get_system"]
