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

from ..analysis.attributes import with_lists
from ..config import ConfigError, space
from .layout import file_order, memory_order
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


def file_attributes(attrs) -> dict:
    """Global attributes as a file stores them: netCDF-safe values, CF ``Conventions``."""
    out = {k: _netcdf_safe(v) for k, v in attrs.items()}
    out.setdefault("Conventions", CONVENTIONS)
    return out


def file_dataset(ds: xr.Dataset) -> tuple[xr.Dataset, dict]:
    """(dataset, encoding) as stored: netCDF-safe attributes, CF attributes, compression,
    no fill value on coordinates, the plane axes swapped."""
    ds = ds.copy()
    ds.attrs = file_attributes(ds.attrs)
    ds = file_order(ds)
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
        return space.free_bytes(folder)
    except OSError:
        return None


def write_bytes_atomically(data, path: Path) -> None:
    """Write ``data`` to ``path`` through a temporary file and a rename; any OSError
    (full disk, permissions, a name too long) becomes one ConfigError, no file left."""

    def write(partial: Path) -> None:
        free = _free_bytes(path.parent)
        if free is not None and len(data) > free:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        with open(partial, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())

    _replace_atomically(path, write, f" ({len(data)} bytes)")


def _replace_atomically(path: Path, write, size: str = "") -> None:
    """``write(partial)`` a temporary file beside ``path``, then rename it over ``path``;
    any OSError becomes one ConfigError naming ``path`` (``size`` added on a full disk),
    and no temporary file is left."""
    partial = path.with_name(path.name + ".partial")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write(partial)
        os.replace(partial, path)
    except OSError as exc:
        with contextlib.suppress(OSError):
            partial.unlink()
        reason = exc.strerror or exc.__class__.__name__
        size = size if exc.errno in (errno.ENOSPC, errno.EDQUOT) else ""
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


def _same(a, b) -> bool:
    return type(a) is type(b) and bool(np.array_equal(np.asarray(a), np.asarray(b)))


def update_attributes(path: str | os.PathLike, written, attrs) -> Path:
    """Give the result file ``path``, which ``write_result`` wrote from a dataset with the
    global attributes ``written``, the attributes ``attrs`` instead: the file
    ``write_result`` would write from that dataset with ``attrs``, without serialising
    its variables again (a whole write of a small sweep's result costs 0.2-0.3 s, nearly
    all of it h5netcdf creating variables; this 0.03 s).

    The attributes from the first one that differs onwards are deleted and written
    again in ``attrs``' order, so the stored order is ``write_result``'s; on a copy that
    replaces ``path`` atomically, holding the output lock, as ``write_result`` does.
    """
    import h5netcdf
    import h5py

    path = Path(path)
    old, new = file_attributes(written), file_attributes(attrs)
    old_keys, new_keys = list(old), list(new)
    first = 0
    while (first < min(len(old_keys), len(new_keys)) and old_keys[first] == new_keys[first]
           and _same(old[old_keys[first]], new[new_keys[first]])):
        first += 1

    def write(partial: Path) -> None:
        shutil.copyfile(path, partial)
        with h5py.File(partial, "r") as f:  # every attribute, h5netcdf's hidden ones too
            stored = list(f.attrs)
        rewritten = set(old_keys[first:])
        start = min((stored.index(k) for k in rewritten if k in stored), default=len(stored))
        hidden = [k for k in stored[start:] if k not in rewritten]  # e.g. _NCProperties
        with h5netcdf.File(partial, "r+") as f:
            for key in old_keys[first:]:
                del f.attrs[key]
            for key in new_keys[first:]:
                f.attrs[key] = new[key]
        with h5py.File(partial, "r+") as f:  # hidden ones after them, as in a new file
            for key in hidden:
                dtype, value = f.attrs.get_id(key).dtype, f.attrs[key]
                del f.attrs[key]
                f.attrs.create(key, value, dtype=dtype)
        with open(partial, "rb+") as fh:
            os.fsync(fh.fileno())

    with output_lock(path, command_line()):
        _replace_atomically(path, write)
    return path


def open_result(path: str | os.PathLike) -> xr.Dataset:
    """Open a result file fully into memory (the file is closed on return), in the
    in-memory dim order, its list-valued attributes as lists (also those an older file
    joined into one text: ``analysis.attributes``)."""
    with xr.open_dataset(path, engine=ENGINE) as ds:
        ds = ds.load()
    ds.attrs = with_lists(ds.attrs)
    return memory_order(ds)


def add_attributes(path: str | os.PathLike, attrs: dict) -> None:
    """Add global attributes to a finished result file (rewritten atomically)."""
    ds = open_result(path)
    ds.attrs.update(attrs)
    write_result(ds, path)
