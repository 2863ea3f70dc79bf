"""Write and read result files (netCDF4-compatible HDF5 through h5netcdf)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

ENGINE = "h5netcdf"


def _netcdf_safe(value):
    if isinstance(value, bool | np.bool_):
        return int(value)
    return value


def write_result(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically: a killed write leaves no half file behind."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(path.name + ".partial")
    ds = ds.copy()
    ds.attrs = {k: _netcdf_safe(v) for k, v in ds.attrs.items()}
    try:
        ds.to_netcdf(partial, engine=ENGINE)
        os.replace(partial, path)
    finally:
        if partial.exists():
            partial.unlink()
    return path


def open_result(path: str | os.PathLike) -> xr.Dataset:
    """Open a result file fully into memory (the file is closed on return)."""
    with xr.open_dataset(path, engine=ENGINE) as ds:
        return ds.load()


def add_attributes(path: str | os.PathLike, attrs: dict) -> None:
    """Add global attributes to a finished result file in place."""
    import h5py

    with h5py.File(path, "a") as f:
        for key, value in attrs.items():
            f.attrs[key] = _netcdf_safe(value)
