"""Basin stability (Menck et al., Nature Physics 2013) from a sweep over random samples.

The share of samples reaching each attractor estimates its basin's share of the sampled
volume (of the full state space, and of the forcing phase when t0 is random). Reported
per non-impacting solution, for all impacting solutions together and per impacting
period, for the non-impacting sum, and for unresolved/diverged outcomes, each with a 95%
Wilson score interval (the binomial interval that stays inside [0, 1] and behaves at
shares near 0 or 1, unlike the normal approximation).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from .labels import parse_label

Z95 = 1.959963984540054


def wilson_interval(k: np.ndarray, n: int, z: float = Z95) -> tuple[np.ndarray, np.ndarray]:
    """95% Wilson score interval for k successes out of n (arrays broadcast)."""
    k = np.asarray(k, dtype=float)
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z / denom * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    # the interval contains p exactly; clamp so that rounding at p = 0 or 1 cannot say not
    return (np.clip(np.minimum(centre - half, p), 0.0, 1.0),
            np.clip(np.maximum(centre + half, p), 0.0, 1.0))


def groups(names: list[str]) -> dict[str, list[int]]:
    """Group label indices: each solution, 'impacting (all)', 'non-impacting (sum)'."""
    out: dict[str, list[int]] = {}
    for i, name in enumerate(names):
        out.setdefault(name, []).append(i)
        kind = parse_label(name).kind
        if kind == "impacting":
            out.setdefault("impacting (all)", []).append(i)
        elif kind in ("pair", "body", "unmatched"):
            out.setdefault("non-impacting (sum)", []).append(i)
    out.setdefault("impacting (all)", [])
    out.setdefault("non-impacting (sum)", [])
    return out


def basin_stability(ds: xr.Dataset, sample_dim: str = "sample") -> xr.Dataset:
    """Shares and Wilson intervals per group, over every grid point of a sweep result.

    Returns dims (grid dims..., group) with ``count``, ``share``, ``ci_low``, ``ci_high``.
    """
    codes = [int(c) for c in ds["label_code"].values]
    names = [str(n) for n in ds["label_name"].values]
    label = ds["label"]
    n = int(np.prod([label.sizes[d] for d in label.dims
                     if d == sample_dim or d in str(ds.attrs.get("ic_dims", "")).split()]))
    ic_dims = [d for d in label.dims if d in str(ds.attrs.get("ic_dims", "")).split()]
    per_label = xr.concat([(label == c).sum(ic_dims) for c in codes], dim="label_index")
    grouping = groups(names)
    group_names = list(grouping)
    counts = xr.concat([per_label.isel(label_index=idx).sum("label_index") if idx else
                        xr.zeros_like(per_label.isel(label_index=0))
                        for idx in grouping.values()], dim="group")
    counts = counts.assign_coords(group=np.array(group_names, dtype=object))
    lo, hi = wilson_interval(counts.values, n)
    out = xr.Dataset(
        {
            "count": counts.astype(np.int64).assign_attrs(long_name="samples reaching it"),
            "share": (counts / n).assign_attrs(long_name="basin stability (share of samples)",
                                               units="1"),
            "ci_low": (counts.dims, lo, {"long_name": "95% Wilson interval, low", "units": "1"}),
            "ci_high": (counts.dims, hi, {"long_name": "95% Wilson interval, high",
                                          "units": "1"}),
        },
        attrs={"n": n, "interval": "95% Wilson score"},
    )
    return out
