"""The Python API (softimpact_cli/api.py): scenes from paths, text and dicts validated as
the CLI validates files; every kind run in memory, sweeps giving the dataset their result
file holds; resumable runs to a file; results opened; a light import."""

import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main
from softimpact_cli.kinds.scene import parse_scene

ROOT = Path(__file__).parents[1]
CONFIGS = ROOT / "configs"

PAIR = {"system": {"model": "duffing"},
        "coupling": {"d": 6.0, "phi": "5*pi/8", "k_c": 8.0, "c_c": 10.0}}
TRAJECTORY = {**PAIR, "analysis": {"kind": "trajectory", "state": [8.0, 0.0, -4.0, 0.0],
                                   "periods": 40}}
PLANE = {"system": {"model": "duffing"},  # figure 6(d): two basins
         "coupling": {"d": 6.0, "phi": 0.0, "k_c": 8.0, "c_c": 10.0},
         "analysis": {"kind": "basins"},
         "initial_conditions": {"kind": "plane", "axes": ["x1", "x2"],
                                "ranges": [[-12.0, 12.0], [-12.0, 12.0]],
                                "resolution": [10, 8]},
         "catalogue": {"grid": 4, "random": 20}}


def arrays(ds) -> dict[str, np.ndarray]:
    out = {}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        values = np.asarray(var.values)
        out[str(name)] = values.astype(str) if values.dtype.kind in "OU" else values
    return out


def assert_same_data(a, b) -> None:
    """Every data variable and coordinate equal (NaN equal to NaN), names and shapes."""
    x, y = arrays(a), arrays(b)
    assert sorted(x) == sorted(y)
    for name in x:
        assert x[name].shape == y[name].shape, name
        if x[name].dtype.kind == "f":
            np.testing.assert_array_equal(x[name], y[name], err_msg=name)
        else:
            assert np.array_equal(x[name], y[name]), name


def cli_result(tmp_path, scene_text: str, *options):
    path = tmp_path / "scene.toml"
    path.write_text(scene_text)
    out = tmp_path / "cli.h5"
    result = CliRunner().invoke(main, ["sweep", str(path), "-o", str(out), "-q", *options])
    assert result.exit_code == 0, result.output
    return si.open_result(out)


# ---------------------------------------------------------------- load_scene


@pytest.mark.parametrize("name", ["demo_basins", "trajectory_duffing", "design_duffing",
                                  "fig04_duffing_catalogue"])
def test_a_dict_gives_the_scene_of_the_file_it_mirrors(name):
    path = CONFIGS / f"{name}.toml"
    from_file = si.load_scene(path)
    from_dict = si.load_scene(tomllib.loads(path.read_text()))
    for field in ("system", "values", "integrator", "analysis", "grid", "initial_conditions",
                  "catalogue", "output"):
        assert getattr(from_dict, field) == getattr(from_file, field), field
    assert from_dict.source == "<dict>"
    # the stored text is TOML that reads back to the same dict
    assert tomllib.loads(from_dict.text) == tomllib.loads(path.read_text())


@pytest.mark.parametrize("doc, toml", [
    ({"system": {"model": "duffng"}}, '[system]\nmodel = "duffng"'),
    ({"system": {"F": "big"}}, '[system]\nF = "big"'),
    ({"system": {"F": True}}, "[system]\nF = true"),
    ({"coupling": {"dd": 1.0}}, "[coupling]\ndd = 1.0"),
    ({"sytem": {}}, "[sytem]"),
    ({"system": 3}, "system = 3"),
    ({"analysis": {"kind": "basins"}, "initial_conditions": {"resolution": [0, 4]}},
     '[analysis]\nkind = "basins"\n[initial_conditions]\nresolution = [0, 4]'),
    ({"analysis": {"kind": "trajectory", "state": [1.0, float("nan"), 0.0, 0.0]}},
     '[analysis]\nkind = "trajectory"\nstate = [1.0, nan, 0.0, 0.0]'),
    ({"grid": {"d": {"start": 1.0, "stop": 2.0}}, "analysis": {"kind": "basins"}},
     '[analysis]\nkind = "basins"\n[grid]\nd = { start = 1.0, stop = 2.0 }'),
])
def test_a_dict_fails_with_the_message_of_its_toml(doc, toml):
    with pytest.raises(si.ConfigError) as from_dict:
        si.load_scene(doc)
    with pytest.raises(si.ConfigError) as from_text:
        parse_scene(toml, "<dict>")
    assert str(from_dict.value) == str(from_text.value)
    assert "\n" not in str(from_dict.value)


