"""xarray's dask probes made lazy (store/xarray_dask.py): a sweep imports no dask, and
dask arrays are still dask arrays to xarray once dask is imported."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_a_sweep_to_file_imports_no_dask(tmp_path):
    code = (
        "import sys, softimpact_cli as si\n"
        f"ds = si.sweep('configs/demo_basins.toml', {str(tmp_path / 'r.h5')!r}, resolution=4,"
        " workers=1, verify_sample=4)\n"
        "loaded = [m for m in ('dask', 'dask.array', 'distributed') if m in sys.modules]\n"
        "assert not loaded, loaded\n"
        f"back = si.open_result({str(tmp_path / 'r.h5')!r})\n"
        "assert (back.label.values == ds.label.values).all()\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT)
    assert proc.returncode == 0, proc.stderr


def test_dask_arrays_stay_dask_arrays_once_dask_is_imported(tmp_path):
    code = (
        "import numpy as np, xarray as xr\n"
        "from softimpact_cli.store.xarray_dask import install\n"
        "from xarray.backends.locks import get_dask_scheduler\n"
        "install()\n"
        "assert get_dask_scheduler() == 'threaded'\n"
        "plain = xr.Dataset({'a': ('x', np.arange(4.0))})\n"
        "assert plain.a.chunks is None\n"
        "import dask, dask.array as da\n"
        "ds = xr.Dataset({'a': ('x', da.arange(4.0, chunks=2))})\n"
        "assert ds.a.chunks == ((2, 2),), ds.a.chunks\n"
        "assert isinstance(ds.a.data, da.Array)\n"
        "with dask.config.set(scheduler='processes'):\n"
        "    assert get_dask_scheduler() == 'multiprocessing'\n"
        f"ds.to_netcdf({str(tmp_path / 'd.nc')!r}, engine='h5netcdf')\n"
        f"back = xr.open_dataset({str(tmp_path / 'd.nc')!r}, engine='h5netcdf').load()\n"
        "assert (back.a.values == np.arange(4.0)).all()\n"
    )
    pytest.importorskip("dask.array")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT)
    assert proc.returncode == 0, proc.stderr


def test_install_is_idempotent_and_keeps_plain_arrays_plain():
    import xarray as xr

    from softimpact_cli.store.xarray_dask import install

    install()
    install()
    v = xr.Variable("x", np.arange(3))
    assert v.chunks is None and isinstance(v.data, np.ndarray)


def test_update_attributes_gives_the_file_write_result_would(tmp_path):
    """store.update_attributes (the verification's last write): same variables, same
    attributes in the same order and types, h5netcdf's hidden ones included."""
    import h5py
    import xarray as xr

    from softimpact_cli.store import update_attributes, write_result

    ds = xr.Dataset({"a": ("x", np.arange(2000.0)), "s": ("y", np.array(["p", "q"]))},
                    coords={"x": np.arange(2000)})
    ds.attrs.update({"n": 3, "name": "before", "flag": True, "status": "pending"})
    written = dict(ds.attrs)
    write_result(ds, tmp_path / "fast.h5")
    ds.attrs.update({"status": "verified", "share": 0.25, "history": "[1, 2]"})
    update_attributes(tmp_path / "fast.h5", written, ds.attrs)
    write_result(ds, tmp_path / "whole.h5")

    def attributes(path):
        with h5py.File(path) as f:
            return [(k, str(f.attrs.get_id(k).dtype), np.asarray(f.attrs[k]).tolist())
                    for k in f.attrs]

    assert attributes(tmp_path / "fast.h5") == attributes(tmp_path / "whole.h5")
    fast = xr.open_dataset(tmp_path / "fast.h5", engine="h5netcdf").load()
    xr.testing.assert_identical(fast, xr.open_dataset(tmp_path / "whole.h5",
                                                      engine="h5netcdf").load())
    assert not list(tmp_path.glob("*.partial"))
