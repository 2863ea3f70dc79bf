"""Scene variants and the run cache: a changed key gives a new scene text (and cache
file); the unchanged figure scene keeps its text."""

import tomllib

from softimpact_cli.reproduce.runs import ROOT, RUNS, Run, cache_path, with_key

SCENE = '[system]\nmodel = "duffing"\n\n[initial_conditions]\nkind = "plane"\nn = 3\n'


def test_with_key_replaces_inserts_or_appends():
    replaced = tomllib.loads(with_key(SCENE, "initial_conditions", "n", 5))
    assert replaced["initial_conditions"]["n"] == 5
    inserted = tomllib.loads(with_key(SCENE, "initial_conditions", "t0", "T/2"))
    assert inserted["initial_conditions"] == {"t0": "T/2", "kind": "plane", "n": 3}
    appended = tomllib.loads(with_key(SCENE, "integrator", "method", "rk4"))
    assert appended["integrator"] == {"method": "rk4"}
    table = tomllib.loads(with_key(SCENE, "grid", "phi", {"start": 0.0, "num": 4}))
    assert table["grid"]["phi"] == {"start": 0.0, "num": 4}


def test_a_variant_is_a_valid_scene_with_its_own_cache_file(tmp_path):
    base, half = RUNS["fig07_basins"], RUNS["fig07_basins_t0half"]
    assert base.scene().initial_conditions.t0 == 0.0
    period = 2 * 3.141592653589793 / 1.3
    assert abs(half.scene().initial_conditions.t0 - period / 2) < 1e-12
    assert cache_path(base.scene(), "x", tmp_path) != cache_path(half.scene(), "x", tmp_path)
    assert cache_path(base.scene(), "x", tmp_path) == cache_path(base.scene(), "x", tmp_path)
    assert base.text() == (ROOT / "configs/figures/fig07_duffing_basins.toml").read_text()


def test_quick_scene_is_smaller_and_cached_apart(tmp_path):
    run = Run("r", "figures/fig14cd_duffing_impacting.toml")
    full, small = run.scene(), run.scene(quick_run=True)
    assert max(small.initial_conditions.resolution) <= 24 < max(full.initial_conditions.resolution)
    assert cache_path(full, "r", tmp_path) != cache_path(small, "r", tmp_path)


def test_every_registered_run_parses():
    for run in RUNS.values():
        assert run.scene().analysis.kind
