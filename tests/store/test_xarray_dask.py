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
