"""Sweeps over model parameters (F, w, ...): each grid point is what a scene at that point
alone gives (its own catalogue, its own forcing period), labels named consistently."""

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main

BODY = """
[system]
model = "duffing"
bodies = 1
{system}
[analysis]
kind = "stability"
[grid]
{grid}
[initial_conditions]
kind = "random"
box = {{x = [-4, 4], v = [-4, 4]}}
n = 24
[catalogue]
grid = 4
random = 12
[verification]
enabled = false
"""

PAIR_MAP = """
[system]
model = "duffing"
{system}
[analysis]
kind = "map"
[grid]
{grid}
[initial_conditions]
kind = "random"
box = {{x1 = [-6, 6], v1 = [-6, 6], x2 = [-6, 6], v2 = [-6, 6]}}
n = 12
[catalogue]
grid = 4
random = 12
[verification]
enabled = false
"""


def names_of(ds, label):
    table = dict(zip(ds["label_code"].values.tolist(), ds["label_name"].values.tolist(),
                     strict=True))
    return [table[int(c)] for c in np.ravel(label)]


@pytest.mark.parametrize("axis, values", [("F", (0.3, 1.5)), ("w", (0.8, 1.3))])
def test_each_point_of_a_parameter_sweep_is_that_scene_alone(axis, values):
    """Swept in F (the catalogue changes: one attractor at F = 0.3, two at 1.5) or in w
    (the forcing period too), each point labels every sample as the scene at that value
    does, orbit period and classification time included."""
    grid = f"{axis} = [{values[0]}, {values[1]}]"
    ds = si.run(BODY.format(system="", grid=grid), workers=1)
    assert ds["label"].dims[0] == axis and ds.sizes[axis] == 2
    assert ds.attrs["grid_parameters"] == [axis]  # a list (analysis/attributes.py)
    for i, value in enumerate(values):
        alone = si.run(BODY.format(system=f"{axis} = {value}", grid=""), workers=1)
        point = ds.isel({axis: i})
        assert names_of(ds, point["label"].values) == names_of(alone, alone["label"].values)
        for var in ("period", "periods_used", "status"):
            np.testing.assert_array_equal(point[var].values.ravel(), alone[var].values.ravel())
    if axis == "F":  # the catalogue changes along F: both names, one code each
        assert {"L1^1", "L1^2"} <= set(ds["label_name"].values.tolist())


def test_a_map_over_F_predicts_with_each_points_attractors(tmp_path):
    """A map over (F, d): at each F the predicted and found counts are those of a map
    over d at that F alone (the d_crit of that F's attractors); info and plot read it."""
    ds = si.run(PAIR_MAP.format(system="", grid="F = [0.5, 1.0]\nd = [2.0, 6.0, 12.0]"),
                workers=1)
    assert ds["predicted_count"].dims[:2] == ("F", "d")
    for i, F in enumerate((0.5, 1.0)):
        alone = si.run(PAIR_MAP.format(system=f"F = {F}", grid="d = [2.0, 6.0, 12.0]"),
                       workers=1)
        for var in ("predicted_count", "found_count"):
            np.testing.assert_array_equal(ds[var].isel(F=i).values.ravel(),
                                          alone[var].values.ravel())
    assert ds["predicted_count"].isel(F=0).values.ravel().tolist() != \
        ds["predicted_count"].isel(F=1).values.ravel().tolist()
    out = tmp_path / "m.h5"
    ds.to_netcdf(out, engine="h5netcdf", invalid_netcdf=True)
    info = CliRunner().invoke(main, ["info", str(out)])
    assert info.exit_code == 0, info.output
    assert "  F=0.5, d=2, phi=0, k_c=8, c_c=10, t0=0: " in info.output
