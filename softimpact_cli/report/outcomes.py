"""Warnings for results that are mostly not results: too many trajectories unresolved (no
period within ``max_periods``) or diverged, or a catalogue without a single solution.

``outcome_warnings(ds, max_periods)`` reads a finished result (a sweep's labels, a
design's verified shares, a catalogue's counts) and returns the sentences to print; the
CLI prints them and, with ``--strict``, ends with STRICT_STATUS.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..kernels.codes import DIVERGED_LABEL, UNRESOLVED_LABEL

THRESHOLD = 0.05  # a share of unresolved (or diverged) trajectories worth a warning
STRICT_STATUS = 3  # exit status of --strict when a warning applies (result written)


def label_counts(ds: xr.Dataset) -> tuple[int, int, int] | None:
    """A sweep's counts: its label codes."""
    if "label" not in ds.data_vars:
        return None
    codes = ds["label"].values
    return (codes.size, int(np.count_nonzero(codes == UNRESOLVED_LABEL)),
            int(np.count_nonzero(codes == DIVERGED_LABEL)))


def design_counts(ds: xr.Dataset) -> tuple[int, int, int] | None:
    """A design's counts: its verified points' samples (rank >= 0, on the full sample)."""
    if "count" not in ds.data_vars:
        return None
    ranked = ds["rank"].values >= 0
    if not ranked.any():
        return None
    groups = [str(g) for g in ds["group"].values]
    counts = ds["count"].values[ranked]

    def total(name: str) -> int:
        return int(counts[:, groups.index(name)].sum()) if name in groups else 0

    return int(ds["n_samples"].values[ranked].sum()), total("unresolved"), total("diverged")


def outcome_warnings(ds: xr.Dataset, max_periods: int, threshold: float = THRESHOLD,
                     shares: tuple[int, int, int] | None = None) -> list[str]:
    """Sentences (no prefix) about unresolved or diverged shares above ``threshold`` and
    about an empty catalogue; empty when the result looks sound. ``shares``: the result's
    (trajectories, unresolved, diverged) as its kind counts them (``outcome_counts``;
    ``kinds.results.outcome_warnings`` passes them), None where it has none."""
    out = []
    if "attractor_name" in ds.variables and ds.sizes.get("attractor", 0) == 0:
        n = int(ds.attrs.get("n_samples", 0))
        counts = ", ".join(f"{k} {int(ds.attrs[f'count_{k}'])}"
                           for k in ("converged", "unresolved", "diverged")
                           if f"count_{k}" in ds.attrs)
        out.append(f"the catalogue found no solution among {n} initial conditions"
                   + (f" ({counts})" if counts else "")
                   + f"; raise [integrator] max_periods (now {max_periods}) or check the scene")
    if shares is None or shares[0] == 0:
        return out
    n, unresolved, diverged = shares
    what = {"unresolved": (unresolved, f"no period within max_periods = {max_periods}"),
            "diverged": (diverged, "state non-finite or beyond [integrator] divergence_bound")}
    for name, (count, why) in what.items():
        if count / n > threshold:
            out.append(f"{100.0 * count / n:.1f}% of trajectories {name} ({why}); "
                       + ("raise [integrator] max_periods or check the scene"
                          if name == "unresolved" else "check the scene's parameters"))
    return out
