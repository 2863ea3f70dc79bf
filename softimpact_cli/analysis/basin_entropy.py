"""Basin entropy S_b and boundary basin entropy S_bb of a basin plane (Daza, Wagemakers,
Georgeot, Guéry-Odelin, Sanjuán, Sci. Rep. 6, 31416 (2016)); the entropy of basin shares
from one random sampling.

A plane of labels (an integer per grid cell) is covered by non-overlapping boxes of
n x n cells, starting at the first cell; the last n - 1 rows or columns that do not fill
a box are left out (a box must be complete for its shares to mean the same in every box).
In box i, p_ij is the share of its cells with label j and

    S_i  = - sum_j p_ij ln p_ij                   (natural logarithm, nats)
    S_b  = (1 / N)   sum_i S_i                     over all N boxes
    S_bb = (1 / N_b) sum_i S_i                     over the N_b boxes holding > 1 label

S_bb > ln 2 is a *sufficient* condition for a fractal boundary (Daza et al. 2016: a
smooth boundary between two basins gives boxes whose entropies average at most ln 2
as n -> 0); S_bb <= ln 2 proves nothing either way. Both depend on the box size n, so
:func:`basin_entropy` reports them for several n.

Every distinct label is its own "basin", as in Attractors.jl: "unresolved" and
"diverged" cells (and each impacting period) count as basins of their own. They are
outcomes, not noise, and hiding them would make a plane look more predictable than the
sweep found it; their shares are reported beside the measures so that a reader can see
when they dominate.

:func:`share_entropy` is what one random sampling (basin stability) supports: the
entropy H = - sum_j p_j ln p_j of the shares p_j of the outcomes over the whole sampled
volume (the box-based S_b with a single box). The local S_b needs neighbouring samples
at the scale of the boundary, which N uniform samples of a 4-D box do not give (their
spacing is (volume / N)^(1/4), a fifth of the box side at N = 1000).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

LN2 = math.log(2.0)


def encode(labels: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(codes, values): the plane's labels as 0 .. K-1 (``values[codes] == labels``)."""
    labels = np.asarray(labels)
    if labels.ndim != 2 or min(labels.shape) < 2:
        raise ValueError(f"labels: a 2-D plane of at least 2 x 2 cells is needed, got shape "
                         f"{labels.shape}")
    values, codes = np.unique(labels, return_inverse=True)
    return codes.reshape(labels.shape).astype(np.intp), values


def box_counts(codes: np.ndarray, k: int, n: int) -> np.ndarray:
    """Cells of each label in every complete n x n box: shape (boxes, k)."""
    rows, cols = (codes.shape[0] // n) * n, (codes.shape[1] // n) * n
    blocks = codes[:rows, :cols].reshape(rows // n, n, cols // n, n).transpose(0, 2, 1, 3)
    blocks = blocks.reshape(-1, n * n)
    out = np.zeros((blocks.shape[0], k), dtype=np.int64)
    for j in range(k):
        out[:, j] = np.count_nonzero(blocks == j, axis=1)
    return out


def _gibbs(counts: np.ndarray) -> np.ndarray:
    """- sum_j p_j ln p_j of each row of counts (0 ln 0 = 0)."""
    total = counts.sum(axis=-1, keepdims=True)
    p = counts / total
    with np.errstate(divide="ignore", invalid="ignore"):
        terms = np.where(p > 0, -p * np.log(np.where(p > 0, p, 1.0)), 0.0)
    return terms.sum(axis=-1)


def box_entropy(labels: np.ndarray, n: int) -> dict:
    """S_b, S_bb, the number of boxes and of boundary boxes at box size ``n`` cells.

    S_bb is NaN when no box holds two labels (no boundary at this box size)."""
    codes, values = encode(labels)
    if isinstance(n, bool) or int(n) != n or n < 2 or n > min(codes.shape):
        raise ValueError(f"box size: a whole number of cells in 2..{min(codes.shape)}, "
                         f"got {n!r}")
    counts = box_counts(codes, len(values), int(n))
    s = _gibbs(counts)
    boundary = np.count_nonzero(counts, axis=1) > 1
    nb = int(boundary.sum())
    return {"S_b": float(s.mean()), "S_bb": float(s[boundary].mean()) if nb else math.nan,
            "boxes": int(len(s)), "boundary_boxes": nb}


def default_box_sizes(shape: tuple[int, int]) -> tuple[int, ...]:
    """Box sizes 2 .. min(20, side / 4): at least four boxes along the shorter side."""
    top = max(2, min(20, min(shape) // 4))
    return tuple(range(2, top + 1))


def basin_entropy(labels: np.ndarray, box_sizes=None) -> xr.Dataset:
    """S_b and S_bb of a plane against the box size (dims ``box_size``, in cells).

    Variables: ``S_b``, ``S_bb``, ``boxes``, ``boundary_boxes``, ``fractal_boundary``
    (S_bb > ln 2: sufficient for a fractal boundary). ``box_sizes``: whole numbers of
    cells (default :func:`default_box_sizes`).
    """
    labels = np.asarray(labels)
    sizes = tuple(box_sizes) if box_sizes is not None else default_box_sizes(labels.shape)
    rows = [box_entropy(labels, n) for n in sizes]
    sbb = np.array([r["S_bb"] for r in rows])
    return xr.Dataset(
        {
            "S_b": ("box_size", [r["S_b"] for r in rows],
                    {"long_name": "basin entropy S_b", "units": "nat"}),
            "S_bb": ("box_size", sbb, {"long_name": "boundary basin entropy S_bb",
                                        "units": "nat"}),
            "boxes": ("box_size", [r["boxes"] for r in rows], {"long_name": "boxes"}),
            "boundary_boxes": ("box_size", [r["boundary_boxes"] for r in rows],
                               {"long_name": "boxes holding more than one label"}),
            "fractal_boundary": ("box_size", np.nan_to_num(sbb, nan=0.0) > LN2,
                                 {"long_name": "S_bb > ln 2 (sufficient for a fractal "
                                               "boundary)"}),
        },
        coords={"box_size": ("box_size", np.asarray(sizes, dtype=np.int64),
                             {"long_name": "box side", "units": "cells"})},
    )


def share_entropy(counts, boot: int = 2000, seed: int = 0) -> tuple[float, float, float]:
    """(H, low, high): entropy of the outcome shares of one random sampling (nats) and its
    95% bootstrap interval (percentiles of H over ``boot`` multinomial resamples of the
    same size, a fixed ``seed`` so that a result is reproducible).

    ``counts``: samples per outcome (every label its own outcome). The plug-in H is
    biased low by about (K - 1) / (2 N) for K outcomes and N samples (Miller-Madow); the
    interval comes from the same estimator and inherits that bias, small beside its width
    at N = 1000.
    """
    counts = np.asarray(counts, dtype=np.int64)
    n = int(counts.sum())
    if n == 0:
        return math.nan, math.nan, math.nan
    h = float(_gibbs(counts.astype(float)))
    rng = np.random.default_rng(seed)
    resampled = rng.multinomial(n, counts / n, size=boot).astype(float)
    lo, hi = np.percentile(_gibbs(resampled), [2.5, 97.5])
    return h, float(min(lo, h)), float(max(hi, h))
