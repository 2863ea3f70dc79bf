"""Tipping probabilities between two parameter points (Kaszas, Feudel and Tél, Phys.
Rev. E 100, 032202 (2019); Attractors.jl ``tipping_probabilities``).

After a sudden change of parameters from point A ("before") to point B ("after"), a
state in the basin of solution i at A goes wherever its basin at B says. The tipping
probability is the overlap of the basins over the same initial conditions,

    P(i -> j) = |B_i(A) ∩ B_j(B)| / |B_i(A)|,

estimated by the share of the sampled starts labelled i at A that are labelled j at B,
with a 95% Wilson interval (the starts of a plane are a lattice, not a random sample:
there the interval describes the sampling of that lattice). Rows sum to 1. Unresolved and
diverged starts are labels like the solutions, so nothing is dropped.

A state *on* solution i, rather than anywhere in its basin, goes where the basin at B
of its own orbit says: :func:`attractor_destinations` labels the section points of each
solution present at A at the parameters of B (what "moving d from 22 to 6, where do the
four states go" asks).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from .labels import name_of
from .stability import wilson_interval


def tipping_probabilities(before: np.ndarray, after: np.ndarray,
                          names: tuple[str, ...] | Mapping[int, str]) -> xr.Dataset:
    """The basin-overlap matrix of two label arrays over the same starts.

    before, after : (n,) label codes at the two parameter points (same starts, same
        order); names : the catalogue's label names (codes 0..len-1; other codes are
        unresolved, diverged, impacting ... as ``labels.name_of`` names them), or a
        {code: name} table (a result's label_code and label_name)
    Returns dims (tip_from, tip_to), each the labels present at that point: tip_count
    (starts), tip_probability (row shares), tip_ci95_low/high (Wilson), and tip_from_share
    (each basin's share of the starts at A).
    """
    before = np.asarray(before).ravel()
    after = np.asarray(after).ravel()
    if before.shape != after.shape:
        raise ValueError(f"before and after label arrays differ in size: {before.size} "
                         f"and {after.size}")
    rows, cols = np.unique(before), np.unique(after)
    count = np.zeros((rows.size, cols.size), dtype=np.int64)
    np.add.at(count, (np.searchsorted(rows, before), np.searchsorted(cols, after)), 1)
    totals = count.sum(axis=1)
    low, high = wilson_interval(count, np.maximum(totals, 1)[:, None])
    def named(code) -> str:
        return names[int(code)] if isinstance(names, Mapping) else name_of(code, names)

    coords = {"tip_from": [named(c) for c in rows], "tip_to": [named(c) for c in cols]}
    dims = ("tip_from", "tip_to")
    return xr.Dataset(
        {"tip_count": (dims, count, {"long_name": "starts in basin i before and j after"}),
         "tip_probability": (dims, count / np.maximum(totals, 1)[:, None],
                             {"long_name": "tipping probability P(i -> j)"}),
         "tip_ci95_low": (dims, low, {"long_name": "95% Wilson interval, low"}),
         "tip_ci95_high": (dims, high, {"long_name": "95% Wilson interval, high"}),
         "tip_from_share": (("tip_from",), totals / max(before.size, 1),
                            {"long_name": "share of the starts in basin i before"})},
        coords=coords)


def attractor_destinations(orbits: dict[str, np.ndarray], label_at_after
                           ) -> dict[str, list[str]]:
    """{solution at A: the labels at B of its section points}.

    orbits : {name: (q, dim) section points of the solution at A}; label_at_after(states
    (n, dim)) -> n label names at the parameters of B (the same start time).
    """
    names = list(orbits)
    if not names:
        return {}
    states = np.concatenate([orbits[n] for n in names])
    labels = list(label_at_after(states))
    out, k = {}, 0
    for name in names:
        q = orbits[name].shape[0]
        out[name] = labels[k:k + q]
        k += q
    return out
