"""The fractality result: ``softimpact measure`` (and ``si.measure``) on a basins result,
``info`` and ``plot fractality`` on what it writes, one-line errors, the scene kind."""

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main
from softimpact_cli.store import write_result
from tests.analysis.test_wada import sectors
from tests.naive import newton_basins

SIDE = 64


def basins_dataset(analysis: str = "basins") -> xr.Dataset:
    """A basins result of two panels as a sweep writes it: Newton's basins (Wada) and
    three sectors (not Wada) on the plane (x1, x2)."""
    label = np.stack([newton_basins(SIDE), sectors(SIDE)]).astype(np.int32)
    label = np.where(label == 2, 1000 + 1, label)  # a code as impacting P1 has
    axis = np.linspace(-2.0, 2.0, SIDE)
    return xr.Dataset(
        {"label": (("panel", "x1", "x2"), label),
         "label_code": (("label_index",), np.array([0, 1, 1001], dtype=np.int32)),
         "label_name": (("label_index",), np.array(["L1^1 R1-0^1", "L1^2 R1-0^1",
                                                    "impacting P1"]))},
        coords={"panel": np.arange(2), "x1": axis, "x2": axis,
                "d": ("panel", [6.0, 9.0]), "phi": ("panel", [0.0, np.pi]),
                "k_c": ("panel", [8.0, 8.0]), "c_c": ("panel", [10.0, 10.0]),
                "t0": ("panel", [0.0, 0.0])},
        attrs={"analysis": analysis, "ic_kind": "plane", "ic_dims": "x1 x2",
               "grid_dims": "panel", "complete": 1, "model": "duffing", "bodies": 2,
               "scene_text": "# made by hand\n", "forcing_period": 4.8,
               "parameters": "c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3", "n": 2 * SIDE**2})


@pytest.fixture
def basins_file(tmp_path):
    return write_result(basins_dataset(), tmp_path / "basins.h5")


def test_measure_finds_the_wada_panel_and_writes_a_result_info_and_plot_read(basins_file,
                                                                           tmp_path):
    out = tmp_path / "fractality.h5"
    ds = si.measure(basins_file, out)
    assert list(ds["verdict"].values) == ["Wada", "not Wada"]
    assert list(ds["n_basins"].values) == [3, 3]
    assert ds.attrs["analysis"] == "fractality" and ds.attrs["source_result"] == str(
        basins_file)
    back = si.open_result(out)
    np.testing.assert_allclose(back["S_b"].values, ds["S_b"].values)
    np.testing.assert_array_equal(back["wada_map"].values, ds["wada_map"].values)
    assert back["d"].values.tolist() == [6.0, 9.0]
    runner = CliRunner()
    info = runner.invoke(main, ["info", str(out)])
    assert info.exit_code == 0, info.output
    assert "Wada: Wada at r = " in info.output and "Wada: not Wada;" in info.output
    assert "d=6, phi=0" in info.output and "alpha" in info.output
    as_json = runner.invoke(main, ["info", str(out), "--json"])
    assert '"fractality"' in as_json.output and '"wada": "Wada"' in as_json.output
    png = tmp_path / "fractality.png"
    plot = runner.invoke(main, ["plot", "fractality", str(out), "-o", str(png),
                                "--max-panels", "1"])
    assert plot.exit_code == 0, plot.output
    assert png.stat().st_size > 10_000
    fig = si.plot.fractality(back)
    assert len(fig.axes) == 6 + 2  # three panels per plane and a colour bar each


def test_the_measure_command_prints_the_table(basins_file, tmp_path):
    out = tmp_path / "m.h5"
    result = CliRunner().invoke(main, ["measure", str(basins_file), "-o", str(out),
                                       "--box-sizes", "2,4,8", "--radii", "1,2,4,8"])
    assert result.exit_code == 0, result.output
    assert "S_bb n=2:" in result.output and result.output.endswith(f"fractality -> {out}\n")
    assert si.open_result(out)["box_size"].values.tolist() == [2, 4, 8]


@pytest.mark.parametrize("make, args, message", [
    (None, [], "missing.h5: no such result file"),
    ("stability", [], "holds a 'stability' result; fractality measures a basins result"),
    ("basins", ["--box-sizes", "2,65"], "box size: a whole number of cells in 2..64"),
    ("basins", ["--radii", "40"], "radii: whole numbers of cells >= 1 with 2 r + 1 <= 64"),
])
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, make, args, message):
    source = tmp_path / "missing.h5"
    if make:
        source = write_result(basins_dataset(make), tmp_path / "source.h5")
    out = tmp_path / "out.h5"
    result = CliRunner().invoke(main, ["measure", str(source), "-o", str(out), *args])
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("softimpact: error: ")
    assert message in lines[0] and str(source) in lines[0]
    assert not out.exists() and not list(tmp_path.glob("out.h5*"))


