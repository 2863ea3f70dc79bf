"""How fractal a basin result is: basin entropy against the box size, the uncertainty
exponent and boundary dimension, and the Wada test, for every plane of a basins result.

One plane per grid point (panel) of a complete ``basins`` sweep over a plane of initial
conditions. The three measures are ``basin_entropy``, ``uncertainty`` and ``wada``;
this module only cuts the result into planes and gathers the answers into one dataset
(dims ``point``, ``box_size``, ``radius``, ``wada_radius``, ``row``, ``col``), the
``fractality`` result. Sizes and radii are in cells of the plane (its resolution), the
same for every point; the cell's size in the plane's units is stored beside them.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config.axes import GRID_AXES
from .attributes import attribute_list
from .basin_entropy import basin_entropy, default_box_sizes
from .uncertainty import default_radii, uncertainty_exponent
from .wada import wada_merge

# attributes a fractality result keeps from the basins result it measured
KEPT_ATTRS = ("model", "bodies", "ic_dims", "parameters", "forcing_period", "t0_mode", "t0",
              "t0_over_T", "plane_fixed", "catalogue_names", "scene_source", "scene_text",
              "scene_sha256", "grid_swept")


def plane_problem(ds: xr.Dataset) -> str | None:
    """What keeps ``ds`` from being measured, or None (a complete basins sweep over a
    plane of initial conditions, at least 4 x 4 cells)."""
    if ds.attrs.get("analysis") != "basins":
        return (f"holds a {ds.attrs.get('analysis')!r} result; fractality measures a basins "
                "result over a plane of initial conditions")
    if ds.attrs.get("ic_kind") != "plane":
        return (f"a basins result over {ds.attrs.get('ic_kind')!r} initial conditions; "
                "fractality needs a plane ([initial_conditions] kind = \"plane\")")
    if int(ds.attrs.get("complete", 1)) != 1:
        return "an incomplete sweep; finish it with softimpact sweep SCENE --resume"
    shape = [ds.sizes[d] for d in _plane_dims(ds)]
    if min(shape) < 4:
        return f"a plane of {shape[0]} x {shape[1]} cells; fractality needs at least 4 x 4"
    return None


def _grid_dims(ds: xr.Dataset) -> tuple[str, ...]:
    return tuple(attribute_list(ds.attrs, "grid_dims", GRID_AXES))


def _plane_dims(ds: xr.Dataset) -> tuple[str, str]:
    """The plane's two axes in the label array's order (rows, columns)."""
    grid = _grid_dims(ds)
    rows, cols = (d for d in ds["label"].dims if d not in grid)
    return rows, cols


def planes(ds: xr.Dataset):
    """(point values, labels (rows, cols)) of every grid point of a basins result."""
    grid = _grid_dims(ds)
    label = ds["label"].transpose(*grid, *_plane_dims(ds))
    shape = label.shape[: len(grid)]
    for index in np.ndindex(*shape):
        sel = dict(zip(grid, index, strict=True))
        point = {a: float(ds[a].isel({k: v for k, v in sel.items() if k in ds[a].dims})
                          .values)
                 for a in tuple(attribute_list(ds.attrs, "grid_parameters")) + GRID_AXES
                 if a in ds}
        yield point, label.values[index]


def measure_plane(labels: np.ndarray, box_sizes=None, radii=None, wada_radius: int = 5,
                  wada_tol: float = 0.05) -> xr.Dataset:
    """The three measures of one plane of labels, in one dataset."""
    return xr.merge([basin_entropy(labels, box_sizes), uncertainty_exponent(labels, radii),
                     wada_merge(labels, wada_radius, wada_tol)], combine_attrs="drop")


def fractality(ds: xr.Dataset, box_sizes=None, radii=None, wada_radius: int = 5,
               wada_tol: float = 0.05) -> xr.Dataset:
    """Basin entropy (S_b, S_bb against ``box_sizes``), uncertainty exponent (f(r) over
    ``radii``, alpha with its fit interval, D = 2 - alpha) and the Wada merging test (up to
    ``wada_radius`` cells, mismatch tolerance ``wada_tol``) of every plane of a basins
    result ``ds``. ValueError when ``ds`` is not one (``plane_problem``) or a size or
    radius does not fit the plane."""
    problem = plane_problem(ds)
    if problem:
        raise ValueError(problem)
    rows, cols = _plane_dims(ds)
    shape = (ds.sizes[rows], ds.sizes[cols])
    box_sizes = tuple(box_sizes) if box_sizes else default_box_sizes(shape)
    radii = tuple(radii) if radii else default_radii(shape)
    codes = [int(c) for c in ds["label_code"].values]
    parts, points, shares = [], [], []
    for point, labels in planes(ds):
        parts.append(measure_plane(labels, box_sizes, radii, wada_radius, wada_tol))
        points.append(point)
        shares.append([np.count_nonzero(labels == c) / labels.size for c in codes])
    out = xr.concat(parts, dim="point", data_vars="all", coords="minimal",
                    compat="override", join="override")
    out = out.assign_coords(
        {a: ("point", np.array([p[a] for p in points])) for a in points[0]})
    out = out.assign_coords(row=("row", ds[rows].values, dict(ds[rows].attrs)),
                            col=("col", ds[cols].values, dict(ds[cols].attrs)))
    out["label_share"] = (("point", "label_index"), np.array(shares),
                          {"long_name": "share of the plane's cells per label", "units": "1"})
    out["n_basins"] = ("point", np.array([int(np.count_nonzero(s)) for s in shares]),
                       {"long_name": "labels present on the plane (each its own basin)"})
    out = out.assign_coords(label_code=("label_index", np.asarray(codes, dtype=np.int32)),
                            label_name=("label_index", ds["label_name"].values.astype(str)))
    step = [float(np.abs(np.diff(ds[a].values)).mean()) if ds.sizes[a] > 1 else np.nan
            for a in (rows, cols)]
    out.attrs = {k: v for k, v in ds.attrs.items()
                 if k in KEPT_ATTRS or k.startswith("verify_")}  # the labels' error too
    out.attrs.update({
        "analysis": "fractality", "source_analysis": "basins",
        # lists: arrays in the file (analysis/attributes.py)
        "plane_axes": [rows, cols], "plane_shape": [int(shape[0]), int(shape[1])],
        "cell_size": [float(f"{step[0]:.6g}"), float(f"{step[1]:.6g}")],
        "grid_dims": list(_grid_dims(ds)),
        "box_sizes": [int(n) for n in box_sizes],
        "radii": [int(r) for r in radii],
        "wada_max_radius": int(wada_radius), "wada_tol": float(wada_tol),
        "labels_convention": "every distinct label a basin (unresolved, diverged and each "
                             "impacting period included), as in Attractors.jl",
    })
    return out
