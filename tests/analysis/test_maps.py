"""Two-parameter maps: predicted counts from d_crit, found counts from samples."""

import numpy as np

from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep

SCENE = """
[system]
model = "duffing"
[analysis]
kind = "map"
[grid]
d = [2.0, 9.0, 22.0]
phi = [0.0, "pi"]
[initial_conditions]
kind = "random"
box = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}
n = 40
seed = 1
[catalogue]
grid = 6
random = 30
"""


def test_map_counts(tmp_path):
    ds = run_sweep(parse_scene(SCENE, "map.toml"), tmp_path / "m.h5", workers=1)
    pred = ds["predicted_count"].squeeze(drop=True)
    free = ds["found_nonimpacting"].squeeze(drop=True)
    found = ds["found_count"].squeeze(drop=True)
    # a non-impacting solution can only be found where it is predicted to survive
    assert (free <= pred).all() and (free <= found).all()
    # d = 22 is above every critical distance: all four combinations predicted
    assert (pred.sel(d=22.0) == 4).all()
    # prediction = count of d_crit below d, from the stored curves
    dc = ds["d_crit"].sel(dcrit_phi=np.pi, method="nearest").values
    assert int(pred.sel(d=9.0, phi=np.pi, method="nearest")) == int((dc < 9.0).sum())
