"""Two-parameter maps: how many solutions coexist, predicted and found.

Predicted (from the critical distances): the number of non-impacting combinations whose
d_crit(phi) lies below d. Found (from sampling initial conditions at each point): the
number of distinct attractors reached, impacting ones included, and of non-impacting
ones alone. Where prediction and finding differ, that is a result: a combination whose
basin the samples missed, or impacting attractors the prediction cannot see.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config.axes import catalogue_key
from .attributes import attribute_list
from .chain_catalogue import survival
from .critical_distance import critical_distances
from .labels import parse_label


def add_map_counts(ds: xr.Dataset, system, values: dict, left_attractors: list,
                   dims: tuple[str, ...], body_lefts: dict | None = None) -> xr.Dataset:
    """Add predicted_count, found_count, found_nonimpacting to a sweep result whose grid
    points span ``dims`` (``sweep.result.grid_dims``).

    ``body_lefts``: when the grid sweeps body parameters (``config.axes``), the left
    attractors at each of their values, {((axis, value), ...): attractors}; the
    prediction at a point then uses the d_crit of its own attractors (``d_crit`` stored
    is the first's)."""
    found, found_free = found_counts(ds)
    phis = np.unique(np.asarray(ds["phi"].values, dtype=float))
    if body_lefts:
        dc, predicted = _predicted_per_body(ds, dims, system, values, body_lefts, phis)
        predicted = predicted.broadcast_like(found)
    else:
        dc = critical_distances(system, values, left_attractors, phis)
        table = {float(p): dc["d_crit"].values[:, i] for i, p in enumerate(dc["phi"].values)}
        d_b, phi_b = xr.broadcast(ds["d"], ds["phi"])
        predicted = np.vectorize(lambda d, p: int(np.sum(table[float(p)] < d)))(d_b.values,
                                                                               phi_b.values)
        predicted = xr.DataArray(predicted, dims=d_b.dims).broadcast_like(found)
    out = ds.assign(
        predicted_count=predicted.transpose(*dims).assign_attrs(
            long_name="non-impacting combinations predicted to survive (d_crit < d)"),
        found_count=found.transpose(*dims).assign_attrs(
            long_name="distinct attractors found (impacting, chaotic and quasi-periodic "
                      "included)"),
        found_nonimpacting=found_free.transpose(*dims).assign_attrs(
            long_name="distinct non-impacting attractors found"),
        d_crit=dc["d_crit"].rename(phi="dcrit_phi", combination="dcrit_combination"),
    )
    return out.assign_coords(dcrit_phi=("dcrit_phi", dc["phi"].values))


def found_counts(ds: xr.Dataset) -> tuple[xr.DataArray, xr.DataArray]:
    """(distinct attractors, distinct non-impacting attractors) the starts of each grid
    point reached."""
    names = [str(n) for n in ds["label_name"].values]
    codes = [int(c) for c in ds["label_code"].values]
    kinds = [parse_label(n).kind for n in names]
    ic_dims = attribute_list(ds.attrs, "ic_dims")
    label = ds["label"]
    present = xr.concat([(label == c).any(ic_dims) for c in codes], dim="label_index")
    attractor = xr.DataArray([k not in ("unresolved", "diverged") for k in kinds],
                             dims="label_index")
    free = xr.DataArray([k in ("pair", "body", "bodies", "unmatched") for k in kinds],
                        dims="label_index")
    return (present & attractor).sum("label_index"), (present & free).sum("label_index")


def add_chain_map_counts(ds: xr.Dataset, system, values: dict, catalogues: dict,
                         dims: tuple[str, ...]) -> xr.Dataset:
    """A chain's map: predicted_count (the products no stop touches at each grid point:
    each stop's critical values against its gap or wall there,
    ``chain_catalogue.survival``), found_count and found_nonimpacting, over the grid
    ``dims`` (the chain's swept parameters by name, then d, phi, k_c, c_c, t0 of length
    1). ``catalogues``: {``config.axes.catalogue_key``: ChainCatalogue}, one per
    distinct value of the parameters the bodies' attractors depend on."""
    found, found_free = found_counts(ds)
    names = set(system.parameter_names)
    shape = tuple(ds.sizes[d] for d in dims)
    predicted = np.zeros(shape, dtype=int)
    for index in np.ndindex(*shape):
        at = dict(values)
        at.update({d: float(ds[d].values[i]) for d, i in zip(dims, index, strict=True)
                   if d in names})
        cat = catalogues[catalogue_key(system, at)]
        predicted[index] = int(np.sum(survival(system, at, cat.critical)))
    predicted = xr.DataArray(predicted, dims=dims).broadcast_like(found)
    return ds.assign(
        predicted_count=predicted.transpose(*dims).assign_attrs(
            long_name="non-impacting products predicted to survive (no stop reached: "
                      "each stop's critical value short of it)"),
        found_count=found.transpose(*dims).assign_attrs(
            long_name="distinct attractors found (impacting, chaotic and quasi-periodic "
                      "included)"),
        found_nonimpacting=found_free.transpose(*dims).assign_attrs(
            long_name="distinct non-impacting attractors found"))


def _predicted_per_body(ds: xr.Dataset, dims: tuple[str, ...], system, values: dict,
                        body_lefts: dict, phis: np.ndarray) -> tuple[xr.Dataset, xr.DataArray]:
    """(d_crit at the first body parameters, predicted count per grid point) when the
    grid sweeps body parameters: each point counts the combinations of its own left
    attractors whose d_crit(phi) lies below d."""
    tables, first = {}, None
    for key, left in body_lefts.items():
        dc = critical_distances(system, {**values, **dict(key)}, left, phis)
        first = dc if first is None else first
        tables[key] = {float(p): dc["d_crit"].values[:, i]
                       for i, p in enumerate(dc["phi"].values)}
    axes = [a for a, _ in next(iter(body_lefts))]
    shape = tuple(ds.sizes[d] for d in dims)
    predicted = np.zeros(shape, dtype=int)
    for index in np.ndindex(*shape):
        sel = dict(zip(dims, index, strict=True))

        def at(name, sel=sel):
            return float(ds[name].isel({k: v for k, v in sel.items() if k in ds[name].dims}))

        key = tuple((a, at(a)) for a in axes)
        predicted[index] = int(np.sum(tables[key][at("phi")] < at("d")))
    return first, xr.DataArray(predicted, dims=dims)
