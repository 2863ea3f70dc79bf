"""The atlas-over-map check: cells where the count of coexisting solutions changes are
found near a curve that bounds the region, and a change no curve explains is listed."""

import json

import numpy as np
import xarray as xr

from softimpact_cli.report.atlas import changed_cells, map_agreement


def atlas_with(line: np.ndarray) -> xr.Dataset:
    n = len(line)
    return xr.Dataset({"pair": (("curve_point", "parameter"), line),
                       "curve_first": (("curve",), np.array([0])),
                       "curve_size": (("curve",), np.array([n]))},
                      attrs={"atlas_parameters": json.dumps(["phi", "d"])})


def map_of(counts: np.ndarray, phi: np.ndarray, d: np.ndarray) -> xr.Dataset:
    return xr.Dataset({"found_count": (("d", "phi"), counts)}, coords={"d": d, "phi": phi})


def test_changed_cells_are_both_sides_of_a_change():
    counts = np.array([[1, 1, 2], [1, 1, 1]])
    assert changed_cells(counts).tolist() == [[False, True, True], [False, False, True]]


def test_a_boundary_along_a_curve_is_explained_and_a_stray_change_is_listed():
    phi = np.linspace(0.0, 6.0, 31)
    d = np.linspace(0.0, 20.0, 41)
    counts = np.where(d[:, None] > 5.0 + phi[None, :], 2, 1)
    counts[35, 3] = 3  # a change no curve explains (a basin missed by sampling, say)
    line = np.column_stack([np.linspace(0.0, 6.0, 7), 5.0 + np.linspace(0.0, 6.0, 7)])
    report = map_agreement(atlas_with(line), map_of(counts, phi, d))
    stray = {(float(phi[3]), float(d[35]))} | {(float(phi[i]), float(d[j])) for i, j in
                                               ((2, 35), (4, 35), (3, 34), (3, 36))}
    assert report["changed_cells"] - report["near_a_curve"] == len(stray)
    assert {tuple(m["point"]) for m in report["missed"]} == stray
    centre = next(m for m in report["missed"] if m["point"] == [phi[3], d[35]])
    assert centre["count"] == 3 and set(centre["differing_neighbours"].values()) == {2}
    # the curve moved four cells away explains nothing of the boundary
    far = map_agreement(atlas_with(line + [0.0, 2.0]), map_of(counts, phi, d))
    assert far["share"] < 0.1