def test_a_value_toml_cannot_hold_is_named():
    with pytest.raises(si.ConfigError, match=r"^<dict>: \[system\] F: not a TOML value"):
        si.load_scene({"system": {"F": None}})
    with pytest.raises(si.ConfigError, match="keys must be strings"):
        si.load_scene({"system": {1: 2.0}})


def test_strings_escape_into_toml_and_numpy_values_are_numbers():
    scene = si.load_scene({**TRAJECTORY, "system": {"model": "duffing", "F": np.float64(0.5)},
                           "output": {"path": 'out "quoted"\\x\t.h5'}})
    assert scene.values["F"] == 0.5
    assert str(scene.output).endswith('out "quoted"\\x\t.h5')


def test_paths_text_and_scenes(tmp_path):
    path = CONFIGS / "trajectory_duffing.toml"
    scene = si.load_scene(path)
    assert si.load_scene(str(path)) == scene
    assert si.load_scene(scene) is scene
    text = si.load_scene(path.read_text(), source="mine")
    assert text.analysis == scene.analysis and text.source == "mine"
    one_line = 'system.model = "duffing"\nanalysis.kind = "catalogue"'
    assert si.load_scene(one_line).analysis.kind == "catalogue"
    with pytest.raises(si.ConfigError, match=r"^<string>: \[system\] model: is required"):
        si.load_scene("")  # text: every default, and the model has none
    assert si.load_scene(tomllib.loads(one_line)).output == Path("results/scene.h5")
    with pytest.raises(si.ConfigError, match="nope.toml: no such scene file"):
        si.load_scene(tmp_path / "nope.toml")
    with pytest.raises(si.ConfigError, match="expected a scene file path"):
        si.load_scene(42)


# ---------------------------------------------------------------- run


def test_run_a_trajectory_as_the_cli_writes_it(tmp_path):
    ds = si.run(TRAJECTORY)
    assert ds.attrs["analysis"] == "trajectory" and ds.attrs["complete"] == 1
    cli = cli_result(tmp_path, si.load_scene(TRAJECTORY).text)
    assert_same_data(ds, cli)
    assert ds.attrs["outcome"] == cli.attrs["outcome"]
    assert ds.attrs["scene_sha256"] == cli.attrs["scene_sha256"]


def test_run_a_basins_plane_in_memory_as_the_cli_writes_it(tmp_path):
    """Same labels, statuses, periods, orbits, catalogue and label table as the file
    ``softimpact sweep`` writes, with several chunks finishing in any order (2 workers)."""
    ds = si.run(PLANE, workers=2, chunk_size=16)
    cli = cli_result(tmp_path, si.load_scene(PLANE).text, "--workers", "1",
                     "--chunk-size", "16")
    assert_same_data(ds, cli)
    assert len(np.unique(ds["label"].values)) >= 2  # a plane with more than one basin
    for key in ("analysis", "n", "n_chunks", "chunk_size", "plan", "catalogue_names",
                "ic_kind", "ic_dims", "scene_sha256", "t0_mode", "complete"):
        assert ds.attrs[key] == cli.attrs[key], key
    assert ds.attrs["executor"] == "local pool, 2 workers"


def small_example(kind: str) -> dict:
    """``softimpact example KIND`` as a dict, cut down to seconds."""
    from softimpact_cli.config.examples import EXAMPLES

    doc = tomllib.loads(EXAMPLES[kind])
    if kind == "stability":
        doc["grid"]["c_c"] = [2.0, 10.0]
        doc["initial_conditions"].update(n=12, t0="random")  # per-sample start times
    if kind == "map":
        doc["grid"] = {"d": [4.0, 20.0], "phi": [0.0, 3.0]}
        doc["initial_conditions"]["n"] = 8
    if kind in ("stability", "map"):
        doc["catalogue"] = {"grid": 4, "random": 20}
    if kind == "dcrit":
        doc["grid"]["phi"]["num"] = 8
    if kind == "bifurcation":
        doc["analysis"].update(start=12.0, stop=10.0, step=1.0)
    return doc


