"""Turn a sweep's chunk arrays into one labelled Dataset (no I/O)."""

from __future__ import annotations

import re

import numpy as np
import xarray as xr

from ..analysis.attributes import attribute_list
from ..analysis.chain_catalogue import stop_values, survival
from ..analysis.labels import latex_of, name_of
from ..config import Scene, forcing_period
from ..config.axes import GRID_AXES, axis_units, catalogue_key
from ..config.chain_scene import CHAIN
from .chunks import RESULT_FIELDS

ATTRIBUTES = {
    "label": ("attractor reached (code; see label_code/label_name)", "1"),
    "status": ("kernel status code (0 converged; see status_message)", "1"),
    "period": ("period of the orbit reached", "forcing periods"),
    "periods_used": ("forcing periods integrated before classification", "forcing periods"),
    "contacts": ("contact onsets on the final orbit", "1"),
    "max_penetration": ("max of x1 - x2 - d on the final orbit (>= 0: impacting)", "1"),
    "captured": ("how it was classified: 0 by the repeat of its own section points, 1 by "
                 "capture near a known stable orbit, 2 by recurrence cells, 3 followed on "
                 "the section after the first pass (second stage)", "1"),
    "steps": ("integrator steps, all methods", "1"),
    "stiff_steps": ("steps taken by Rodas4 (the others by the explicit pair)", "1"),
}


def cf_word(name: str) -> str:
    """A label name as a CF flag_meanings word: letters, digits and _ - . + @ only."""
    return re.sub(r"[^A-Za-z0-9_.+@-]", "_", name.strip()) or "_"


def categorical_attrs(codes, names, dtype) -> dict:
    """CF categorical attributes of the label variable: ``flag_values`` (the codes, of
    the variable's type), ``flag_meanings`` (CF-safe words, unique) and ``flag_names``
    (the real names, "; " separated, same order)."""
    words: list[str] = []
    for name in names:
        word = cf_word(name)
        while word in words:
            word += "_"
        words.append(word)
    return {"flag_values": np.array(codes, dtype=dtype), "flag_meanings": " ".join(words),
            "flag_names": "; ".join(names)}


def t0_attrs(t0_values, period: float, random: bool, swept: bool) -> dict:
    """Global attributes recording the start time actually used: ``t0_mode`` (fixed,
    grid or random), ``t0`` (time units; the grid's values when swept) and
    ``t0_over_T`` (the same in forcing periods). Random: only the mode (the per-sample
    times are the variable ``sample_t0``)."""
    if random:
        return {"t0_mode": "random"}
    values = np.array(list(dict.fromkeys(float(v) for v in np.ravel(t0_values))))
    t0 = values if swept else float(values[0])
    return {"t0_mode": "grid" if swept else "fixed", "t0": t0, "t0_over_T": t0 / period}


def sweep_dataset(scene: Scene, arrays: dict[str, np.ndarray], orbits: dict,
                  names: tuple[str, ...], t0_per_sample: np.ndarray | None) -> xr.Dataset:
    """Dataset with dims (*swept model parameters, d, phi, k_c, c_c, t0,
    *initial-condition dims) (``Grid.dims``).

    ``arrays``: flat per-trajectory arrays (RESULT_FIELDS) in plan order; ``orbits``:
    {(grid point, code): (flat index, section points)} with the first occurrence kept.
    """
    grid = scene.grid
    ic = scene.initial_conditions
    dims = grid.dims + ic.dims
    shape = grid.shape + ic.shape
    along = ("panel",) if grid.panels else None
    coords: dict = {a: (along or a, np.array(grid.axes[a]), {"units": axis_units(a)})
                    for a in grid.names}
    # the forcing period of the scene, or of the first grid point when w is swept (each
    # point then has its own, 2 pi / w, and starts at t0 = 0: config.sweep.W_SWEPT_T0)
    period = forcing_period(grid.point(0) if "w" in grid.swept else scene.values)
    if "t0" not in grid.swept and ic.t0 is not None:  # the fixed start actually used
        coords["t0"] = (along or "t0", np.full(len(grid.axes["t0"]), float(ic.t0)),
                        coords["t0"][2])
    coords["t0"][2]["long_name"] = "time at which the initial state is imposed"
    if grid.panels:
        coords["panel"] = ("panel", np.arange(grid.size))
    for a, values in ic.coords().items():
        coords[a] = (a, values, {"long_name": f"initial {a}", "units": "1"})
    data = {}
    for key in RESULT_FIELDS:
        long_name, units = ATTRIBUTES[key]
        data[key] = (dims, arrays[key].reshape(shape), {"long_name": long_name, "units": units})
    codes = sorted(set(range(len(names))) | set(np.unique(arrays["label"]).tolist()))
    label_names = [name_of(c, names) for c in codes]
    data["label"][2].update(categorical_attrs(codes, label_names, RESULT_FIELDS["label"]))
    coords["label_index"] = ("label_index", np.arange(len(codes)))
    data["label_code"] = (("label_index",), np.array(codes, dtype=np.int32),
                          {"long_name": "label code"})
    data["label_name"] = (("label_index",), np.array(label_names, dtype=object),
                          {"long_name": "label name (ASCII)"})
    data["label_latex"] = (("label_index",), np.array([latex_of(n) for n in label_names],
                                                      dtype=object),
                           {"long_name": "label name (LaTeX)"})
    # one representative orbit per (grid point, label) for plots (projections of attractors)
    dim = len(scene.system.state_names)
    max_q = max((o[1].shape[0] for o in orbits.values()), default=1)
    orbit_arr = np.full((len(codes), grid.size, max_q, dim), np.nan)
    position = {c: i for i, c in enumerate(codes)}
    for (point, code), (_, pts) in orbits.items():
        orbit_arr[position[code], point, : pts.shape[0]] = pts
    coords["orbit_point"] = ("orbit_point", np.arange(max_q))
    coords["variable"] = ("variable", list(scene.system.state_names))
    data["attractor_points"] = (
        ("label_index",) + grid.dims + ("orbit_point", "variable"),
        orbit_arr.reshape((len(codes),) + grid.shape + (max_q, dim)),
        {"long_name": "section points of an orbit reached, per label and grid point",
         "units": "1"})
    if ic.kind != "plane":
        data["initial_state"] = (("sample", "variable"), ic.array(),
                                 {"long_name": "initial state", "units": "1"})
    if t0_per_sample is not None:
        data["sample_t0"] = (("sample",), t0_per_sample,
                             {"long_name": "time at which each sample's state is imposed "
                                           "(random t0)", "units": "1"})
    attrs = {
        "analysis": scene.analysis.kind,
        "ic_kind": ic.kind,
        "ic_dims": list(ic.dims),  # lists: arrays in the file (analysis/attributes.py)
        "grid_swept": list(grid.swept),
        "grid_dims": list(grid.dims),
        **t0_attrs(coords["t0"][1], period, t0_per_sample is not None,
                   "t0" in grid.swept),
        "forcing_period": period,
        "catalogue_names": list(names),
    }
    if grid.parameters:  # model parameters swept besides GRID_AXES (their own dims)
        attrs["grid_parameters"] = list(grid.parameters)
    if ic.kind == "plane":
        attrs["plane_fixed"] = ", ".join(f"{k}={v}" for k, v in (ic.fixed or {}).items())
    return xr.Dataset(data, coords=coords, attrs=attrs)


