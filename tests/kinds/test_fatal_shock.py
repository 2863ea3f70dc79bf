"""The fatal_shock kind on one Duffing body (two attractors): along one direction the
boundary is found to 1e-3, checked by labelling the two bracketing starts independently;
info, plot and one-line errors."""

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main
from softimpact_cli.kinds.scene import parse_scene

BODY = """
[system]
model = "duffing"
bodies = 1
[analysis]
kind = "fatal_shock"
solution = "L1^1"
phases = 2
directions = 4
max_shock = 24.0
scan = 24
tol = 1e-3
"""


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    out = tmp_path_factory.mktemp("shock") / "shock.h5"
    path = out.with_suffix(".toml")
    path.write_text(BODY)
    run = CliRunner().invoke(main, ["sweep", str(path), "-o", str(out), "-q"])
    assert run.exit_code == 0, run.output
    return out


def label_direct(state, t0):
    states = [[float(x) for x in state]]
    text = ('[system]\nmodel = "duffing"\nbodies = 1\n[analysis]\nkind = "basins"\n'
            f'[initial_conditions]\nkind = "list"\nstates = {states}\nt0 = {t0!r}\n')
    ds = si.run(parse_scene(text, "<direct>"), workers=1, verify=False)
    names = dict(zip(ds["label_code"].values.tolist(), ds["label_name"].values.tolist(),
                     strict=True))
    return str(names[int(ds["label"].values.ravel()[0])])


def test_the_boundary_along_each_axis_is_found_to_1e_3(result):
    ds = si.open_result(result)
    directions = ds["direction"].values
    np.testing.assert_allclose(directions, [[1, 0], [0, 1], [-1, 0], [0, -1]], atol=1e-15)
    mag = ds["shock_magnitude"].values
    assert np.all(np.isfinite(mag))
    for k, i in np.ndindex(*mag.shape):
        y, t = ds["orbit_state"].values[k], float(ds["shock_time"].values[k])
        fatal = label_direct(y + mag[k, i] * directions[i], t)
        assert fatal != "L1^1" and fatal == str(ds["shock_destination"].values[k, i])
        assert label_direct(y + (mag[k, i] - 1e-3) * directions[i], t) == "L1^1"
    # the two phases are half a period apart: the body's symmetry x -> -x maps them
    np.testing.assert_allclose(mag[0], mag[1][[2, 3, 0, 1]], atol=2e-3)
    assert ds.attrs["mfs"] == pytest.approx(np.min(mag))


def test_info_and_plot(result, tmp_path):
    runner = CliRunner()
    info = runner.invoke(main, ["info", str(result)])
    assert info.exit_code == 0 and "minimal fatal shock of L1^1: " in info.output
    assert "(an upper bound; 2 phases x 4 directions" in info.output
    png = tmp_path / "s.png"
    run = runner.invoke(main, ["plot", "fatal_shock", str(result), "-o", str(png)])
    assert run.exit_code == 0, run.output
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize("body, message", [
    ('solution = "L1^1"', None),
    ("", "[analysis] solution: is required"),
    ("solution = 3", "[analysis] solution: must be a label name"),
    ('solution = "L7^1"', "[analysis] solution: 'L7^1' is not in the catalogue at this "
                          "point; one of 'L1^1', 'L1^2'"),
])
def test_the_solution_must_be_named_and_exist(tmp_path, body, message):
    if message is None:
        return
    scene = tmp_path / "s.toml"
    scene.write_text(BODY.replace('solution = "L1^1"\n', body + "\n"))
    run = CliRunner().invoke(main, ["sweep", str(scene), "-o", str(tmp_path / "x.h5")])
    assert run.exit_code == 2 and message in run.output
    assert len(run.output.strip().splitlines()) == 1
    assert not (tmp_path / "x.h5").exists()


def test_a_result_where_every_kick_survives_plots(tmp_path):
    """No kick up to max_shock is fatal (every magnitude inf): the plot
    draws the scan's reach instead of failing on the empty reductions."""
    path = tmp_path / "calm.toml"
    path.write_text(BODY.replace("max_shock = 24.0", "max_shock = 0.05")
                    .replace("scan = 24", "scan = 2"))
    out = tmp_path / "calm.h5"
    runner = CliRunner()
    run = runner.invoke(main, ["sweep", str(path), "-o", str(out), "-q"])
    assert run.exit_code == 0, run.output
    assert np.all(np.isinf(si.open_result(out)["shock_magnitude"].values))
    png = tmp_path / "calm.png"
    run = runner.invoke(main, ["plot", "fatal_shock", str(out), "-o", str(png)])
    assert run.exit_code == 0, run.output
    assert png.stat().st_size > 10_000
