"""List-valued global attributes of a result, written as lists and read back as lists.

A result's attributes that hold several values (the plane's axes, the grid's dims, the
catalogue's names, a fractality's box sizes, ...) are Python lists in memory and arrays
in the file (netCDF string or number arrays: ``ncdump`` shows ``ic_dims = "x1", "x2"``).
Results written before 2026-11-27 joined them into one text ("x1 x2", names with "; ");
:func:`attribute_list` reads every form, so old files still open. ``store.open_result``
gives every attribute of :data:`LIST_ATTRIBUTES` as a list; readers of datasets from
elsewhere (``xarray.open_dataset`` returns a one-element array as its element) call
:func:`attribute_list`.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import numpy as np

# name -> how results written before the change joined its values (None: whitespace)
LIST_ATTRIBUTES: dict[str, str | None] = {
    "ic_dims": None, "grid_swept": None, "grid_dims": None, "grid_parameters": None,
    "catalogue_names": "; ",
    "plane_axes": None, "plane_shape": None, "cell_size": None, "box_sizes": None,
    "radii": None,
}
NUMERIC = ("plane_shape", "cell_size", "box_sizes", "radii")  # numbers, not names


def _number(text: str) -> int | float:
    try:
        return int(text)
    except ValueError:
        return float(text)


def as_list(key: str, value: Any) -> list:
    """``value`` of the list-valued attribute ``key`` as a list, whatever form it was
    stored in (a list or array; a scalar: one element; old joined text; JSON text)."""
    if isinstance(value, str):
        text = value.strip()
        if text.startswith("["):
            try:
                return list(json.loads(text))
            except ValueError:
                pass
        separator = LIST_ATTRIBUTES.get(key)
        parts = [p for p in (text.split(separator) if separator else text.split()) if p]
        return [_number(p) for p in parts] if key in NUMERIC else parts
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, list | tuple):
        return [v.item() if isinstance(v, np.generic) else v for v in value]
    return [value.item() if isinstance(value, np.generic) else value]


def attribute_list(attrs: Mapping[str, Any], key: str, default=()) -> list:
    """The list-valued attribute ``key`` of ``attrs`` (a list of ``default`` when it is
    absent)."""
    return as_list(key, attrs[key]) if key in attrs else list(default)


def with_lists(attrs: Mapping[str, Any]) -> dict[str, Any]:
    """``attrs`` with every attribute of LIST_ATTRIBUTES as a list (the reader's form)."""
    return {k: as_list(k, v) if k in LIST_ATTRIBUTES else v for k, v in attrs.items()}
