"""The atlas kind end to end: bad scenes are one line naming the key and file (exit 2,
nothing written); a run writes curves that info --json lists and plot atlas draws (also
over a dcrit result); figure 7's folds lie on the fold curves of its (phi, d) scene."""

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact_cli.analysis.atlas_augmented import AugmentedMap
from softimpact_cli.analysis.continuation import correct
from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store.h5netcdf_ import open_result
from softimpact_cli.systems import get_system

ROOT = Path(__file__).resolve().parents[2]
SCENE = """
[system]
model = "duffing"
bodies = 1
F = 2.5

[analysis]
kind = "atlas"
{analysis}
step = 0.05
max_step = 0.3
max_points = 40
max_period = 1
slices = 0
switch_depth = 0

[catalogue]
grid = 8
random = 40

[output]
path = "{out}"
"""
DCRIT = """
[system]
model = "duffing"

[analysis]
kind = "dcrit"

[grid]
phi = {{ start = 1.9, stop = 2.0, num = 3 }}

[output]
path = "{out}"
"""
GOOD = 'parameters = ["w", "F"]\nranges = { w = [1.27, 1.33], F = [2.3, 2.8] }'


@pytest.mark.parametrize("analysis, message", [
    ('parameters = ["d", "F"]\nranges = { d = [0, 1], F = [2.3, 2.8] }',
     "[analysis] parameters: 'd' is not a parameter of the model (allowed: c, k1, k2, F, w"),
    ('parameters = ["F", "F"]\nranges = { F = [2.3, 2.8] }',
     "[analysis] parameters: the two parameters must differ"),
    ('parameters = ["w", "F"]\nranges = { w = [1.27, 1.33], F = [2.6, 2.8] }',
     "[analysis] ranges: the rectangle holds no catalogue orbit: the catalogue is searched "
     "at the scene's F = 2.5"),
    ('parameters = ["w", "F"]\nranges = { w = [1.27, 1.33] }',
     "[analysis] ranges: must give [low, high] for exactly w and F"),
    ('parameters = ["w", "F"]\nranges = { w = [1.33, 1.27], F = [2.3, 2.8] }',
     "[analysis] ranges: w must be [low, high] with low < high"),
])
def test_bad_scenes_are_one_line_naming_key_and_file(analysis, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(SCENE.format(analysis=analysis, out="r.h5"), "scene.toml")
    assert str(err.value).startswith("scene.toml: ")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_bad_scene_exits_2_with_one_line_and_writes_nothing(tmp_path):
    out = tmp_path / "bad.h5"
    scene = tmp_path / "bad.toml"
    scene.write_text(SCENE.format(analysis='parameters = ["w", "w"]\nranges = { w = [1, 2] }',
                                  out=out))
    result = CliRunner().invoke(main, ["sweep", str(scene)])
    assert result.exit_code == 2
    assert result.output.strip().count("\n") == 0 and "parameters" in result.output
    assert not out.exists()


def test_a_run_writes_a_fold_curve_that_info_and_plot_show(tmp_path):
    """The Duffing body's upper fold (F = 2.5655883 at w = 1.3) followed in (w, F): every
    point has a multiplier +1 (info --json), and the curve crosses w = 1.3 there."""
    out = tmp_path / "fold.h5"
    scene = tmp_path / "fold.toml"
    scene.write_text(SCENE.format(analysis=GOOD, out=out))
    runner = CliRunner()
    result = runner.invoke(main, ["sweep", str(scene)])
    assert result.exit_code == 0, result.output
    data = json.loads(runner.invoke(main, ["info", str(out), "--json"]).output)["atlas"]
    assert data["parameters"] == ["w", "F"]
    (curve,) = data["curves"]
    assert curve["kind"] == "fold" and curve["orbit"] == "L1^1"
    assert all(end.startswith("parameter bound") for end in curve["ends"])  # across
    for (w, _), mu in zip(curve["points"], curve["multipliers"], strict=True):
        mu = np.array([complex(*m) for m in mu])
        assert np.min(np.abs(mu - 1.0)) < 1e-7  # a fold
        assert np.prod(mu).real == pytest.approx(np.exp(-0.05 * 2 * np.pi / w), rel=1e-7)
    w, F = np.array(curve["points"]).T
    k = np.argsort(w)
    assert np.interp(1.3, w[k], F[k]) == pytest.approx(2.5655883, abs=1e-4)
    text = runner.invoke(main, ["info", str(out)]).output
    assert "fold            L1^1" in text
    png = tmp_path / "fold.png"
    plot = runner.invoke(main, ["plot", "atlas", str(out), "-o", str(png)])
    assert plot.exit_code == 0, plot.output
    assert png.stat().st_size > 10_000
    bad = runner.invoke(main, ["plot", "atlas", str(out), "--over", str(out), "-o",
                               str(png)])
    assert bad.exit_code == 2 and "--over" in bad.output and "'atlas' result" in bad.output
    dcrit = tmp_path / "dcrit.h5"
    (tmp_path / "dcrit.toml").write_text(DCRIT.format(out=dcrit))
    assert runner.invoke(main, ["sweep", str(tmp_path / "dcrit.toml")]).exit_code == 0
    bad = runner.invoke(main, ["plot", "atlas", str(out), "--over", str(dcrit), "-o",
                               str(png)])
    assert bad.exit_code == 2 and "the atlas is in (w, F), not (phi, d)" in bad.output


@pytest.mark.slow
def test_figure_7_folds_lie_on_the_fold_curves_of_its_phi_d_scene(tmp_path):
    """configs/atlas/fig07_folds_phi_d.toml (its band of phases narrowed around 5 pi/8):
    at phi = 5 pi/8 the fold curves pass through figure 7's folds d = 15.4916, 10.1972,
    7.8172 (Newton on the curve at fixed phi from its nearest points, to 1e-4: the
    figure's digits)."""
    out = tmp_path / "fig07.h5"
    scene = tmp_path / "fig07.toml"
    text = (ROOT / "configs/atlas/fig07_folds_phi_d.toml").read_text()
    # the scene's band of phases narrowed to the one the test reads (5 pi/8 = 1.9635):
    # the same curves through it, a quarter of their length
    narrow = text.replace("phi = [1.9, 2.03]", "phi = [1.955, 1.975]")
    assert narrow != text
    scene.write_text(narrow.replace("results/atlas_fig07_folds.h5", str(out)))
    result = CliRunner().invoke(main, ["sweep", str(scene)])
    assert result.exit_code == 0, result.output
    ds = open_result(out)
    phi = 5 * np.pi / 8
    pair = get_system("duffing", 2)
    values = {**pair.defaults(), "phi": phi, "k_c": 8.0, "c_c": 20.0, "d": 22.5}
    found = []
    for c in np.flatnonzero(ds["curve_kind"].values == "fold"):
        first, size = int(ds["curve_first"].values[c]), int(ds["curve_size"].values[c])
        pairs = ds["pair"].values[first:first + size]
        states = ds["state"].values[first:first + size]
        aug = AugmentedMap(pair, values, ("phi", "d"), int(ds["curve_periods"].values[c]),
                           "fold")
        for k in range(size - 1):
            if (pairs[k, 0] - phi) * (pairs[k + 1, 0] - phi) > 0:
                continue
            w = (phi - pairs[k, 0]) / (pairs[k + 1, 0] - pairs[k, 0])
            guess = np.concatenate([(1 - w) * states[k] + w * states[k + 1], [phi],
                                    [(1 - w) * pairs[k, 1] + w * pairs[k + 1, 1]]])
            u, value, _ = correct(aug, guess, np.eye(6)[4], 1e-9)
            found.append(u[-1])
            assert np.min(np.abs(np.linalg.eigvals(value.monodromy) - 1)) < 1e-7
    for d in (15.4916, 10.1972, 7.8172):
        assert min(abs(np.array(found) - d)) < 1e-4, (d, found)
    dcrit = tmp_path / "dcrit.h5"
    (tmp_path / "dcrit.toml").write_text(DCRIT.format(out=dcrit).replace(
        'model = "duffing"', 'model = "duffing"\n\n[coupling]\nk_c = 8.0\nc_c = 20.0'))
    runner = CliRunner()
    assert runner.invoke(main, ["sweep", str(tmp_path / "dcrit.toml")]).exit_code == 0
    png = tmp_path / "over.png"
    plot = runner.invoke(main, ["plot", "atlas", str(out), "--over", str(dcrit), "-o",
                                str(png)])
    assert plot.exit_code == 0, plot.output
    assert png.stat().st_size > 10_000
