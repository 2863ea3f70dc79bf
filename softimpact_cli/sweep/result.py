"""Turn a sweep's chunk arrays into one labelled Dataset (no I/O)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config import GRID_AXES, GRID_UNITS, Scene
from ..labels import latex_of, name_of
from .chunks import RESULT_FIELDS

ATTRIBUTES = {
    "label": ("attractor reached (code; see label_code/label_name)", "1"),
    "status": ("kernel status code (0 converged; see status_message)", "1"),
    "period": ("period of the orbit reached", "forcing periods"),
    "periods_used": ("forcing periods integrated before classification", "forcing periods"),
    "contacts": ("contact onsets on the final orbit", "1"),
    "max_penetration": ("max of x1 - x2 - d on the final orbit (>= 0: impacting)", "1"),
    "captured": ("how it was classified: 0 by the repeat of its own section points, 1 by "
                 "capture near a known stable orbit, 2 by recurrence cells", "1"),
    "steps": ("integrator steps, all methods", "1"),
    "stiff_steps": ("steps taken by Rodas4 (the others by the explicit pair)", "1"),
}


def sweep_dataset(scene: Scene, arrays: dict[str, np.ndarray], orbits: dict,
                  names: tuple[str, ...], t0_per_sample: np.ndarray | None) -> xr.Dataset:
    """Dataset with dims (d, phi, k_c, c_c, t0, *initial-condition dims).

    ``arrays``: flat per-trajectory arrays (RESULT_FIELDS) in plan order; ``orbits``:
    {(grid point, code): (flat index, section points)} with the first occurrence kept.
    """
    grid = scene.grid
    ic = scene.initial_conditions
    dims = grid.dims + ic.dims
    shape = grid.shape + ic.shape
    along = ("panel",) if grid.panels else None
    coords: dict = {a: (along or a, np.array(grid.axes[a]), {"units": GRID_UNITS[a]})
                    for a in GRID_AXES}
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
        "ic_dims": " ".join(ic.dims),
        "grid_swept": " ".join(grid.swept),
        "grid_dims": " ".join(grid.dims),
        "t0_mode": "random" if t0_per_sample is not None else
                   ("grid" if "t0" in grid.swept else "fixed"),
        "forcing_period": 2 * np.pi / float(scene.values["w"]),
        "catalogue_names": "; ".join(names),
    }
    if ic.kind == "plane":
        attrs["plane_fixed"] = ", ".join(f"{k}={v}" for k, v in (ic.fixed or {}).items())
    return xr.Dataset(data, coords=coords, attrs=attrs)
