"""Write and read result files (netCDF4-compatible HDF5 through h5netcdf).

A result is serialised to memory first and then written with plain file I/O to a
temporary name that is renamed over the target: a full disk or an unwritable folder is
one ConfigError naming the path (HDF5 never writes to a failing disk), and a killed or
failed write leaves no half file behind.

On disk a result follows CF-1.10 where it applies: ``Conventions`` and ``history``
global attributes, no ``_FillValue`` on coordinates, zlib compression (level 4,
shuffle) on every variable over COMPRESS_MIN elements, and a plane of initial
conditions stored with its first axis last, so that generic tools
(``ds.label.plot()``) put x1 on the horizontal axis. ``open_result`` restores the
in-memory order (grid dims, then the plane axes as named in ``ic_dims``).
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
from pathlib import Path

import numpy as np
import xarray as xr

from ..config import ConfigError
from .lock import output_lock
from .provenance import command_line
from .xarray_dask import install as _lazy_dask

_lazy_dask()  # writing a file imports no dask while none is in use (xarray_dask.py)

ENGINE = "h5netcdf"
CONVENTIONS = "CF-1.10"
COMPRESS_MIN = 1000  # variables with more elements than this are compressed
COMPRESSION = {"zlib": True, "complevel": 4, "shuffle": True}


def _netcdf_safe(value):
    if isinstance(value, bool | np.bool_):
        return int(value)
    return value


def _plane_axes(ds: xr.Dataset) -> tuple[str, str] | None:
    """The two plane axes (in-memory order) of a plane-of-initial-conditions result."""
    if ds.attrs.get("ic_kind") != "plane":
        return None
    axes = str(ds.attrs.get("ic_dims", "")).split()
    return (axes[0], axes[1]) if len(axes) == 2 else None


def _swap_plane(ds: xr.Dataset, order: tuple[str, str]) -> xr.Dataset:
    """Transpose every variable ending in the plane axes so that they end in ``order``."""
    pair = set(order)
    out = ds.copy()
    for name, var in ds.variables.items():
        if len(var.dims) >= 2 and set(var.dims[-2:]) == pair and var.dims[-2:] != order:
            out[name] = var.transpose(*var.dims[:-2], *order)
    return out


def file_dataset(ds: xr.Dataset) -> tuple[xr.Dataset, dict]:
    """(dataset, encoding) as stored: netCDF-safe attributes, CF attributes, compression,
    no fill value on coordinates, the plane axes swapped."""
    ds = ds.copy()
    attrs = {k: _netcdf_safe(v) for k, v in ds.attrs.items()}
    attrs.setdefault("Conventions", CONVENTIONS)
    ds.attrs = attrs
    plane = _plane_axes(ds)
    if plane is not None:
        ds = _swap_plane(ds, plane[::-1])
    encoding = {}
    for name, var in ds.variables.items():
        var.encoding = {}
        enc: dict = {}
        if name in ds.coords:
            enc["_FillValue"] = None
        if var.size > COMPRESS_MIN and var.dtype.kind in "biuf":
            enc.update(COMPRESSION)
        if enc:
            encoding[name] = enc
    return ds, encoding


def _free_bytes(folder: Path) -> int | None:
    try:
        return shutil.disk_usage(folder).free
    except OSError:
        return None


def write_bytes_atomically(data, path: Path) -> None:
    """Write ``data`` to ``path`` through a temporary file and a rename; any OSError
    (full disk, permissions, a name too long) becomes one ConfigError, no file left."""
    partial = path.with_name(path.name + ".partial")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        free = _free_bytes(path.parent)
        if free is not None and len(data) > free:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        with open(partial, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(partial, path)
    except OSError as exc:
        with contextlib.suppress(OSError):
            partial.unlink()
        reason = exc.strerror or exc.__class__.__name__
        size = f" ({len(data)} bytes)" if exc.errno in (errno.ENOSPC, errno.EDQUOT) else ""
        raise ConfigError(f"{path}: cannot write the result{size}: {reason}") from None
    finally:
        with contextlib.suppress(OSError):
            partial.unlink()


def write_result(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically, holding the output lock while writing."""
    path = Path(path)
    stored, encoding = file_dataset(ds)
    data = stored.to_netcdf(engine=ENGINE, encoding=encoding)  # in memory
    with output_lock(path, command_line()):
        write_bytes_atomically(data, path)
    return path


def open_result(path: str | os.PathLike) -> xr.Dataset:
    """Open a result file fully into memory (the file is closed on return), in the
    in-memory dim order."""
    with xr.open_dataset(path, engine=ENGINE) as ds:
        ds = ds.load()
    plane = _plane_axes(ds)
    return _swap_plane(ds, plane) if plane is not None else ds


def add_attributes(path: str | os.PathLike, attrs: dict) -> None:
    """Add global attributes to a finished result file (rewritten atomically)."""
    ds = open_result(path)
    ds.attrs.update(attrs)
    write_result(ds, path)
