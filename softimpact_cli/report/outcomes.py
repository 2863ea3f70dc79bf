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


def catalogue_search(ds: xr.Dataset) -> tuple[int, dict[str, int]]:
    """(initial conditions, {outcome: count}) of the result's one-body catalogue search:
    a sweep stores them as ``catalogue_n_samples`` and ``catalogue_count_*``, a
    catalogue result as ``n_samples`` and ``count_*``."""
    prefix = "catalogue_" if "catalogue_n_samples" in ds.attrs else ""
    counts = {k: int(ds.attrs[f"{prefix}count_{k}"])
              for k in ("converged", "unresolved", "diverged")
              if f"{prefix}count_{k}" in ds.attrs}
    return int(ds.attrs.get(f"{prefix}n_samples", 0)), counts


def nonperiodic_attractors(ds: xr.Dataset) -> dict[str, int]:
    """{name: trajectories} of the attractors that are not periodic the second stage named
    in a result (the "settling" sets, left unresolved, are not attractors)."""
    if "nonperiodic_code" not in ds:
        return {}
    out: dict[str, int] = {}
    for code, name, members in zip(ds["nonperiodic_code"].values, ds["nonperiodic_name"].values,
                                   ds["nonperiodic_members"].values, strict=True):
        if int(code) != UNRESOLVED_LABEL:
            out[str(name)] = out.get(str(name), 0) + int(members)
    return out


def _empty_catalogue(ds: xr.Dataset) -> bool:
    return "attractor_name" in ds.variables and ds.sizes.get("attractor", 0) == 0


def outcome_notes(ds: xr.Dataset) -> list[str]:
    """Sentences (no prefix) that explain a result without faulting it: a catalogue search
    without a periodic solution beside attractors that are not periodic, which the sweep's
    second stage found (the search runs the first pass only, so it leaves their starts
    unresolved)."""
    found = nonperiodic_attractors(ds)
    if not (_empty_catalogue(ds) and found):
        return []
    n, counts = catalogue_search(ds)
    listed = ", ".join(f"{name} ({k} trajectories)" for name, k in found.items())
    return [f"the catalogue search found no periodic solution among {n} initial conditions"
            + (f" ({', '.join(f'{k} {v}' for k, v in counts.items())})" if counts else "")
            + f"; the sweep's second stage found {len(found)} attractor"
            + ("s" if len(found) > 1 else "") + f" that {'are' if len(found) > 1 else 'is'} "
            f"not periodic: {listed}"]


def outcome_warnings(ds: xr.Dataset, max_periods: int, threshold: float = THRESHOLD,
                     shares: tuple[int, int, int] | None = None,
                     section_periods: int = 0) -> list[str]:
    """Sentences (no prefix) about unresolved or diverged shares above ``threshold`` and
    about an empty catalogue; empty when the result looks sound. ``shares``: the result's
    (trajectories, unresolved, diverged) as its kind counts them (``outcome_counts``;
    ``kinds.results.outcome_warnings`` passes them), None where it has none.
    ``section_periods``: the second stage's budget after ``max_periods`` (0: off). An
    empty catalogue beside attractors that are not periodic is no fault
    (:func:`outcome_notes` says it)."""
    out = []
    if _empty_catalogue(ds) and not nonperiodic_attractors(ds):
        n, counts = catalogue_search(ds)
        listed = ", ".join(f"{k} {v}" for k, v in counts.items())
        out.append(f"the catalogue found no solution among {n} initial conditions"
                   + (f" ({listed})" if listed else "")
                   + f"; raise [integrator] max_periods (now {max_periods}) or check the scene")
    if shares is None or shares[0] == 0:
        return out
    n, unresolved, diverged = shares
    budget = f"no period within max_periods = {max_periods}"
    advice = "raise [integrator] max_periods or check the scene"
    if section_periods > 0:
        budget += (f", nor a period or a recurrent set in section_periods = "
                   f"{section_periods} more")
        advice = "raise [integrator] max_periods or section_periods, or check the scene"
    what = {"unresolved": (unresolved, budget),
            "diverged": (diverged, "state non-finite or beyond [integrator] divergence_bound")}
    for name, (count, why) in what.items():
        if count / n > threshold:
            out.append(f"{100.0 * count / n:.1f}% of trajectories {name} ({why}); "
                       + (advice if name == "unresolved" else "check the scene's parameters"))
    return out
