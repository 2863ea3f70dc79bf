"""A trajectory's result size is estimated before it is computed (issue 31, item 10): the
estimate bounds what is stored, --dry-run shows it, and a disk too full for it is said in
one line before any integration (on eab4deb a 15 MB trajectory computed 11.8 s, then
failed on the full disk)."""

import importlib
import os
import shutil
from collections import namedtuple

from click.testing import CliRunner

from softimpact_cli import api
from softimpact_cli.cli import main
from softimpact_cli.kinds import get as kind_of
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store import write_result

SCENE = """
[system]
model = "duffing"
[coupling]
d = 3.0
phi = "pi"
[analysis]
kind = "trajectory"
state = [3.0, 0.0, -3.0, 0.0]
periods = {periods}
samples_per_period = 32
t0 = "T/3"
"""


def test_the_estimate_bounds_every_stored_variable(tmp_path):
    scene = parse_scene(SCENE.format(periods=20), "t.toml")
    estimate = kind_of("trajectory").result_bytes(scene)
    ds = api.run(scene)
    out = write_result(ds, tmp_path / "t.h5")
    stored = sum(v.nbytes for v in ds.variables.values())
    assert stored <= estimate and out.stat().st_size <= estimate
    # the part that grows with the run is counted, not left to the fixed overhead
    longer = parse_scene(SCENE.format(periods=2000), "t.toml")
    grown = kind_of("trajectory").result_bytes(longer) - estimate
    assert grown >= 8 * (2000 - 20) * 32 * (1 + 4)  # time and 4 states per sample


def test_dry_run_shows_the_size(tmp_path):
    scene = tmp_path / "t.toml"
    scene.write_text(SCENE.format(periods=100_000))
    result = CliRunner().invoke(main, ["sweep", str(scene), "-o", str(tmp_path / "t.h5"),
                                       "--dry-run"])
    assert result.exit_code == 0, result.output
    assert "samples per period; result at most 128.4 MiB" in result.output, result.output
    assert not (tmp_path / "t.h5").exists()


def test_too_little_disk_space_is_refused_before_computing(tmp_path, monkeypatch):
    scene = tmp_path / "t.toml"
    scene.write_text(SCENE.format(periods=100_000))
    out = tmp_path / "t.h5"
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(1 << 30, 1 << 30, 1 << 20))

    def computed(*args, **kwargs):
        raise AssertionError("the trajectory was computed")

    # the module itself (softimpact_cli.kinds is also the API's function of that name)
    monkeypatch.setattr(importlib.import_module("softimpact_cli.kinds.run"), "run_scene",
                        computed)
    result = CliRunner().invoke(main, ["sweep", str(scene), "-o", str(out)])
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert lines[-1] == (f"softimpact: error: {out}: not enough disk space: the result "
                         f"needs at most 128.4 MiB, and the file system of {tmp_path} has "
                         "1.0 MiB free"), result.output
    assert sorted(os.listdir(tmp_path)) == ["t.toml"]
