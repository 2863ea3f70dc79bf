"""Sweeps: labels consistent across the grid, determinism across executors, resumability,
the file layout, and clean errors for bad grids."""

import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest
import xarray as xr

from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store import open_result
from softimpact_cli.sweep import run_sweep

SCENE = """
[system]
model = "duffing"
[coupling]
d = 6.0
[integrator]
cell_size = 0.0  # chunks of a few trajectories here; cells take whole blocks (test_chunks)
[analysis]
kind = "basins"
[grid]
phi = [0.0, "pi"]
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [{res}, {res}]
[catalogue]
grid = 6
random = 30
seed = 2
[output]
path = "{out}"
"""

DATA_VARS = ("label", "status", "period", "periods_used", "contacts", "max_penetration",
             "label_code", "label_name")


def scene_text(out, res=6):
    return SCENE.format(out=out, res=res)


def equal_results(a: xr.Dataset, b: xr.Dataset) -> None:
    """Same values, dimension by dimension (a file opened with xr.open_dataset has x1 last)."""
    for v in DATA_VARS:
        assert np.array_equal(a[v].values, b[v].transpose(*a[v].dims).values), v
    assert np.array_equal(a["attractor_points"].values,
                          b["attractor_points"].transpose(*a["attractor_points"].dims).values,
                          equal_nan=True)


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial") / "serial.h5"
    scene = parse_scene(scene_text(out), "serial.toml")
    ds = run_sweep(scene, out, workers=1, chunk_size=10)
    return scene, out, ds


def test_layout_with_xarray(serial):
    _, out, _ = serial
    with xr.open_dataset(out) as ds:
        # on disk the plane's first axis is last: generic plots put x1 horizontally
        assert ds["label"].dims == ("d", "phi", "k_c", "c_c", "t0", "x2", "x1")
        assert open_result(out)["label"].dims == ("d", "phi", "k_c", "c_c", "t0", "x1", "x2")
        assert ds.sizes["phi"] == 2 and ds.sizes["x1"] == 6 and ds.sizes["x2"] == 6
        assert ds["phi"].values[1] == pytest.approx(np.pi)
        for v in ("label", "period", "periods_used", "status", "max_penetration", "contacts"):
            assert "long_name" in ds[v].attrs and "units" in ds[v].attrs
        assert ds.attrs["complete"] == 1 and ds.attrs["wall_s"] > 0
        assert "[grid]" in ds.attrs["scene_text"] and len(ds.attrs["scene_sha256"]) == 64
        for key in ("softimpact_version", "integrator_method", "integrator_rtol", "machine",
                    "started", "finished"):
            assert key in ds.attrs
        names = list(ds["label_name"].values)
        # every label in the data is in the table; catalogue solutions come first
        assert set(np.unique(ds["label"].values)) <= set(ds["label_code"].values)
        assert names[:4] == ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1", "L1^2 R1-0^2"]


def test_layout_with_h5py(serial):
    _, out, _ = serial
    with h5py.File(out, "r") as f:
        assert f["label"].shape == (1, 2, 1, 1, 1, 6, 6)
        assert f["label"].attrs["long_name"].startswith("attractor reached")
        assert set(f["label_code"][:]) >= {0, 1, 2, 3}
        assert f.attrs["complete"] == 1
        assert "scene_text" in f.attrs


def test_labels_are_the_catalogues_and_consistent_across_grid(serial):
    _, _, ds = serial
    assert set(ds.attrs["catalogue_names"]) == {  # a list (analysis/attributes.py)
        "L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1", "L1^2 R1-0^2"}
    # the small-small solution exists at both phases (d = 6 is far above its d_crit)
    small = ds["label"].sel(phi=0.0)
    assert (small == 0).sum() > 0 and (ds["label"].isel(phi=1) == 0).sum() > 0
    assert (ds["status"] == 0).all()


def test_same_result_on_a_pool_of_two(serial, tmp_path):
    scene, _, ds = serial
    out = tmp_path / "pool.h5"
    pooled = run_sweep(parse_scene(scene_text(out), "pool.toml"), out, workers=2, chunk_size=7)
    equal_results(ds, pooled)


def test_same_result_on_dask_local_cluster(serial, tmp_path):
    pytest.importorskip("dask.distributed")
    _, _, ds = serial
    out = tmp_path / "dask.h5"
    res = run_sweep(parse_scene(scene_text(out), "dask.toml"), out, scheduler="local:2",
                    chunk_size=12)
    equal_results(ds, res)
    with xr.open_dataset(out) as back:
        assert back.attrs["executor"].startswith("dask")


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "softimpact_cli", *args], capture_output=True,
                          text=True)


