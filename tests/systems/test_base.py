"""The systems contract (systems/base.py): what is registered, and a third body refused
loudly wherever the code is written for one body or a pair."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from softimpact_cli.systems import REGISTRY, get_system
from softimpact_cli.systems.base import SUPPORTED_BODIES, check_bodies


def test_every_registered_system_is_a_body_or_a_pair():
    assert SUPPORTED_BODIES == (1, 2)
    for (model, bodies), system in REGISTRY.items():
        assert (system.model, system.bodies) == (model, bodies)
        assert system.dim == 2 * bodies and len(system.state_names) == system.dim
        sf = system.surfaces(system.pack(system.defaults() | {"law": "paper"}))
        assert sf.A.shape[1] == system.dim
        assert sf.contact == (0 if bodies == 2 else -1)


def test_check_bodies_names_the_place_and_the_docstring():
    check_bodies(1, "here")
    check_bodies(2, "here")
    for bodies in (0, 3):
        with pytest.raises(NotImplementedError) as info:
            check_bodies(bodies, "label_orbit")
        message = str(info.value)
        assert message.startswith("label_orbit: written for 1 or 2 bodies, not ")
        assert "'Adding a body'" in message and "systems/base.py" in message


def three_body_system():
    """The Duffing pair relabelled as three bodies: only the body count is wrong."""
    pair = get_system("duffing", 2)
    return replace(pair, bodies=3, state_names=pair.state_names + ("x3", "v3"))


def test_pair_code_refuses_a_third_body():
    from softimpact_cli.analysis.catalogue import Catalogue, label_orbit
    from softimpact_cli.config import IntegratorSettings
    from softimpact_cli.config.sweep import read_grid
    from softimpact_cli.store.catalogues import build_catalogue

    system = three_body_system()
    with pytest.raises(NotImplementedError, match="^build_catalogue"):
        build_catalogue(system, system.defaults(), IntegratorSettings(), np.zeros((1, 2)))
    empty = Catalogue("duffing", {}, (), (), (), {}, 0)
    # labels name n bodies now (issue 32 item 4); an orbit that is not the catalogue's size
    # is refused by name
    with pytest.raises(ValueError, match="^label_orbit: an orbit of 6 state variables"):
        label_orbit(empty, np.zeros((1, 6)), impacting=False)
    with pytest.raises(NotImplementedError, match=r"^\[grid\]"):
        read_grid("s.toml", {}, {}, 3, 1.0, lambda axis, v: None)
