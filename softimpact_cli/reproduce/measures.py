"""Reading what the study's statements are about out of result datasets: catalogue
names, critical distances, destruction points, plane basin shares, basin-stability
shares (with 95% Wilson intervals) and the box-counting dimension of a basin boundary."""

from __future__ import annotations

import numpy as np

from ..analysis.attributes import attribute_list
from ..analysis.labels import parse_label
from ..analysis.stability import basin_stability, wilson_interval
from ..config.axes import COUPLING_AXES
from ..report.info import sweep_summary
from ..sweep.result import grid_dims


def is_solution(name: str) -> bool:
    """A non-impacting periodic solution (pair or one body)."""
    try:
        return parse_label(name).kind in ("pair", "body")
    except ValueError:
        return False


def is_impacting(name: str) -> bool:
    return name.startswith("impacting")


def combination_names(ds) -> list[str]:
    return [str(n) for n in ds["combination_name"].values]


def attractor_periods(ds) -> list[int]:
    return [int(p) for p in ds["attractor_period"].values]


def dcrit_curve(ds, name: str) -> tuple[np.ndarray, np.ndarray]:
    """(phi, d_crit) of one combination of a dcrit result."""
    names = [str(n) for n in ds["combination_label"].values]
    row = ds["d_crit"].transpose("combination", "phi").values[names.index(name)]
    return ds["phi"].values, row


def dcrit_at(ds, name: str, phi: float) -> float:
    phis, row = dcrit_curve(ds, name)
    k = int(np.argmin(np.abs(phis - phi)))
    if abs(phis[k] - phi) > 1e-9:
        raise ValueError(f"phi = {phi} is not on the result's phase grid")
    return float(row[k])


def survivors(ds, d: float, phi: float) -> list[str]:
    """Combinations with d_crit(phi) < d: the non-impacting states that exist at (d, phi)."""
    names = [str(n) for n in ds["combination_label"].values]
    return [n for n in names if dcrit_at(ds, n, phi) < d]


def branches(ds) -> dict[str, dict]:
    """{branch: {destroyed_at, falls_to, impacting_range, labels along d}} of a bifurcation."""
    names = [str(n) for n in ds["branch_name"].values]
    codes = {int(c): str(n) for c, n in zip(ds["label_code"].values, ds["label_name"].values,
                                            strict=True)}
    label = ds["label"].transpose("branch", "d").values
    return {name: {"destroyed_at": float(ds["destroyed_at"].values[i]),
                   "falls_to": str(ds["falls_to"].values[i]),
                   "impacting_range": [float(v) for v in ds["impacting_range"].values[i]],
                   "d": ds["d"].values, "labels": [codes.get(int(c), "?") for c in label[i]]}
            for i, name in enumerate(names)}


def first_grid_d(branch: dict, test) -> float:
    """The first d of the branch's d grid (d decreasing) whose label passes ``test``."""
    for d, name in zip(branch["d"], branch["labels"], strict=True):
        if test(name):
            return float(d)
    return float("nan")


def plane_points(ds) -> list[dict]:
    """Per grid point of a basins result: parameters, counts, fractions, n (cells)."""
    points = sweep_summary(ds)["points"]
    for p in points:
        p["n"] = sum(p["counts"].values())
    return points


def point_at(points: list[dict], **where) -> dict:
    for p in points:
        if all(abs(float(p[k]) - float(v)) < 1e-6 for k, v in where.items()):
            return p
    raise KeyError(f"no grid point at {where}")


def found(point: dict) -> tuple[list[str], list[str]]:
    """(non-impacting solutions, impacting solutions) with at least one start."""
    names = [n for n, c in point["counts"].items() if c > 0]
    return sorted(n for n in names if is_solution(n)), sorted(n for n in names
                                                             if is_impacting(n))


def share(point: dict, names) -> tuple[float, tuple[float, float]]:
    """Share of the starts reaching any of ``names`` ("impacting (all)" and
    "non-impacting (sum)" group them), with its 95% Wilson interval over the n starts."""
    if names == "impacting (all)":
        names = [n for n in point["counts"] if is_impacting(n)]
    elif names == "non-impacting (sum)":
        names = [n for n in point["counts"] if is_solution(n)]
    elif isinstance(names, str):
        names = [names]
    k = sum(point["counts"].get(n, 0) for n in names)
    lo, hi = wilson_interval(np.array(k), point["n"])
    return k / point["n"], (float(lo), float(hi))


def stability_points(ds) -> list[dict]:
    """Per grid point of a stability result: parameters and counts per group."""
    bs = basin_stability(ds)
    dims = grid_dims(ds)
    count = bs["count"].transpose(*dims, "group").values
    groups = [str(g) for g in bs["group"].values]
    points = []
    for k, index in enumerate(np.ndindex(*count.shape[:-1])):
        point = {a: float(v) for a, v in sweep_summary(ds)["points"][k].items()
                 if a in COUPLING_AXES or (a == "t0" and v != "random")}
        if ds.attrs.get("t0_mode") == "random":
            point["t0"] = "random"
        point["counts"] = {g: int(count[index][j]) for j, g in enumerate(groups)
                           if "(" not in g}
        point["n"] = int(bs.attrs["n"])
        points.append(point)
    return points


