"""Basin stability (Menck et al., Nature Physics 2013) from a sweep over random samples.

The share of samples reaching each attractor estimates its basin's share of the sampled
volume (of the full state space, and of the forcing phase when t0 is random). Reported
per non-impacting solution, for all impacting solutions together and per impacting
period, for the non-impacting sum, and for unresolved/diverged outcomes, each with a 95%
Wilson score interval (the binomial interval that stays inside [0, 1] and behaves at
shares near 0 or 1, unlike the normal approximation).

The same sampling gives the basin entropy of the shares, H = - sum_j p_j ln p_j over
the distinct outcomes (each label: every non-impacting solution, each impacting period,
unresolved, diverged), with a 95% bootstrap interval (``basin_entropy.share_entropy``):
how unpredictable the final state of one random start in the box is, ln K at most for K
outcomes. The box-wise basin entropy S_b of a plane needs neighbouring starts at the
boundary's scale, which random samples do not give; see ``basin_entropy``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from .attributes import attribute_list
from .basin_entropy import share_entropy
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
        if kind.startswith("impacting"):  # periodic, chaotic or quasi-periodic
            out.setdefault("impacting (all)", []).append(i)
        elif kind in ("pair", "body", "bodies", "unmatched", "chaotic", "quasi-periodic"):
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
                     if d == sample_dim or d in attribute_list(ds.attrs, "ic_dims")]))
    ic_dims = [d for d in label.dims if d in attribute_list(ds.attrs, "ic_dims")]
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
    return out.assign(_share_entropy(per_label))


def _share_entropy(per_label: xr.DataArray) -> dict:
    """H of the outcome shares and its 95% bootstrap interval at every grid point."""
    counts = per_label.transpose(..., "label_index")
    values = counts.values.reshape(-1, counts.sizes["label_index"])
    h = np.array([share_entropy(row) for row in values]).reshape(*counts.shape[:-1], 3)
    dims = counts.dims[:-1]
    names = (("entropy", "basin entropy of the shares H"),
             ("entropy_ci_low", "H, 95% bootstrap interval, low"),
             ("entropy_ci_high", "H, 95% bootstrap interval, high"))
    return {k: (dims, h[..., i], {"long_name": name, "units": "nat"})
            for i, (k, name) in enumerate(names)}
