"""Kind "lyapunov" on a chain from its catalogue and along a [grid] axis by the chain's
names: the products' exponents are their bodies' Floquet exponents (no stop touches them),
and each grid value's spectrum is the one of the scene at that value."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store.catalogues import scene_catalogue

CHAIN = """\
[system]
model = "chain"
bodies = 2
k2 = 0.05
F = 1.5
w = 1.4
phi = [0.0, "pi"]

[[stop]]
between = [1, 2]
d = 20.0

[analysis]
kind = "lyapunov"
periods = 200
transient = 20
segments = 10
"""


def test_a_chains_catalogue_spectra_are_its_bodies_floquet_exponents(tmp_path):
    """Two Duffing bodies, each with two period-1 attractors, far apart (d = 20): the four
    products are solutions, each spectrum's section states stay on its product's orbit,
    and its exponents are the union of the bodies' Floquet exponents ln|mu| / T (to 3e-4:
    200 periods over complex multipliers), summing to -2c."""
    scene = parse_scene(CHAIN + 'start = "catalogue"\n[catalogue]\ngrid = 4\nrandom = 0\n'
                        'box = {x = [-4.0, 4.0], v = [-4.0, 4.0]}\n'
                        f'[output]\npath = "{tmp_path / "l.h5"}"\n', "s.toml")
    ds = run_scene(scene)
    names = [str(n) for n in ds["solution"].values]
    assert names == ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1", "L1^2 R1-0^2"]
    assert ds["exponent"].shape == (4, 4)
    diff = np.abs(ds["exponent"].values - ds["floquet_exponent"].values)
    assert np.all(diff < 3e-4), diff
    for k, product in enumerate(scene_catalogue(scene).products):
        assert product.name == names[k] and product.orbit.shape[0] == 1
        np.testing.assert_allclose(ds["section_state"].values[k],
                                   np.broadcast_to(product.orbit[0], (200, 4)), atol=1e-6)
    np.testing.assert_allclose(ds["exponent"].values.sum(axis=1), -0.1, atol=1e-8)


def test_a_chains_grid_axis_gives_the_spectrum_at_each_value(tmp_path):
    grid = CHAIN.replace("d = 20.0", "d = 2.0") + (
        'state = [1.0, 0.0, -1.0, 0.0]\nfollow = false\n[grid]\n"stop.1.d" = [1.5, 3.0]\n')
    ds = run_scene(parse_scene(grid + f'[output]\npath = "{tmp_path / "g.h5"}"\n', "g.toml"))
    assert ds.attrs["axis"] == "stop.1.d"
    np.testing.assert_array_equal(ds["stop.1.d"].values, [1.5, 3.0])
    for k, d in enumerate((1.5, 3.0)):
        one = CHAIN.replace("d = 20.0", f"d = {d}") + 'state = [1.0, 0.0, -1.0, 0.0]\n'
        alone = run_scene(parse_scene(one + f'[output]\npath = "{tmp_path / f"{k}.h5"}"\n'))
        np.testing.assert_array_equal(ds["exponent"].values[k], alone["exponent"].values[0])
    assert not np.array_equal(ds["exponent"].values[0], ds["exponent"].values[1])


def test_a_chains_grid_of_two_axes_is_refused_in_one_line():
    with pytest.raises(ConfigError) as err:
        parse_scene(CHAIN + 'state = [1.0, 0.0, -1.0, 0.0]\n[grid]\n"F.2" = [1.0, 2.0]\n'
                    'w = [1.2, 1.3]\n', "s.toml")
    assert "[grid]: lyapunov follows one parameter; give one axis (any of the chain's " \
           "parameters by name" in str(err.value) and "\n" not in str(err.value)