def plane_labels(ds, panel: int) -> tuple[np.ndarray, list[np.ndarray], dict[int, str]]:
    """(labels (ny, nx) of grid point ``panel``, [first-axis values, second-axis values],
    {code: name}) of a basins result on a plane."""
    dims = grid_dims(ds)
    ic_dims = attribute_list(ds.attrs, "ic_dims")
    label = ds["label"].transpose(*dims, *ic_dims).values
    label = label.reshape(-1, *label.shape[len(dims):])[panel]
    axes = [ds[d].values for d in ic_dims]
    table = {int(c): str(n) for c, n in zip(ds["label_code"].values, ds["label_name"].values,
                                            strict=True)}
    return label, axes, table


def boundary_dimension(label: np.ndarray) -> float:
    """Box-counting dimension of the set of cells that touch another basin: about 1 for
    a smooth boundary curve, more for a fractal one (boxes of 1, 2, 4, ... cells)."""
    edge = np.zeros(label.shape, dtype=bool)
    edge[:-1, :] |= label[:-1, :] != label[1:, :]
    edge[:, :-1] |= label[:, :-1] != label[:, 1:]
    sizes, counts = [], []
    size = 1
    while size <= min(label.shape) // 8:
        ny, nx = label.shape[0] // size, label.shape[1] // size
        boxes = edge[:ny * size, :nx * size].reshape(ny, size, nx, size).any(axis=(1, 3))
        sizes.append(size)
        counts.append(max(int(boxes.sum()), 1))
        size *= 2
    if len(sizes) < 2:
        return float("nan")
    slope = np.polyfit(np.log(sizes), np.log(counts), 1)[0]
    return float(-slope)


def row_shares(label: np.ndarray, code: int) -> np.ndarray:
    """Share of each row (fixed second-axis value... i.e. fixed velocity) reaching ``code``."""
    return (label == code).mean(axis=1)


def stable_impacting_leg(ds, name: str) -> dict:
    """Where branch ``name`` of a continuation result is a stable impacting orbit after it
    grazes, followed from its start in the direction of the falling parameter: the stable
    non-impacting points first, then the stable impacting run that follows them.

    Returns {"grazing": parameter of the grazing event that opens the run, "low", "high":
    the run's parameter range, "fold": the fold event that closes it (NaN: the run ends
    otherwise), "end": what ends it ("fold", "unstable", "not impacting" or the branch's
    end), "parameter", "modulus": (k,) the run's parameter values (rising) and largest
    |multiplier| there}. A branch with no such run has NaN everywhere and empty arrays.
    """
    names = [str(n) for n in ds["branch_name"].values]
    b = names.index(name)
    first, size = int(ds["branch_first"].values[b]), int(ds["branch_size"].values[b])
    start = int(ds["branch_start"].values[b]) - first
    lam = ds["parameter"].values[first:first + size]
    stable = ds["stable"].values[first:first + size].astype(bool)
    impacting = ds["impacting"].values[first:first + size].astype(bool)
    mu = ds["multiplier_re"].values[first:first + size] + \
        1j * ds["multiplier_im"].values[first:first + size]
    modulus = np.max(np.abs(mu), axis=1)
    down = -1 if start > 0 and (start == size - 1 or lam[start - 1] < lam[start]) else 1
    k = start
    while 0 <= k + down < size and stable[k] and not impacting[k]:
        k += down
    run = []
    while 0 <= k < size and stable[k] and impacting[k]:
        run.append(k)
        k += down
    events = [(str(kind), float(p)) for kind, br, p in zip(
        ds["event_kind"].values, ds["event_branch"].values, ds["event_parameter"].values,
        strict=True) if int(br) == b]
    nan = float("nan")
    if not run:
        return {"grazing": nan, "low": nan, "high": nan, "fold": nan, "end": "no run",
                "parameter": np.array([]), "modulus": np.array([])}
    lo, hi = float(lam[run].min()), float(lam[run].max())
    step = float(np.max(np.abs(np.diff(lam)))) if size > 1 else 0.0

    def nearest(kind: str, value: float) -> float:
        near = [p for e, p in events if e == kind and abs(p - value) <= step]
        return min(near, key=lambda p: abs(p - value)) if near else nan

    fold = nearest("fold", lo)
    if np.isfinite(fold):
        end = "fold"
    elif not 0 <= k < size:
        end = str(ds["branch_end_low" if down < 0 else "branch_end_high"].values[b])
    else:
        end = "unstable" if not stable[k] else "not impacting"
    order = np.argsort(lam[run])
    return {"grazing": nearest("grazing", hi), "low": lo, "high": hi, "fold": fold,
            "end": end, "parameter": lam[run][order], "modulus": modulus[run][order]}