# ---------------------------------------------------------------- reading the schema


def grid_dims(ds) -> tuple[str, ...]:
    """The dims a sweep's grid points span: its swept model parameters and GRID_AXES, or
    ("panel",); without those a selection took away (``ds.sel(d=10)`` keeps d as a
    scalar coordinate)."""
    dims = attribute_list(ds.attrs, "grid_dims", GRID_AXES)
    return tuple(d for d in dims if d in ds.dims or d not in ds.coords)


def grid_axes(ds) -> tuple[str, ...]:
    """Every axis with a value at each grid point: the model parameters the sweep spans
    besides GRID_AXES (attribute ``grid_parameters``), then GRID_AXES. A chain's result
    (attribute ``model = "chain"``) has no pair's coupling: its d, phi, k_c, c_c dims
    (length 1, kept so every sweep result has them) are no axes of it."""
    own = tuple(attribute_list(ds.attrs, "grid_parameters"))
    if ds.attrs.get("model") == CHAIN:
        return own + ("t0",)
    return own + GRID_AXES


def grid_point(ds, index: tuple[int, ...]) -> dict:
    """Parameter values of the grid point at ``index`` (over grid_dims); t0 is "random"
    when each sample has its own start time."""
    dims = grid_dims(ds)
    sel = dict(zip(dims, index, strict=True))
    point = {a: float(ds[a].isel({k: v for k, v in sel.items() if k in ds[a].dims}).values)
             for a in grid_axes(ds)}
    if ds.attrs.get("t0_mode") == "random":
        point["t0"] = "random"
    return point


def point_survival(ds: xr.Dataset, system, values: dict, catalogues: dict) -> xr.Dataset:
    """A chain's sweep ``ds`` with which products survive at each grid point: the
    variables ``combination_survives`` (grid dims..., combination) and ``stop_value``
    (grid dims..., stop) replace the catalogue table's, which say it at one point only.

    Each point reads its own catalogue (``catalogues``, by ``config.axes.catalogue_key``)
    at its own stop values (``chain_catalogue.survival``); a product is the stored one of
    that name (``combination_name``), 0 where the point's catalogue has no such name."""
    dims = grid_dims(ds)
    shape = tuple(ds.sizes[d] for d in dims)
    names = [str(n) for n in ds["combination_name"].values]
    parameters = set(system.parameter_names)
    n_stops = ds.sizes.get("stop", 0)
    survives = np.zeros(shape + (len(names),), dtype=np.int8)
    stops = np.zeros(shape + (n_stops,))
    for index in np.ndindex(*shape):
        at = {**values, **{a: v for a, v in grid_point(ds, index).items() if a in parameters}}
        cat = catalogues[catalogue_key(system, at)]
        alive = dict(zip(cat.names, survival(system, at, cat.critical), strict=True))
        survives[index] = [alive.get(name, False) for name in names]
        stops[index] = stop_values(system, at)
    return ds.assign(
        combination_survives=(dims + ("combination",), survives,
                              {"long_name": "1: no stop touches it at the grid point's "
                                            "values (each point its own)"}),
        stop_value=(dims + ("stop",), stops,
                    {"long_name": "each stop's gap (between bodies) or wall position at "
                                  "the grid point", "units": "1"}))
