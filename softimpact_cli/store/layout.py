"""The two dim orders of a result over a plane of initial conditions.

In memory (what the analyses, reports and figures index) a plane's variables end in its
axes as named in ``ic_dims`` (``x1, x2``). On disk they end in the reverse (``x2, x1``),
so that generic tools (``ds.label.plot()``, ncview) put the plane's first axis on the
horizontal axis; the Python API hands datasets out in that file order too, so that
``si.run``, ``si.open_result`` and ``xarray.open_dataset`` agree. Each function is
idempotent and leaves every other result as it is.
"""

from __future__ import annotations

import xarray as xr

from ..analysis.attributes import attribute_list


def plane_axes(ds: xr.Dataset) -> tuple[str, str] | None:
    """The two plane axes (in-memory order) of a plane-of-initial-conditions result."""
    if ds.attrs.get("ic_kind") != "plane":
        return None
    axes = attribute_list(ds.attrs, "ic_dims")
    return (axes[0], axes[1]) if len(axes) == 2 else None


def _ending_in(ds: xr.Dataset, order: tuple[str, str]) -> xr.Dataset:
    """Every variable ending in the two plane axes transposed to end in ``order``."""
    pair = set(order)
    out = ds.copy()
    for name, var in ds.variables.items():
        if len(var.dims) >= 2 and set(var.dims[-2:]) == pair and var.dims[-2:] != order:
            out[name] = var.transpose(*var.dims[:-2], *order)
    return out


def memory_order(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with a plane's variables ending in (first axis, second axis)."""
    plane = plane_axes(ds)
    return _ending_in(ds, plane) if plane is not None else ds


def file_order(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with a plane's variables ending in (second axis, first axis), as stored."""
    plane = plane_axes(ds)
    return _ending_in(ds, plane[::-1]) if plane is not None else ds