def test_an_existing_result_needs_overwrite(basins_file, tmp_path):
    out = tmp_path / "out.h5"
    out.write_bytes(b"keep me")
    result = CliRunner().invoke(main, ["measure", str(basins_file), "-o", str(out)])
    assert result.exit_code == 2 and "--overwrite" in result.output
    assert out.read_bytes() == b"keep me"
    again = CliRunner().invoke(main, ["measure", str(basins_file), "-o", str(out),
                                      "--overwrite"])
    assert again.exit_code == 0, again.output


def test_a_plane_too_small_or_not_a_plane_is_refused():
    ds = basins_dataset()
    with pytest.raises(si.ConfigError, match="result: a basins result over 'random'"):
        si.measure(ds.assign_attrs(ic_kind="random"))
    with pytest.raises(si.ConfigError, match="an incomplete sweep"):
        si.measure(ds.assign_attrs(complete=0))
    with pytest.raises(si.ConfigError, match="a plane of 3 x 3 cells"):
        si.measure(ds.isel(x1=slice(0, 3), x2=slice(0, 3)))


def test_the_scene_kind_reads_its_keys_and_refuses_what_does_not_fit():
    from softimpact_cli.config.examples import example
    from softimpact_cli.kinds.scene import parse_scene

    text = example("fractality")
    scene = parse_scene(text, "f.toml")
    assert scene.analysis.box_sizes == (2, 3, 4, 5, 6, 8, 10)
    assert scene.initial_conditions.resolution == (40, 40)
    with pytest.raises(si.ConfigError, match=r"\[analysis\] radii: \[1, 2, 3, 4, 20\] does "
                                             "not fit a plane of 40 cells"):
        parse_scene(text.replace("radii = [1, 2, 3, 4, 6]", "radii = [1, 2, 3, 4, 20]"),
                    "f.toml")
    with pytest.raises(si.ConfigError, match=r"\[analysis\] box_sizes: must be a non-empty"):
        parse_scene(text.replace("box_sizes = [2, 3, 4, 5, 6, 8, 10]", "box_sizes = [1]"),
                    "f.toml")


@pytest.mark.slow
def test_the_scene_kind_sweeps_verifies_and_measures(tmp_path):
    from softimpact_cli.config.examples import example

    ds = si.run(example("fractality"), resolution=24, workers=1)
    assert ds.attrs["analysis"] == "fractality" and ds.sizes["point"] == 1
    assert ds.attrs["verify_status"] in ("verified", "bounded")  # the sweep's own check
    assert int(ds["n_basins"].values[0]) == 2 and str(ds["verdict"].values[0]) == "n/a"


def test_info_says_when_the_fit_is_not_to_be_trusted():
    from softimpact_cli.report.fractality import fractality_summary

    noise = np.random.default_rng(1).integers(0, 2, (1, 40, 40)).astype(np.int32)
    ds = basins_dataset().isel(panel=[0], x1=slice(0, 40), x2=slice(0, 40))
    ds["label"] = (("panel", "x1", "x2"), noise)
    salt = si.measure(ds)  # salt and pepper: every window of two labels at once
    assert "saturated" in fractality_summary(salt)["fractality"][0]["fit_note"]
    few = np.zeros((1, 40, 40), dtype=np.int32)
    few[0, 20, 20] = 1  # one cell of another basin: its boundary is a point
    ds["label"] = (("panel", "x1", "x2"), few)
    point = fractality_summary(si.measure(ds))["fractality"][0]
    assert point["fit_note"].startswith("the basins besides the largest hold fewer than 50")
    assert point["dimension"] < 0.5
    smooth = fractality_summary(si.measure(basins_dataset()))["fractality"]
    assert smooth[1]["fit_note"] is None  # the sectors


def test_the_ln2_verdict_names_its_box_sizes_and_distrusts_coarse_boxes():
    from softimpact_cli.report.fractality import LN2, ln2_verdict

    high, low = LN2 + 0.1, LN2 - 0.1
    sizes = [2, 3, 4, 5, 9, 20]
    assert ln2_verdict(sizes, [high] * 4 + [low, high], 3, 100) == \
        "fractal (S_bb > ln 2 at n = 2-5, 20)"
    assert ln2_verdict(sizes, [low] * 5 + [high], 3, 100).startswith(
        "inconclusive (S_bb > ln 2 only at n = 20, boxes over a tenth")
    assert ln2_verdict(sizes, [high] * 6, 2, 100).startswith("undecided (two basins")
    assert ln2_verdict(sizes, [low] * 6, 4, 100) == "undecided (S_bb <= ln 2 at every box size)"
    assert ln2_verdict(sizes, [float("nan")] * 6, 1, 100) == "no boundary"
