"""A bifurcation diagram along any parameter: a frequency response (w) of one body against
the closed-form linear response, and the keys' errors."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene

ROOT = Path(__file__).resolve().parents[2]
LINEAR = """
[system]
model = "duffing"
bodies = 1
k2 = 0.0
[analysis]
kind = "bifurcation"
parameter = "w"
start = 0.5
stop = 1.5
step = 0.1
[catalogue]
grid = 4
random = 8
[integrator]
convergence_tol = 1e-10
rtol = 1e-10
atol = 1e-12
"""


def test_frequency_response_of_a_linear_body_is_the_closed_form(tmp_path):
    """k2 = 0: the period-1 orbit is A sin(w t - delta), A = F / sqrt((k1 - w^2)^2 +
    (c w)^2). Its section point (x, v) at t = nT gives A = sqrt(x^2 + (v / w)^2); each
    step has its own forcing period 2 pi / w (a period kept from the scene's w = 1.3
    would put the section elsewhere and the amplitudes off by far more)."""
    ds = si.run(LINEAR, workers=1)
    w = ds["w"].values
    np.testing.assert_allclose(w, np.linspace(0.5, 1.5, 11), atol=1e-12)
    x = ds["section_x1"].isel(branch=0, point=0).values
    v = ds["section_v1"].isel(branch=0, point=0).values
    amplitude = np.hypot(x, v / w)
    exact = 1.0 / np.sqrt((1.0 - w**2) ** 2 + (0.05 * w) ** 2)
    np.testing.assert_allclose(amplitude, exact, rtol=1e-8)
    assert ds["period"].values.tolist() == [[1] * 11]
    assert ds["label"].values.tolist() == [[0] * 11]  # L1^1 all along, by continuity
    assert np.isnan(ds["destroyed_at"].values[0]) and ds.attrs["parameter"] == "w"
    out = tmp_path / "fr.h5"
    ds.to_netcdf(out, engine="h5netcdf", invalid_netcdf=True)
    info = CliRunner().invoke(main, ["info", str(out)])
    assert info.exit_code == 0 and "w                            0.5 -> 1.5 (11 steps)" in \
        info.output
    drawn = CliRunner().invoke(main, ["plot", "bifurcation", str(out), "-o",
                                      str(tmp_path / "fr.png")])
    assert drawn.exit_code == 0, drawn.output


def test_a_pair_follows_any_parameter_and_d_by_default():
    scene = parse_scene('[system]\nmodel = "duffing"\n[analysis]\nkind = "bifurcation"\n'
                        "parameter = \"F\"\nstart = 1.0\nstop = 0.8\nstep = 0.1\n", "b.toml")
    assert scene.analysis.parameter == "F"
    d = parse_scene('[system]\nmodel = "duffing"\n[analysis]\nkind = "bifurcation"\n'
                    "start = 10.0\nstop = 8.0\nstep = 1.0\n", "b.toml")
    assert d.analysis.parameter == "d"


@pytest.mark.parametrize("body, message", [
    ('parameter = "t0"', "[analysis] parameter: must be one of 'c', 'k1', 'k2', 'F', 'w', "
                         "got 't0'"),
    ('parameter = "w"\nstart = 0.0', "[analysis] start: must be > 0 (a value of w)"),
    ("", "[analysis] kind: bifurcation along d needs a pair ([system] bodies = 2); one body "
         "follows its solutions along parameter = one of c, k1, k2, F, w"),
])
def test_bad_parameter_keys_are_one_line(body, message):
    text = ('[system]\nmodel = "duffing"\nbodies = 1\n[analysis]\nkind = "bifurcation"\n'
            + (body + "\n" if body else "") + "start = 0.5\nstop = 1.5\nstep = 0.1\n")
    text = text.replace("start = 0.0\nstart = 0.5", "start = 0.0")
    with pytest.raises(ConfigError) as err:
        parse_scene(text, "b.toml")
    assert str(err.value).startswith(f"b.toml: {message}")


def test_cli_bad_parameter_exit_2(tmp_path):
    scene = tmp_path / "b.toml"
    scene.write_text(LINEAR.replace('parameter = "w"', 'parameter = "omega"'))
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene), "-o",
                           str(tmp_path / "b.h5")], capture_output=True, text=True)
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1
    assert "[analysis] parameter: must be one of" in proc.stderr
    assert not (tmp_path / "b.h5").exists()


def test_the_frequency_response_scene_finds_the_fold():
    """configs/frequency_response_duffing.toml: the large-amplitude orbit of the hardening
    Duffing body jumps to the small one past its fold (w between 1.50 and 1.52); the
    small one lives on to w = 2."""
    ds = si.run(si.load_scene(ROOT / "configs" / "frequency_response_duffing.toml"),
                workers=1)
    names = [str(n) for n in ds["branch_name"].values]
    assert names == ["L1^1", "L1^2"]
    small, large = (ds.isel(branch=i) for i in range(2))
    assert np.isnan(float(small["destroyed_at"])) and set(small["label"].values) == {0}
    assert float(large["destroyed_at"]) == pytest.approx(1.52)
    assert str(large["falls_to"].values) == "L1^1"
    w = ds["w"].values
    before = w < 1.51
    amplitude = np.hypot(large["section_x1"].isel(point=0), large["section_v1"].isel(point=0)
                         / w).values
    assert amplitude[before].min() > 10.0 and amplitude[~before].max() < 1.0


def test_continuation_follows_any_model_parameter_as_the_grid_does():
    """The continuation's parameters are the grid axes (config.axes), not a list of its
    own: continued in the damping c, a linear body's period-1 orbit at w = 0.9 has the
    closed-form amplitude at every point."""
    ds = si.run(LINEAR.replace('parameter = "w"\nstart = 0.5\nstop = 1.5\nstep = 0.1\n',
                               'parameter = "c"\nlow = 0.02\nhigh = 0.3\nstep = 0.02\n'
                               "max_step = 0.05\n")
                .replace('kind = "bifurcation"', 'kind = "continuation"')
                .replace("k2 = 0.0\n", "k2 = 0.0\nw = 0.9\n"), workers=1)
    c = ds["parameter"].values
    assert c.min() == pytest.approx(0.02) and c.max() == pytest.approx(0.3)
    x, v = ds["state"].values.T
    exact = 1.0 / np.sqrt((1.0 - 0.81) ** 2 + (c * 0.9) ** 2)
    np.testing.assert_allclose(np.hypot(x, v / 0.9), exact, rtol=1e-8)


PAIR_RANGE = ('[system]\nmodel = "duffing"\n[analysis]\nkind = "bifurcation"\n'
              "start = {start}\nstop = {stop}\nstep = {step}\n")
CHAIN_RANGE = ('[system]\nmodel = "chain"\nbodies = 2\n[[stop]]\nbetween = [1, 2]\nd = 5.0\n'
               '[analysis]\nkind = "bifurcation"\nparameter = "stop.1.d"\n'
               "start = {start}\nstop = {stop}\nstep = {step}\n")


@pytest.mark.parametrize("text", [PAIR_RANGE, CHAIN_RANGE], ids=["pair", "chain"])
@pytest.mark.parametrize("start, stop, step, message", [
    (8.0, 8.0, 1.0, "[analysis] stop: must differ from start"),
    (8.0, 9.0, 1e-6, "[analysis] step: 1000000 steps; at most"),
    (8.0, 9.0, -1.0, "[analysis] step: must be > 0"),
])
def test_a_bad_range_is_one_line_for_a_preset_and_a_chain(text, start, stop, step, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(text.format(start=start, stop=stop, step=step), "b.toml")
    assert str(err.value).startswith(f"b.toml: {message}") and "\n" not in str(err.value)
