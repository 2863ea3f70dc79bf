"""Result files: written whole or not at all (a full disk is one clean error, item 12),
and readable by generic tools (CF attributes, compression, no fill value on coordinates,
x1 on the horizontal axis of ``ds.label.plot()``)."""

import os
import subprocess
import sys

import h5py
import numpy as np
import pytest
import xarray as xr

from softimpact_cli.config import ConfigError
from softimpact_cli.store import add_attributes, open_result, write_result


def plane_result(n=40):
    """A plane result shaped like a sweep's: grid dims, then the plane x1, x2."""
    rng = np.random.default_rng(0)
    dims = ("d", "t0", "x1", "x2")
    return xr.Dataset(
        {"label": (dims, rng.integers(0, 4, (1, 1, n, n + 1)).astype(np.int32)),
         "period": (dims, rng.integers(1, 3, (1, 1, n, n + 1)).astype(np.int16)),
         "small": (("x1",), np.arange(n, dtype=float))},
        coords={"d": ("d", [6.0]), "t0": ("t0", [0.0]), "x1": np.linspace(-1, 1, n),
                "x2": np.linspace(-2, 2, n + 1)},
        attrs={"ic_kind": "plane", "ic_dims": "x1 x2", "complete": True})


def test_on_disk_layout_is_cf_friendly_and_read_back_unchanged(tmp_path):
    ds = plane_result()
    out = write_result(ds, tmp_path / "r.h5")
    with h5py.File(out, "r") as f:
        assert f.attrs["Conventions"] == "CF-1.10"
        for name in ("d", "t0", "x1", "x2"):
            assert "_FillValue" not in f[name].attrs, name
        assert f["label"].compression == "gzip" and f["label"].compression_opts == 4
        assert f["label"].shuffle and f["period"].compression == "gzip"
        assert f["small"].compression is None  # 40 elements: not worth it
    with xr.open_dataset(out) as raw:
        # x1 last: xarray (and most tools) put the last dim on the horizontal axis
        assert raw["label"].dims == ("d", "t0", "x2", "x1")
        import matplotlib

        matplotlib.use("Agg")
        mesh = raw["label"].isel(d=0, t0=0).plot()
        assert mesh.axes.get_xlabel().startswith("x1")
        assert mesh.axes.get_ylabel().startswith("x2")
    back = open_result(out)
    assert back["label"].dims == ds["label"].dims
    for name in ("label", "period", "small"):
        assert np.array_equal(back[name].values, ds[name].values)
    assert back.attrs["complete"] == 1


def test_add_attributes_keeps_the_data(tmp_path):
    out = write_result(plane_result(), tmp_path / "r.h5")
    add_attributes(out, {"check_sample": 10})
    back = open_result(out)
    assert back.attrs["check_sample"] == 10
    assert np.array_equal(back["label"].values, plane_result()["label"].values)


def test_full_disk_is_one_clean_error_and_leaves_nothing(tmp_path):
    if not os.path.exists("/dev/full"):
        pytest.skip("needs /dev/full")
    out = tmp_path / "r.h5"
    # the temporary file the writer opens is /dev/full: every write fails with ENOSPC
    (tmp_path / "r.h5.partial").symlink_to("/dev/full")
    with pytest.raises(ConfigError) as exc:
        write_result(plane_result(), out)
    assert str(exc.value).startswith(f"{out}: cannot write the result (")
    assert str(exc.value).endswith("bytes): No space left on device")
    assert sorted(os.listdir(tmp_path)) == []


def test_too_little_free_space_is_refused_before_writing(tmp_path, monkeypatch):
    import shutil

    from softimpact_cli.store import h5netcdf_

    real = shutil.disk_usage
    monkeypatch.setattr(h5netcdf_.shutil, "disk_usage",
                        lambda p: real(p)._replace(free=100))
    with pytest.raises(ConfigError, match="No space left on device"):
        write_result(plane_result(), tmp_path / "r.h5")
    assert os.listdir(tmp_path) == []


@pytest.mark.slow
def test_full_disk_while_writing_a_trajectory_cli(tmp_path):
    """The issue's case: a trajectory result on a full disk (segfault, exit -11, on main)."""
    if not os.path.exists("/dev/full"):
        pytest.skip("needs /dev/full")
    out = tmp_path / "t.h5"
    (tmp_path / "t.h5.partial").symlink_to("/dev/full")
    scene = tmp_path / "t.toml"
    scene.write_text("[system]\nmodel = 'duffing'\n[coupling]\nd = 6.0\n[analysis]\n"
                     "kind = 'trajectory'\nstate = [8.0, 0.0, -4.0, 0.0]\nperiods = 5\n")
    res = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene), "-o",
                          str(out)], capture_output=True, text=True)
    assert res.returncode == 2, res.stderr
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"softimpact: error: {out}: cannot write")
    assert lines[0].endswith("No space left on device")
    assert sorted(os.listdir(tmp_path)) == ["t.toml"]