@pytest.mark.slow  # 5-10 s each on a busy 2-core machine
@pytest.mark.parametrize("kind", ["stability", "map", "dcrit", "bifurcation"])
def test_run_every_other_kind_as_the_cli_writes_it(kind, tmp_path):
    doc = small_example(kind)
    sweep = kind in ("stability", "map")
    ds = si.run(doc, workers=2, **({"chunk_size": 5} if sweep else {}))
    cli = cli_result(tmp_path, si.load_scene(doc).text, "--workers", "1",
                     *(("--chunk-size", "5") if sweep else ()))
    assert_same_data(ds, cli)
    assert ds.attrs["analysis"] == kind and ds.attrs["scene_sha256"] == cli.attrs[
        "scene_sha256"]


def test_run_quick_and_resolution_shrink_as_the_cli_flags_do():
    ds = si.run({**PLANE, "initial_conditions": {**PLANE["initial_conditions"],
                                                 "resolution": [30, 30]}},
                resolution=6, workers=1)
    assert ds.sizes["x1"] == 6 and ds.sizes["x2"] == 6
    assert "# --resolution 6:" in ds.attrs["scene_text"]
    quick = si.shrink_scene(si.load_scene(CONFIGS / "demo_basins.toml"), quick=True)
    assert quick.initial_conditions.resolution == (24, 24)
    with pytest.raises(si.ConfigError, match="resolution: must be a whole number"):
        si.run(PLANE, resolution=0.5)


def test_progress_is_off_unless_asked_and_counts_every_trajectory(capsys, tmp_path,
                                                                   monkeypatch):
    monkeypatch.chdir(tmp_path)  # the scene's [output] path would be results/scene.h5
    seen = []

    def progress(total, initial=0):
        seen.append((total, initial))
        return lambda labels: seen.append(len(labels))

    si.run(PLANE, workers=1, chunk_size=40, progress=progress)
    assert seen[0] == (80, 0) and sum(seen[1:]) == 80
    si.run(PLANE, workers=1)
    assert capsys.readouterr().err == ""  # quiet by default
    si.run(PLANE, workers=1, progress=True)  # a tqdm.auto bar (text on stderr here)
    assert "80/80" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []  # run writes nothing


# ---------------------------------------------------------------- sweep, open_result


def test_sweep_resumes_an_interrupted_run_to_the_in_memory_result(tmp_path):
    out = tmp_path / "plane.h5"

    def stop_after_first_chunk(total, initial=0):
        def tick(labels):
            raise KeyboardInterrupt
        return tick

    with pytest.raises(KeyboardInterrupt):
        si.sweep(PLANE, out, workers=1, chunk_size=16, progress=stop_after_first_chunk)
    assert int(si.open_result(out).attrs["complete"]) == 0
    assert len(list(Path(f"{out}.parts").glob("chunk-*.npz"))) == 1
    with pytest.raises(si.ConfigError, match="result exists; pass --overwrite"):
        si.sweep(PLANE, out, workers=1)
    done = si.sweep(PLANE, out, resume=True, workers=1)
    assert done.attrs["resumed"] == 1 and done.attrs["sessions"] == 2
    assert_same_data(si.open_result(out), si.run(PLANE, workers=1, chunk_size=16))


def test_sweep_writes_a_whole_kind_and_refuses_resume(tmp_path):
    out = tmp_path / "t.h5"
    ds = si.sweep(TRAJECTORY, out)
    assert_same_data(ds, si.open_result(out))
    with pytest.raises(si.ConfigError, match="result exists"):
        si.sweep(TRAJECTORY, out)
    with pytest.raises(si.ConfigError, match="resume is for sweeps"):
        si.sweep(TRAJECTORY, out, resume=True)
    si.sweep(TRAJECTORY, out, overwrite=True)


def test_sweep_defaults_to_the_scene_output_path(tmp_path):
    out = tmp_path / "sub" / "x.h5"
    si.sweep({**TRAJECTORY, "output": {"path": str(out)}})
    assert si.open_result(out).attrs["analysis"] == "trajectory"


