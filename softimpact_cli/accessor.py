"""``ds.si``: an xarray accessor on softimpact results, for notebooks.

::

    ds = si.run(scene)            # or si.open_result(path), xarray.open_dataset(path)
    ds.si.names()                 # {0: 'L1^1 R1-0^1', 1: 'L1^2 R1-0^2', -2: 'unresolved'}
    ds.si.shares()                # a DataFrame: label, count, share, ci_low, ci_high

It is registered on ``xarray.Dataset`` when this module is imported: by every
``softimpact_cli`` function that returns a dataset (``si.run``, ``si.sweep``,
``si.open_result``, ``si.System``'s), by importing ``softimpact_cli`` after xarray, or
explicitly (``import softimpact_cli.accessor``) before ``xarray.open_dataset``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from .analysis.stability import basin_stability
from .store.layout import memory_order

# the rows basin_stability adds beside each label (sums over labels)
GROUP_ROWS = ("impacting (all)", "non-impacting (sum)")
COLUMNS = ("label", "count", "share", "ci_low", "ci_high")


@xr.register_dataset_accessor("si")
class SoftimpactAccessor:
    """softimpact's view of a result dataset: ``ds.si.names()``, ``ds.si.shares()``."""

    def __init__(self, ds: xr.Dataset):
        self._ds = ds

    def names(self) -> dict[int, str]:
        """{label code: attractor name} of a sweep result (basins, stability, map,
        tipping), in the result's code order (``label_code``, ``label_name``)."""
        ds = self._ds
        if "label_code" not in ds or "label_name" not in ds:
            raise ValueError(f"ds.si.names: a {ds.attrs.get('analysis', 'dataset')!r} "
                             "result has no label table (label_code, label_name); sweep "
                             "results (basins, stability, map, tipping) have one")
        return {int(c): str(n) for c, n in zip(ds["label_code"].values,
                                               ds["label_name"].values, strict=True)}

    def shares(self, groups: bool = False):
        """The share of the starts reaching each attractor, with its 95% Wilson score
        interval, at every grid point of a sweep result (``analysis.stability``).

        Returns a table with a row per (grid point, label): the grid axes that vary
        between the result's points (none for one point), then ``label`` (its name),
        ``count`` (starts reaching it), ``share``, ``ci_low``, ``ci_high``; a pandas
        DataFrame when pandas imports, else a list of dicts. ``groups``: also the rows
        "impacting (all)" and "non-impacting (sum)" (sums over labels).
        """
        names = list(self.names().values())
        table = basin_stability(memory_order(self._ds))
        wanted = names + [g for g in GROUP_ROWS if groups]
        table = table.sel(group=[g for g in wanted if g in table["group"].values])
        dims = [d for d in table["share"].dims if d != "group"]
        varying = [d for d in dims if table.sizes[d] > 1]
        # coordinates along the varying dims (a panel grid's d and phi along "panel")
        axes = [str(c) for c, v in table.coords.items()
                if c != "group" and v.dims and set(v.dims) <= set(varying)]
        rows = []
        for index in np.ndindex(*(table.sizes[d] for d in dims)):
            point = table.isel(dict(zip(dims, index, strict=True)))
            where = {a: point[a].values.item() for a in axes}
            for k, label in enumerate(point["group"].values):
                rows.append({**where, "label": str(label),
                             "count": int(point["count"].values[k]),
                             **{c: float(point[c].values[k]) for c in COLUMNS[2:]}})
        try:
            import pandas as pd  # an xarray dependency; the list serves without it
        except ImportError:
            return rows
        return pd.DataFrame(rows, columns=[*axes, *COLUMNS])
