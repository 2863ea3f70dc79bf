"""The continuation kind end to end: scene errors name the key and file, a run writes a
result whose info --json and figure hold the branches and bifurcations."""

import json
import threading
from pathlib import Path

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene

SCENE = """
[system]
model = "duffing"
bodies = 1
F = 1.0

[analysis]
kind = "continuation"
parameter = "F"
low = 0.2
high = 3.0
start = "state"
state = [-0.14, -1.9]
step = 0.05
max_step = 0.3
{extra}

[output]
path = "{out}"
"""


@pytest.mark.parametrize("extra, message", [
    ('parameter = "d"', "[analysis] parameter: must be one of 'c', 'k1', 'k2', 'F', 'w'"),
    ("low = 1.5", "[analysis] low: the branch starts at the scene's F = 1.0"),
    ("high = 0.1", "[analysis] high: must be > low"),
    ("min_step = 0.1", "[analysis] step: must lie in [min_step, max_step]"),
    ('branches = ["L1^1"]', "[analysis] branches: only with start = 'catalogue'"),
])
def test_bad_keys_are_one_line_naming_key_and_file(extra, message):
    text = SCENE.format(extra="", out="r.h5").replace('parameter = "F"\nlow = 0.2\n'
                                                        'high = 3.0\n', "")
    key = extra.split(" = ")[0]
    defaults = {"parameter": '"F"', "low": "0.2", "high": "3.0"}
    lines = [f"{k} = {v}" for k, v in defaults.items() if k != key] + [extra]
    text = text.replace('kind = "continuation"\n',
                        'kind = "continuation"\n' + "\n".join(lines) + "\n")
    with pytest.raises(ConfigError) as err:
        parse_scene(text, "scene.toml")
    assert str(err.value).startswith("scene.toml: ")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_run_writes_branches_and_folds_that_info_and_plot_show(tmp_path):
    out = tmp_path / "fold.h5"
    scene = tmp_path / "fold.toml"
    scene.write_text(SCENE.format(extra="max_points = 200", out=out))
    runner = CliRunner()
    result = runner.invoke(main, ["sweep", str(scene)])
    assert result.exit_code == 0, result.output
    info = runner.invoke(main, ["info", str(out), "--json"])
    data = json.loads(info.output)["continuation"]
    assert [e["kind"] for e in data["bifurcations"]] == ["fold", "fold"]
    assert sorted(e["parameter"] for e in data["bifurcations"]) == [
        pytest.approx(0.6188944, abs=1e-6), pytest.approx(2.5655883, abs=1e-6)]
    (branch,) = data["branches"]
    assert [r["stable"] for r in branch["stability"]] == [True, False, True]
    text = runner.invoke(main, ["info", str(out)]).output
    assert "fold             F = 2.56558" in text
    png = tmp_path / "fold.png"
    plot = runner.invoke(main, ["plot", "continuation", str(out), "-o", str(png)])
    assert plot.exit_code == 0, plot.output
    assert png.stat().st_size > 10_000


def test_no_start_converging_is_one_line_and_writes_nothing(tmp_path):
    out = tmp_path / "none.h5"
    scene = tmp_path / "none.toml"
    scene.write_text(SCENE.format(extra="tolerance = 1e-30", out=out))
    timers_before = {t for t in threading.enumerate() if t.name == "softimpact-progress"}
    result = CliRunner().invoke(main, ["sweep", str(scene)])
    assert result.exit_code == 2
    line = result.output.strip().splitlines()[-1]
    assert "[analysis] start: Newton shooting converged at no start" in line
    assert not out.exists()
    # its progress line (started for 1 branch, never reached) ends with the command: a
    # timer left running printed into a later test's captured stderr
    # (timers other tests left running are theirs to answer for)
    assert not [t for t in threading.enumerate()
                if t.name == "softimpact-progress" and t not in timers_before]


@pytest.mark.slow
def test_the_pitchfork_scene_reports_and_follows_its_two_branch_points(tmp_path):
    """configs/continuation/pitchfork_w.toml (the README's command): the symmetric orbit
    of the pair at phi = pi, d = 6 loses and regains stability in w through two branch
    points (no fold); the asymmetric pair switched onto at the first ends at the second.
    About 30 s of computing."""
    out = tmp_path / "pitchfork.h5"
    runner = CliRunner()
    scene = Path(__file__).parents[2] / "configs" / "continuation" / "pitchfork_w.toml"
    result = runner.invoke(main, ["sweep", str(scene), "-o", str(out)])
    assert result.exit_code == 0, result.output
    data = json.loads(runner.invoke(main, ["info", str(out), "--json"]).output)["continuation"]
    symmetric = "L1^1 R1-0^1"
    points = [e for e in data["bifurcations"] if e["kind"] == "branch point"]
    assert [e["branch"] for e in points] == [symmetric, symmetric]
    assert sorted(e["parameter"] for e in points) == [pytest.approx(1.0642063, abs=1e-6),
                                                       pytest.approx(1.1251762, abs=1e-6)]
    for e in points:
        assert min(abs(complex(*m) - 1.0) for m in e["multipliers"]) < 1e-8
    branches = {b["name"]: b for b in data["branches"]}
    assert sorted(branches) == [symmetric, f"{symmetric} BP1+", f"{symmetric} BP1-"]
    for side in "+-":
        b = branches[f"{symmetric} BP1{side}"]
        assert b["switched_from"] == symmetric
        assert b["ends"] == ["switched", f"meets {symmetric} at a branch point"]
        assert b["range"] == [pytest.approx(1.0642063, abs=1e-6), pytest.approx(1.18358,
                                                                                  abs=1e-4)]
        assert b["stability"][1] == {"stable": True, "from": pytest.approx(1.0642, abs=1e-3),
                                     "to": pytest.approx(1.0997, abs=1e-3)}
    text = runner.invoke(main, ["info", str(out)]).output
    assert f"branch point     w = 1.064206254 on {symmetric};" in text
    png = tmp_path / "pitchfork.png"
    plot = runner.invoke(main, ["plot", "continuation", str(out), "-o", str(png)])
    assert plot.exit_code == 0, plot.output
    assert png.stat().st_size > 10_000
