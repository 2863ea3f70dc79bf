"""The sweep plan's size estimate and resource checks (issue 20, items 2 and 19)."""

import shutil
from collections import namedtuple

import numpy as np
import pytest
import xarray as xr

from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep
from softimpact_cli.sweep.chunks import RESULT_FIELDS
from softimpact_cli.sweep.plan import BYTES_PER_IC, Plan

SCENE = """
[system]
model = "duffing"
bodies = 1
[integrator]
max_periods = 300
[analysis]
kind = "{kind}"
[grid]
t0 = [0.0, "T/2"]
[initial_conditions]
{ic}
[catalogue]
grid = 3
random = 0
"""
PLANE = ('kind = "plane"\naxes = ["x", "v"]\nranges = [[-3.0, 3.0], [-3.0, 3.0]]\n'
         'resolution = [3, 4]')
RANDOM = 'kind = "random"\nn = 5\nbox = {x = [-3.0, 3.0], v = [-3.0, 3.0]}'


def test_bytes_per_trajectory_counts_every_result_field():
    assert BYTES_PER_IC == sum(np.dtype(t).itemsize for t in RESULT_FIELDS.values())


@pytest.mark.parametrize("ic", [PLANE, RANDOM], ids=["plane", "random"])
def test_estimate_bounds_every_stored_variable(ic, tmp_path):
    scene = parse_scene(SCENE.format(kind="basins", ic=ic), "p.toml")
    plan = Plan(scene, 7)
    out = tmp_path / "r.h5"
    run_sweep(scene, out, workers=1, chunk_size=7)
    with xr.open_dataset(out) as ds:
        stored = sum(v.nbytes for v in ds.variables.values())
    assert stored <= plan.result_bytes
    assert out.stat().st_size <= plan.result_bytes
    assert "result at most" in plan.describe()


def test_disk_check_names_the_path_and_the_free_space(tmp_path, monkeypatch):
    scene = parse_scene(SCENE.format(kind="basins", ic=PLANE), "p.toml")
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(100, 100, 0))
    with pytest.raises(ConfigError) as info:
        Plan(scene, 7).check_resources(tmp_path / "sub" / "r.h5", "p.toml")
    msg = str(info.value)
    assert msg.startswith(f"{tmp_path / 'sub' / 'r.h5'}: not enough disk space: the result "
                          "needs at most ") and f"{tmp_path} has 0.0 B free" in msg, msg
