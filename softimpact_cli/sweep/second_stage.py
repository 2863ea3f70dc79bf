"""The sweep's side of the second stage (``analysis/section_follow.py``,
``analysis/nonperiodic.py``): what a chunk returns about its recurrent trajectories, as
plain arrays a chunk file stores (so a resumed run loses nothing), and the parent's
relabelling once every chunk is in.

A worker follows its unresolved trajectories on the section and labels the periodic ones
itself (their codes are fixed by kind and period); the recurrent ones keep
``UNRESOLVED_LABEL`` in the chunk and travel as ``SECTION_ARRAYS``. After the last chunk
the parent gathers them in flat-index order and :func:`relabel` deduplicates, computes
one Lyapunov spectrum per attractor and writes the attractor codes: the same in every
worker count, executor and resume.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..analysis.engine import Problem
from ..analysis.nonperiodic import (
    Recurrent,
    attractor_table,
    identify,
    known_attractors,
    section_spectrum,
)
from ..analysis.section_follow import SectionFollow
from ..kernels.codes import PENDING

SECTION_ARRAYS = ("section_flat", "section_point", "section_ncells", "section_cells",
                  "section_ncloud", "section_cloud", "section_impacting", "section_end",
                  "section_end_t")
ORBIT_CLOUD = 200  # section points per recurrent attractor kept for plots (attractor_points)


def pack(found: list[tuple[int, int, SectionFollow]], dim: int) -> dict[str, np.ndarray]:
    """Recurrent trajectories (flat, grid point, follow) as SECTION_ARRAYS."""
    cells = [f.cells for _, _, f in found]
    clouds = [f.cloud for _, _, f in found]
    return {
        "section_flat": np.array([k for k, _, _ in found], dtype=np.int64),
        "section_point": np.array([p for _, p, _ in found], dtype=np.int64),
        "section_ncells": np.array([len(c) for c in cells], dtype=np.int64),
        "section_cells": np.concatenate(cells) if cells else np.zeros((0, dim), np.int64),
        "section_ncloud": np.array([len(c) for c in clouds], dtype=np.int64),
        "section_cloud": np.concatenate(clouds) if clouds else np.zeros((0, dim)),
        "section_impacting": np.array([f.impacting for _, _, f in found], dtype=np.int8),
        "section_end": (np.stack([f.end_state for _, _, f in found]) if found
                        else np.zeros((0, dim))),
        "section_end_t": np.array([f.end_time for _, _, f in found], dtype=np.float64),
    }


def progress_codes(result: dict, start: int) -> np.ndarray:
    """A chunk's label codes for the progress line, its recurrent trajectories (still
    ``UNRESOLVED_LABEL`` in the chunk, named after the last one) as ``PENDING``: the line
    counts them apart from those left unresolved. ``start``: the chunk's first flat index."""
    codes = np.array(result["label"], copy=True)
    flat = result.get("section_flat")
    if flat is not None and len(flat):
        codes[np.asarray(flat) - start] = PENDING
    return codes


def unpack(arrays: dict) -> list[Recurrent]:
    """The Recurrent trajectories of one chunk's arrays (none from a chunk file written
    before the second stage existed)."""
    if "section_flat" not in arrays:
        return []
    cell_end = np.cumsum(arrays["section_ncells"])
    cloud_end = np.cumsum(arrays["section_ncloud"])
    out = []
    for i, flat in enumerate(arrays["section_flat"]):
        c1, p1 = int(cell_end[i]), int(cloud_end[i])
        c0, p0 = c1 - int(arrays["section_ncells"][i]), p1 - int(arrays["section_ncloud"][i])
        out.append(Recurrent(int(flat), int(arrays["section_point"][i]),
                             arrays["section_cells"][c0:c1], arrays["section_cloud"][p0:p1],
                             bool(arrays["section_impacting"][i]), arrays["section_end"][i],
                             float(arrays["section_end_t"][i])))
    return out


def relabel(context, labels: np.ndarray, orbits: dict, found: list[Recurrent],
            state_names: tuple[str, ...], known=None) -> xr.Dataset:
    """Write the attractor codes of the recurrent trajectories ``found`` (any order) into
    the flat ``labels`` (in place, indexed by flat index), add each attractor's cloud to
    ``orbits`` at the grid points where it occurs (first flat index kept), and return the
    attractor table. ``context``: the sweep's ``SweepContext`` (grid values and
    integrator settings); ``known``: a result whose attractors keep their codes."""
    found = sorted(found, key=lambda r: r.flat)
    s = context.integrator

    def spectrum(point: int, state: np.ndarray, t: float):
        values, _ = context.point_values(point)
        return section_spectrum(Problem(context.system(), values, s),
                                state, t)

    seeds = known_attractors(known, s.section_cell)
    codes, attractors = identify(found, spectrum, s.section_zero_exponent, seeds)
    for rec, code in zip(found, codes, strict=True):
        labels[rec.flat] = code
        key = (rec.point, int(code))
        if code >= 0 and (key not in orbits or rec.flat < orbits[key][0]):
            orbits[key] = (rec.flat, rec.cloud[:ORBIT_CLOUD])
    return attractor_table(attractors, state_names)