def test_sigkill_then_resume_equals_uninterrupted(serial, tmp_path):
    _, _, ds = serial
    out = tmp_path / "killed.h5"
    scene = tmp_path / "killed.toml"
    scene.write_text(scene_text(out))
    proc = subprocess.Popen([sys.executable, "-m", "softimpact_cli", "sweep", str(scene),
                             "--workers", "1", "--chunk-size", "4", "-q"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    parts = tmp_path / "killed.h5.parts"
    deadline = time.time() + 240
    while time.time() < deadline:
        if parts.is_dir() and len(list(parts.glob("chunk-*.npz"))) >= 3:
            break
        if proc.poll() is not None:
            pytest.fail(f"sweep ended before it could be killed: {proc.stderr.read()}")
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    # an unfinished file says so
    info = _cli("info", str(out), "--json")
    assert info.returncode == 0, info.stderr
    summary = json.loads(info.stdout)
    assert summary["complete"] is False and 0 < summary["progress"]["chunks_done"] < 18
    # it is not taken for a result, and not overwritten silently
    again = _cli("sweep", str(scene), "-q")
    assert again.returncode == 2 and "--resume" in again.stderr
    resumed = _cli("sweep", str(scene), "--resume", "-q", "--workers", "1")
    assert resumed.returncode == 0, resumed.stderr
    back = open_result(out)
    assert back.attrs["complete"] == 1 and back.attrs["resumed"] == 1
    equal_results(ds, back)
    assert not parts.exists()


def test_resume_with_another_scene_is_refused(tmp_path):
    out = tmp_path / "r.h5"
    scene = tmp_path / "r.toml"
    scene.write_text(scene_text(out, res=3))
    proc = subprocess.Popen([sys.executable, "-m", "softimpact_cli", "sweep", str(scene),
                             "--workers", "1", "--chunk-size", "1", "-q"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    parts = tmp_path / "r.h5.parts"
    deadline = time.time() + 240
    while time.time() < deadline and not (parts.is_dir() and any(parts.glob("chunk-*.npz"))):
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    scene.write_text(scene_text(out, res=3).replace("d = 6.0", "d = 7.0"))
    res = _cli("sweep", str(scene), "--resume")
    assert res.returncode == 2 and "another scene" in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1


BAD_GRIDS = {
    "num zero": ("[grid]\nd = {start = 1, stop = 2, num = 0}\n", "[grid] d.num"),
    "wrong-way step": ("[grid]\nd = {start = 5, stop = 1, step = 0.5}\n", "[grid] d.step"),
    "unknown axis": ("[grid]\nk = [1, 2]\n", "[grid] k"),
    "negative c_c": ("[grid]\nc_c = [1, -2]\n", "[grid] c_c"),
}


def _sweep_scene(tmp_path, grid="", ic=None):
    out = tmp_path / "bad.h5"
    ic = ic or ("kind = 'plane'\naxes = ['x1', 'x2']\nranges = [[-1, 1], [-1, 1]]\n"
                "resolution = [3, 3]\n")
    return out, (f"[system]\nmodel='duffing'\n[analysis]\nkind='basins'\n{grid}"
                 f"[initial_conditions]\n{ic}[output]\npath='{out}'\n")


@pytest.mark.parametrize("name", sorted(BAD_GRIDS))
def test_bad_grids(tmp_path, name):
    grid, key = BAD_GRIDS[name]
    out, text = _sweep_scene(tmp_path, grid=grid)
    scene = tmp_path / "s.toml"
    scene.write_text(text)
    res = _cli("sweep", str(scene))
    assert res.returncode == 2, res.stderr
    assert key in res.stderr and "s.toml" in res.stderr and "Traceback" not in res.stderr
    assert len(res.stderr.strip().splitlines()) == 1
    assert not out.exists() and not (tmp_path / "bad.h5.parts").exists()


@pytest.mark.parametrize("ic, key", [
    ("kind = 'plane'\naxes = ['x1', 'y']\nranges = [[-1, 1], [-1, 1]]\n",
     "[initial_conditions] axes"),
    ("kind = 'random'\nn = 0\nbox = {x1=[-1,1], v1=[-1,1], x2=[-1,1], v2=[-1,1]}\n",
     "[initial_conditions] n"),
    ("kind = 'random'\nn = 5\nbox = {x1=[-1,1], v1=[-1,1], x2=[-1,1]}\n",
     "[initial_conditions] box.v2"),
    ("kind = 'list'\nstates = [[1, 2, 3]]\n", "[initial_conditions] states"),
    ("kind = 'plane'\nt0 = 'random'\nranges = [[-1, 1], [-1, 1]]\n", "[initial_conditions] t0"),
])
def test_bad_initial_conditions(tmp_path, ic, key):
    out, text = _sweep_scene(tmp_path, ic=ic)
    scene = tmp_path / "s.toml"
    scene.write_text(text)
    res = _cli("sweep", str(scene))
    assert res.returncode == 2 and key in res.stderr, res.stderr
    assert not out.exists()
