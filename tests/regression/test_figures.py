"""Every figure scene runs at quick resolution and obeys facts true at any resolution."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from softimpact_cli.analysis.labels import parse_label
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import load_scene, quick
from softimpact_cli.sweep import run_sweep

FIGURES = Path(__file__).parents[2] / "configs" / "figures"
BASIN_SCENES = sorted(p.name for p in FIGURES.glob("*.toml")
                      if load_scene(p).analysis.kind == "basins")
DCRIT_SCENES = sorted(p.name for p in FIGURES.glob("*.toml")
                      if load_scene(p).analysis.kind == "dcrit")


def tiny(scene):
    scene = quick(scene)
    ic = replace(scene.initial_conditions, resolution=(8, 8))
    return replace(scene, initial_conditions=ic)


@pytest.mark.parametrize("name", BASIN_SCENES)
def test_basin_scene_structure(name, tmp_path):
    scene = tiny(load_scene(FIGURES / name))
    ds = run_sweep(scene, tmp_path / "r.h5", workers=1)
    names = [str(n) for n in ds["label_name"].values]
    catalogue = ds.attrs["catalogue_names"]  # a list (analysis/attributes.py)
    assert names[: len(catalogue)] == catalogue
    for n in names:
        parse_label(n)  # every label is one of the study's names
    assert ds["label"].size == scene.grid.size * 64
    assert set(np.unique(ds["label"].values)) <= set(ds["label_code"].values)
    assert (ds["status"] >= 0).all()


def test_far_apart_every_combination_coexists(tmp_path):
    """Fig 6(a): d = 22 is above every Duffing critical distance at phi = 0: all four
    combinations appear, none impacting."""
    scene = load_scene(FIGURES / "fig06_duffing_basins.toml")
    grid = replace(scene.grid, axes={k: v[:1] for k, v in scene.grid.axes.items()})
    ic = replace(scene.initial_conditions, resolution=(16, 16))
    ds = run_sweep(replace(scene, grid=grid, initial_conditions=ic), tmp_path / "a.h5",
                   workers=1)
    found = {str(ds["label_name"].values[list(ds["label_code"].values).index(c)])
             for c in np.unique(ds["label"].values)}
    assert found == {"L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1", "L1^2 R1-0^2"}
    assert (ds["max_penetration"] < 0).all()


@pytest.mark.parametrize("name", DCRIT_SCENES)
def test_dcrit_scene_structure(name):
    scene = load_scene(FIGURES / name)
    phis = tuple(np.linspace(0.0, 2 * np.pi, 6, endpoint=False))
    scene = replace(scene, analysis=replace(scene.analysis, phis=phis))
    ds = run_scene(scene)
    assert ds["d_crit"].shape == (ds.sizes["combination"], 6)
    assert np.isfinite(ds["d_crit"].values).all()
    # |x1 - x2| <= |x1| + |x2| <= 2 max amplitude (amplitudes are sampled maxima, hence
    # the small relative slack; d_crit's maximum is located exactly)
    amp = float(ds["attractor_amplitude"].max()) * (1 + 1e-4)
    assert (ds["d_crit"].values <= 2 * amp).all()
    assert (ds["d_crit"].values >= -2 * amp).all()
