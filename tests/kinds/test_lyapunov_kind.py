"""[analysis] kind = "lyapunov": the scene, its errors (one line, exit 2), the API, a
grid run and the CLI's run, info and plot."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene

PAIR = """
[system]
model = "duffing"
[coupling]
d = 10.5
phi = 5.28
k_c = 8.0
c_c = 10.0
"""
IMPACTING = "[-9.7384, 0.5832, 1.3324, -1.7490]"


def scene(analysis: str, extra: str = "") -> str:
    return PAIR + "[analysis]\nkind = \"lyapunov\"\n" + analysis + extra


@pytest.mark.parametrize("analysis, extra, message", [
    ("", "", "[analysis] state: is required with start = 'state'"),
    (f"state = {IMPACTING}\nperiods = 100\nsegments = 7\n", "",
     "[analysis] segments: must divide periods (100) into equal segments, got 7"),
    ("state = [1.0, 2.0]\n", "", "[analysis] state: must be a list of 4 numbers"),
    (f"state = {IMPACTING}\nstart = \"orbit\"\n", "",
     "[analysis] start: must be one of 'state', 'catalogue'"),
    (f"start = \"catalogue\"\nstate = {IMPACTING}\n", "",
     "[analysis] state: not used with start = 'catalogue'"),
    (f"state = {IMPACTING}\nsaltation = 1\n", "", "[analysis] saltation: must be true or false"),
    (f"state = {IMPACTING}\n", "[grid]\nd = [9.0, 10.0]\nc_c = [2.0, 3.0]\n",
     "[grid]: lyapunov follows one parameter; give one axis"),
    ("start = \"catalogue\"\n", "[grid]\nd = [9.0, 10.0]\n",
     "[grid]: not used by kind 'lyapunov'"),
    (f"state = {IMPACTING}\nperiods = 1\n", "", "[analysis] periods: must be"),
])
def test_bad_scenes_fail_in_one_line(analysis, extra, message, tmp_path):
    text = scene(analysis, extra)
    with pytest.raises(ConfigError) as info:
        parse_scene(text, "s.toml")
    assert message in str(info.value) and "\n" not in str(info.value)
    path = tmp_path / "s.toml"
    path.write_text(text)
    out = CliRunner().invoke(main, ["sweep", str(path), "-o", str(tmp_path / "o.h5")])
    assert out.exit_code == 2 and out.output.count("\n") == 1 and message in out.output
    assert not (tmp_path / "o.h5").exists()


def test_api_trajectory_and_saltation_switch():
    """The impacting period-1 orbit of figure 14(c) through the API: with saltation the
    largest exponent is the orbit's -0.044, without it a spurious +0.079."""
    with_s = si.run(scene(f"state = {IMPACTING}\ntransient = 20\nperiods = 100\n"))
    assert with_s.attrs["analysis"] == "lyapunov" and with_s.sizes["order"] == 4
    lam = with_s["exponent"].values[0]
    assert -0.05 < lam[0] < -0.038 and np.all(np.diff(lam) <= 0)
    assert with_s["switches"].values[0] == 2 * 120
    without = si.run(scene(f"state = {IMPACTING}\ntransient = 20\nperiods = 100\n"
                           "saltation = false\n"))
    assert without["exponent"].values[0, 0] > 0.05
    assert without.attrs["saltation"] == 0


def test_grid_run_info_and_plot(tmp_path):
    """Along c_c (each value from the last end state): one spectrum per value, the
    parameter as coordinate, info's table and a two-panel figure."""
    path = tmp_path / "g.toml"
    path.write_text(scene(f"state = {IMPACTING}\ntransient = 10\nperiods = 40\nsegments = 4\n",
                          "[grid]\nc_c = [10.0, 8.0, 6.0]\n"))
    out = tmp_path / "g.h5"
    run = CliRunner().invoke(main, ["sweep", str(path), "-o", str(out), "-q"])
    assert run.exit_code == 0, run.output
    ds = si.open_result(out)
    assert ds.attrs["source"] == "grid" and list(ds["c_c"].values) == [10.0, 8.0, 6.0]
    # the strongly damped direction follows the stop's damping: about -(c_c) x contact share
    assert np.all(np.diff(ds["exponent"].values[:, 3]) > 0.1)
    info = CliRunner().invoke(main, ["info", str(out)])
    assert info.exit_code == 0 and "c_c = 8" in info.output and "+-" in info.output
    summary = json.loads(CliRunner().invoke(main, ["info", str(out), "--json"]).output)
    assert len(summary["spectra"]) == 3
    figure = tmp_path / "g.png"
    drawn = CliRunner().invoke(main, ["plot", "lyapunov", str(out), "-o", str(figure)])
    assert drawn.exit_code == 0, drawn.output
    fig = si.plot.lyapunov(ds)
    assert len(fig.axes) == 2
