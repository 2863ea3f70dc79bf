"""Error against run time: reruns at tightened settings."""

import json
import subprocess
import sys

import numpy as np
import xarray as xr

from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kinds.check import check_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.check import tightened

SWEEP = """
[system]
model = "duffing"
[coupling]
d = 10.5
phi = 5.28
[analysis]
kind = "stability"
[initial_conditions]
kind = "random"
box = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}
n = 50
[catalogue]
grid = 6
random = 30
[output]
path = "{out}"
"""


def test_tightened_settings():
    t = tightened(IntegratorSettings())
    assert t.rtol == 1e-10 and t.atol == 1e-12 and t.convergence_tol == 1e-7
    assert t.max_periods == 6000 and t.steps_per_period == 5760


def test_sweep_check_report():
    report = check_scene(parse_scene(SWEEP.replace("{out}", "x.h5"), "s.toml"), sample=12)
    assert report["sample"] == 12 and 0 <= report["changed"] <= 12
    assert report["changed_share"] == report["changed"] / 12
    assert sum(report["changes"].values()) == report["changed"]
    assert report["wall_s"] > 0 and report["tight_wall_s"] > 0


def test_dcrit_check_is_small():
    scene = parse_scene('[system]\nmodel = "duffing"\n[analysis]\nkind = "dcrit"\n'
                        '[grid]\nphi = [0.5, 2.0, 4.0]\n[catalogue]\ngrid = 6\nrandom = 30\n')
    report = check_scene(scene, sample=3)
    assert report["sample"] == 3 and report["max_change"] < 1e-8


def test_sweep_check_n_sets_the_verification_sample(tmp_path):
    """`sweep --check N` verifies the sweep on N trajectories; `info --json` shows it."""
    out = tmp_path / "c.h5"
    scene = tmp_path / "c.toml"
    scene.write_text(SWEEP.replace("{out}", str(out)))
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene),
                           "--check", "10", "-q", "--workers", "1"], capture_output=True,
                          text=True)
    assert proc.returncode == 0, proc.stderr
    with xr.open_dataset(out) as ds:
        assert ds.attrs["verify_sample"] == 10
        assert 0.0 <= ds.attrs["verify_share"] <= 1.0
        assert np.isfinite(ds.attrs["verify_check_wall_s"])
    info = json.loads(subprocess.run([sys.executable, "-m", "softimpact_cli", "info",
                                      str(out), "--json"], capture_output=True,
                                     text=True).stdout)
    assert info["verification"]["sample"] == 10 and "wall_s" in info


def test_check_after_a_sweep_compares_the_stored_labels(tmp_path):
    """A sweep's check judges the labels the sweep stored (recurrence cells depend on the
    order of a run): a label corrupted in the result is counted as changed."""
    from softimpact_cli.sweep import run_sweep

    out = tmp_path / "s.h5"
    scene = parse_scene(SWEEP.replace("{out}", str(out)), "s.toml")
    ds = run_sweep(scene, out, workers=1)
    clean = check_scene(scene, sample=50, result=ds)
    assert clean["changed"] == 0
    bad = ds.copy(deep=True)
    flat = bad["label"].values.reshape(-1)
    flat[:5] = -3  # "diverged" where the sweep found attractors
    report = check_scene(scene, sample=50, result=bad)
    assert report["changed"] == 5
    assert all(k.startswith("diverged -> ") for k in report["changes"])
    assert report["wall_s"] == float(ds.attrs["wall_s"])  # sample = all 50 trajectories


def test_fail_over_names_the_share_that_exceeds_it():
    from softimpact_cli.kinds.check import over_limit

    report = {"kind": "labels", "changed_share": 0.04, "changed": 2, "sample": 50}
    assert over_limit(report, None) is None and over_limit(report, 0.05) is None
    assert "label change share 0.04 > --fail-over 0.01" in over_limit(report, 0.01)
    assert "d_crit" in over_limit({"kind": "d_crit", "max_change": 1e-3}, 1e-6)


def test_check_fail_over_exits_1(monkeypatch, tmp_path):
    from click.testing import CliRunner

    from softimpact_cli import cli as check_module  # where the command calls check_scene
    from softimpact_cli.cli import main

    report = {"kind": "labels", "sample": 10, "changed": 3, "changed_share": 0.3,
              "changes": {"A -> B": 3}, "wall_s": 1.0, "tight_wall_s": 2.0, "wall_ratio": 2.0}
    monkeypatch.setattr(check_module, "check_scene", lambda *a, **k: report)
    scene = tmp_path / "s.toml"
    scene.write_text(SWEEP.replace("{out}", str(tmp_path / "x.h5")))
    failed = CliRunner().invoke(main, ["check", str(scene), "--fail-over", "0.1"])
    assert failed.exit_code == 1 and "--fail-over 0.1" in failed.output
    passed = CliRunner().invoke(main, ["check", str(scene), "--fail-over", "0.5"])
    assert passed.exit_code == 0, passed.output
