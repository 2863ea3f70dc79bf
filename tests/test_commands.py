"""The library functions behind the command line (``commands.py``), called directly: what
they write goes through a Console, the exit status is returned, bad input is refused
before anything is computed."""

import json

import pytest
import xarray as xr
from click.testing import CliRunner

from softimpact_cli import commands
from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.report.outcomes import STRICT_STATUS
from tests.report.test_outcomes import SCENE  # a basins sweep that resolves nothing


class Recorder:
    """A Console's streams kept as lists of lines."""

    def __init__(self):
        self.out, self.err, self.kept = [], [], []

    def console(self) -> commands.Console:
        return commands.Console(out=self.out.append, err=self.err.append,
                                keep=self.kept.append)


def test_sweep_scene_writes_through_its_console_and_returns_the_strict_status(tmp_path):
    out = tmp_path / "r.h5"
    scene = tmp_path / "r.toml"
    scene.write_text(SCENE.format(out=out))
    seen = Recorder()
    options = commands.SweepOptions(workers=1, quiet=True, strict=True)
    assert commands.sweep_scene(str(scene), options, seen.console()) == STRICT_STATUS == 3
    assert seen.out[0].startswith("basins: 9 trajectories (") and seen.out[0].endswith(
        f"-> {out}")
    assert seen.out[1].startswith("label error")
    assert any(line.startswith("softimpact: warning: 100.0% of trajectories unresolved (no "
                               "period within max_periods = 5)") for line in seen.err)
    assert len(seen.kept) == 1 and callable(seen.kept[0])  # what a Ctrl-C would keep
    with xr.open_dataset(out) as ds:  # written before the status
        assert ds.attrs["complete"] == 1

    again = Recorder()
    lenient = commands.SweepOptions(workers=1, quiet=True, overwrite=True)
    assert commands.sweep_scene(str(scene), lenient, again.console()) == 0
    assert again.err == seen.err  # the same warnings, no exit status

    # `info` prints what info_text returns
    printed = CliRunner().invoke(main, ["info", str(out)])
    assert printed.exit_code == 0 and printed.output == commands.info_text(str(out)) + "\n"
    assert json.loads(commands.info_text(str(out), as_json=True))["analysis"] == "basins"

    # `compare` prints what compare_files returns, and fails on the limits it names
    text, why = commands.compare_files(str(out), str(out), max_label_change=0.0)
    assert why == [] and text == CliRunner().invoke(main, ["compare", str(out), str(out)]
                                                    ).output.rstrip("\n")


def test_bad_options_are_refused_before_anything_runs(tmp_path):
    out = tmp_path / "r.h5"
    scene = tmp_path / "r.toml"
    scene.write_text(SCENE.format(out=out))
    seen = Recorder()
    with pytest.raises(ConfigError, match="--check 5 and --no-verify: choose one"):
        commands.sweep_scene(str(scene), commands.SweepOptions(check_n=5, no_verify=True),
                             seen.console())
    with pytest.raises(ConfigError, match='kind: must be "design" for this command, got '
                                          "'basins'"):
        commands.design_scene(str(scene), None, commands.RunOptions(), seen.console())
    assert not out.exists() and seen.out == seen.err == seen.kept == []


def test_dry_run_prints_the_plan_only(tmp_path):
    out = tmp_path / "r.h5"
    scene = tmp_path / "r.toml"
    scene.write_text(SCENE.format(out=out))
    seen = Recorder()
    options = commands.SweepOptions(dry_run=True, workers=1)
    assert commands.sweep_scene(str(scene), options, seen.console()) == 0
    cli = CliRunner().invoke(main, ["sweep", str(scene), "--dry-run", "--workers", "1"])
    assert cli.exit_code == 0 and cli.output == "\n".join(seen.out) + "\n"
    assert seen.out and not out.exists()