def test_open_result_says_what_is_wrong(tmp_path):
    with pytest.raises(si.ConfigError, match="no such result file"):
        si.open_result(tmp_path / "none.h5")
    with pytest.raises(si.ConfigError, match="is a directory"):
        si.open_result(tmp_path)
    (tmp_path / "junk.h5").write_text("junk")
    with pytest.raises(si.ConfigError, match="not a softimpact result file"):
        si.open_result(tmp_path / "junk.h5")


# ---------------------------------------------------------------- the package


def test_import_is_light_and_names_stay_the_api_functions():
    code = ("import sys, softimpact_cli as si; "
            "heavy = [m for m in ('matplotlib', 'xarray', 'h5py', 'click') if m in sys.modules]; "
            "assert not heavy, heavy; "
            "from softimpact_cli.sweep import run_sweep; import softimpact_cli.sweep.runner; "
            "from softimpact_cli import api; "
            "assert si.sweep is api.sweep and si.run is api.run, si.sweep; "
            "assert callable(si.plot.basins)")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


# ---------------------------------------------------------------- datasets as handed out

TWO_D = {**PLANE, "grid": {"d": [6.0, 10.0]}}


@pytest.fixture(scope="module")
def two_planes(tmp_path_factory):
    """A plane at d = 6 and d = 10 (10 x 8 starts each), run in memory and written."""
    out = tmp_path_factory.mktemp("two") / "two.h5"
    return si.run(TWO_D, workers=1), si.sweep(TWO_D, out, workers=1), out


def test_run_sweep_open_result_and_open_dataset_order_dims_alike(two_planes):
    """Issue 31.12: the file's order (x2 before x1: ``ds.label.plot()`` puts x1 on the
    horizontal axis) from si.run, si.sweep, si.open_result and xarray.open_dataset."""
    import xarray as xr

    ran, swept, out = two_planes
    with xr.open_dataset(out, engine="h5netcdf") as raw:
        expected = {name: var.dims for name, var in raw.variables.items()}
    assert expected["label"][-2:] == ("x2", "x1")
    for ds in (ran, swept, si.open_result(out)):
        assert {name: var.dims for name, var in ds.variables.items()} == expected
    assert ran["label"].shape[-2:] == (8, 10)
    assert_same_data(ran, si.open_result(out))


def test_the_figures_and_measure_take_either_order(two_planes):
    from softimpact_cli.store import open_result as read_in_memory_order

    ran, _, out = two_planes
    internal = read_in_memory_order(out)
    assert internal["label"].dims[-2:] == ("x1", "x2")
    a, b = si.plot.basins(ran), si.plot.basins(internal)
    images = [[im.get_array() for ax in f.axes for im in ax.get_images()] for f in (a, b)]
    assert len(images[0]) == 2
    for x, y in zip(*images, strict=True):
        np.testing.assert_array_equal(x, y)


def test_a_selected_slice_plots(two_planes):
    """Issue 31.12: ``ds.sel(d=10)`` (d then a scalar coordinate) draws the d = 10 panel."""
    ran, _, _ = two_planes
    whole = si.plot.basins(ran)
    one = si.plot.basins(ran.sel(d=10.0))
    (image,) = one.axes[0].get_images()
    np.testing.assert_array_equal(image.get_array(), whole.axes[1].get_images()[0].get_array())
    assert "d = 10" in one.axes[0].get_title()


def test_one_panel_on_your_own_axes_is_titled_once(two_planes):
    """Issue 31.12: two one-panel plots on the caller's subplots: each panel says its own
    parameters in one line; the long description is not repeated on each."""
    from matplotlib.figure import Figure

    ran, _, _ = two_planes
    fig = Figure()
    left, right = fig.subplots(1, 2)
    si.plot.basins(ran.isel(d=[0]), ax=left)  # one grid point each
    si.plot.basins(ran.isel(d=[1]), ax=right)
    titles = [left.get_title(), right.get_title()]
    assert all("\n" not in t for t in titles), titles
    assert "d = 6" in titles[0] and "d = 10" in titles[1]
    assert fig.get_suptitle() == ""
    alone = si.plot.basins(ran.isel(d=[0]))  # a figure of its own keeps its description
    assert alone.axes[0].get_title().count("\n") >= 2
