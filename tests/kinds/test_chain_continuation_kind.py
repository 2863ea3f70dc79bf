"""kind = "continuation" on a chain: any parameter by its name, the non-impacting products
as catalogue starts, each stop's grazing named in info and drawn; bad keys refused in one
line (the numbers themselves: tests/analysis/test_chain_continuation.py)."""

from __future__ import annotations

import json

import pytest
import xarray as xr
from click.testing import CliRunner

from softimpact_cli import plot as si_plot
from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene

SCENE = """\
[system]
model = "chain"
bodies = 2
k2 = 0.01
F = [1.0, 0.5]
w = 1.3
phi = [0.0, 2.0]

[[stop]]
between = [1, 2]
d = 2.0
c_c = 2.0

[[stop]]
body = 2
wall = -1.2
side = "left"
c_c = 2.0

[analysis]
kind = "continuation"
parameter = "stop.1.d"
low = 1.85
high = 2.0
step = 0.05
max_step = 0.1
max_points = 8
switch_depth = 0

[catalogue]
grid = 3
random = 0
"""


PARAMETER = 'parameter = "stop.1.d"\nlow = 1.85\nhigh = 2.0'
BRANCHES = "switch_depth = 0"


@pytest.mark.parametrize("old, new, message", [
    (PARAMETER, 'parameter = "stop.3.d"\nlow = 1.0\nhigh = 2.0',
     "[analysis] parameter: must be one of 'w', 'm.1'"),
    (PARAMETER, 'parameter = "m.2"\nlow = -1.0\nhigh = 2.0',
     "[analysis] low: must be > 0 (a value of m.2), got -1.0"),
    (PARAMETER, 'parameter = "stop.1.d"\nlow = 1.85\nhigh = 1.9',
     "[analysis] low: the branch starts at the scene's stop.1.d = 2.0"),
    (BRANCHES, "branches = [1]", "[analysis] branches: must be a list of product names like "
                                 "'B1:P1^1 B2:P1-0^2 B3:P1-0^1', got [1]"),
])
def test_bad_keys_on_a_chain_are_one_line(old, new, message):
    text = SCENE.replace(old, new)
    with pytest.raises(ConfigError) as err:
        parse_scene(text, "s.toml")
    assert str(err.value).startswith("s.toml: ")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_product_no_search_finds_is_named_with_those_found(tmp_path):
    scene = parse_scene(SCENE.replace("switch_depth = 0", 'branches = ["L3^1 R1-0^1"]')
                        + f'[output]\npath = "{tmp_path / "x.h5"}"\n', "s.toml")
    with pytest.raises(ConfigError, match=r"branches: 'L3\^1 R1-0\^1' is not a product of "
                                          r"the chain's catalogue \(L1\^1 R1-0\^1, "):
        run_scene(scene)
    assert not (tmp_path / "x.h5").exists()


def test_a_chain_continuation_runs_and_info_and_plot_name_the_grazed_stop(tmp_path):
    out, png = tmp_path / "chain.h5", tmp_path / "chain.png"
    scene = tmp_path / "chain.toml"
    scene.write_text(SCENE + f'\n[output]\npath = "{out}"\n')
    runner = CliRunner()
    result = runner.invoke(main, ["sweep", str(scene)])
    assert result.exit_code == 0, result.output
    data = json.loads(runner.invoke(main, ["info", str(out), "--json"]).output)
    (event,) = data["continuation"]["bifurcations"]
    assert event["kind"] == "grazing" and event["stop"] == 1
    # the product's max of x1 - x2 (chain_dcrit's critical value; tested there)
    assert event["parameter"] == pytest.approx(1.8972862, abs=1e-6)
    # the catalogue's products no stop touches at d = 2 (not the large orbit's, L1^2 ...)
    assert data["continuation"]["starts"] == {"L1^1 R1-0^1": "traced"}
    text = runner.invoke(main, ["info", str(out)]).output
    assert "grazing stop 1   stop.1.d = 1.89728" in text
    plot = runner.invoke(main, ["plot", "continuation", str(out), "-o", str(png)])
    assert plot.exit_code == 0, plot.output
    assert png.stat().st_size > 10_000
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        fig = si_plot.continuation(ds.load())
    labels = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert labels.count("G1") == 2  # the grazed stop, beside its marker on both bodies' panels
