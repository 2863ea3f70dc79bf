"""Minimal fatal shock: the smallest instantaneous perturbation of the state, at some
phase of a solution's orbit, that sends the system to another attractor (Klinshov,
Nekorkin and Kurths, New J. Phys. 18, 013004 (2016); Attractors.jl
``minimal_fatal_shock``).

The search: at ``M`` phases t_k = k T / M of the orbit (its states y_k), along ``N``
unit directions u (random on the sphere of the state space, Euclidean norm over
(x1, v1, x2, v2) or (x, v)), the shock magnitudes r = max_shock * (1..S) / S are
labelled first; along each direction, the first magnitude whose label is not the
solution's brackets a boundary crossing with the one before it, and bisection narrows
that bracket to ``tol``. The minimal fatal shock is the smallest bracket's upper end, a
shock verified fatal (its start is labelled otherwise); it is an upper bound of the true
minimum, which another direction, or a thinner tongue of another basin between two
scanned magnitudes, can undercut. More directions (``directions``), a finer scan
(``scan``) or more phases tighten it; ``shock_magnitude`` keeps every direction's value,
so the spread over directions shows how anisotropic the basin is.
"""

from __future__ import annotations

from collections.abc import Callable
from math import ceil, log2

import numpy as np
import xarray as xr

Labeller = Callable[[np.ndarray, int], list[str]]  # (states (n, dim), phase index) -> names


def unit_directions(n: int, dim: int, seed: int = 0) -> np.ndarray:
    """``n`` random unit vectors in R^dim, uniform on the sphere (normalised Gaussians);
    for dim = 2 and ``seed`` None, ``n`` equally spaced angles instead."""
    if dim == 2 and seed is None:
        angle = 2 * np.pi * np.arange(n) / n
        return np.column_stack([np.cos(angle), np.sin(angle)])
    g = np.random.default_rng(seed).standard_normal((n, dim))
    return g / np.linalg.norm(g, axis=1, keepdims=True)


def fatal_shocks(orbit: np.ndarray, target: str, label: Labeller, directions: np.ndarray,
                 max_shock: float, scan: int = 16, tol: float = 1e-3, tick=None
                 ) -> tuple[np.ndarray, np.ndarray]:
    """(magnitude (M, N), destination (M, N)): along each direction at each phase, the
    smallest fatal shock found (inf and "" when none up to ``max_shock``) and the label it
    leads to.

    orbit : (M, dim) states of the solution at its M phases; label(states, k) names the
    attractor each start at phase k reaches; directions : (N, dim) unit vectors;
    tick(1) : called after each phase (progress).
    """
    if not max_shock > 0 or scan < 1 or not tol > 0:
        raise ValueError(f"max_shock > 0, scan >= 1 and tol > 0 needed, got {max_shock}, "
                         f"{scan}, {tol}")
    m, n = orbit.shape[0], directions.shape[0]
    magnitude = np.full((m, n), np.inf)
    destination = np.full((m, n), "", dtype=object)
    step = max_shock / scan
    rounds = max(0, ceil(log2(step / tol)))
    for k in range(m):
        r = step * np.arange(1, scan + 1)
        starts = orbit[k][None, None, :] + r[None, :, None] * directions[:, None, :]
        names = np.array(label(starts.reshape(-1, orbit.shape[1]), k),
                         dtype=object).reshape(n, scan)
        fatal = names != target
        found = fatal.any(axis=1)
        first = np.argmax(fatal, axis=1)
        hi = np.where(found, r[first], np.inf)
        lo = np.where(found, hi - step, 0.0)
        dest = np.where(found, names[np.arange(n), first], "")
        idx = np.flatnonzero(found)
        for _ in range(rounds):
            if idx.size == 0:
                break
            mid = 0.5 * (lo[idx] + hi[idx])
            got = np.array(label(orbit[k] + mid[:, None] * directions[idx], k), dtype=object)
            away = got != target
            hi[idx[away]] = mid[away]
            dest[idx[away]] = got[away]
            lo[idx[~away]] = mid[~away]
        magnitude[k] = hi
        destination[k] = dest
        if tick is not None:
            tick(1)
    return magnitude, destination.astype(str)


def fatal_shock_dataset(orbit: np.ndarray, times: np.ndarray, target: str,
                        label: Labeller, directions: np.ndarray, max_shock: float,
                        scan: int, tol: float, variables: tuple[str, ...], tick=None
                        ) -> xr.Dataset:
    """The search as a result: every (phase, direction) value and the minimum with its
    phase, direction and destination (attributes ``mfs_*``)."""
    magnitude, destination = fatal_shocks(orbit, target, label, directions, max_shock, scan,
                                          tol, tick)
    ds = xr.Dataset(
        {"shock_magnitude": (("shock_phase", "shock_direction"), magnitude,
                             {"long_name": "smallest fatal shock found along the direction "
                                           "(inf: none up to max_shock)"}),
         "shock_destination": (("shock_phase", "shock_direction"), destination,
                               {"long_name": "label the fatal shock leads to"}),
         "direction": (("shock_direction", "variable"), directions,
                       {"long_name": "unit shock direction"}),
         "orbit_state": (("shock_phase", "variable"), orbit,
                         {"long_name": "state of the solution at the phase"})},
        coords={"shock_time": ("shock_phase", times), "variable": list(variables)},
        attrs={"analysis": "fatal_shock", "target": target, "max_shock": max_shock,
               "scan": scan, "tol": tol, "n_phases": orbit.shape[0],
               "n_directions": directions.shape[0]})
    if np.isfinite(magnitude).any():
        k, i = np.unravel_index(np.argmin(magnitude), magnitude.shape)
        ds.attrs.update(mfs=float(magnitude[k, i]), mfs_time=float(times[k]),
                        mfs_direction=directions[i].astype(float),
                        mfs_destination=str(destination[k, i]),
                        outcome=f"minimal fatal shock {magnitude[k, i]:.4g} at t = "
                                f"{times[k]:.4g} -> {destination[k, i]}")
    else:
        ds.attrs.update(mfs=np.inf, outcome=f"no fatal shock up to {max_shock:g} "
                                            f"({orbit.shape[0]} phases x "
                                            f"{directions.shape[0]} directions)")
    return ds
