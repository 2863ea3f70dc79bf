"""[analysis] kind = "tipping": where the basins and the solutions go when the parameters
jump from one point to another (``analysis.tipping``).

A sweep kind: the [initial_conditions] (a plane or random samples) at exactly two [grid]
points, the first "before" and the second "after" (``[grid] panels = [{d = 22.0}, {d =
6.0}]``); chunked, resumable and verified like basins. After the sweep it adds the
tipping probabilities (basin overlap, rows: labels before, columns: labels after, with
95% Wilson intervals) and where each solution present before goes (its section points at
t = 0 mod T labelled at the second point).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..analysis.attributes import attribute_list
from ..analysis.tipping import attractor_destinations, tipping_probabilities
from ..config.axes import is_chain
from ..config.reader import ConfigError
from ..report.compare import compare_sweeps, sweep_comparison_text
from ..report.info import sweep_summary
from ..report.outcomes import label_counts
from ..report.tipping import tipping_lines, tipping_summary
from ..sweep import label_states
from ..sweep.plan import SweepSettings
from ..sweep.result import grid_dims
from .base import AnalysisKind, PlotOption, PlotSpec, Sections
from .sweeps import KEYS, SHOW_ERROR, SWEEP_VARIABLES, _reader, check, plan, shrink
from .sweeps import sections as sweep_sections


@dataclass(frozen=True)
class TippingAnalysis(SweepSettings):
    """[analysis] kind = "tipping": a sweep over two grid points, then the tipping matrix
    and where each solution goes (``add_tipping``)."""

    @property
    def after_sweep(self):
        return add_tipping


def sections(analysis, ctx) -> Sections:
    read = sweep_sections(analysis, ctx)
    if read.grid.size != 2:
        raise ConfigError(f"{ctx.source}: [grid]: kind 'tipping' needs exactly 2 grid points "
                          f"(before and after, e.g. panels = [{{d = 22.0}}, {{d = 6.0}}]), "
                          f"got {read.grid.size}")
    return read


def add_tipping(ds, scene, catalogue):
    """The sweep's extra variables: the tipping matrix and the solutions' destinations."""
    dims = grid_dims(ds)
    ic_dims = attribute_list(ds.attrs, "ic_dims")
    label = ds["label"].transpose(*dims, *ic_dims).values.reshape(2, -1)
    codes = [int(c) for c in ds["label_code"].values]
    table = dict(zip(codes, (str(n) for n in ds["label_name"].values), strict=True))
    matrix = tipping_probabilities(label[0], label[1], table)
    present = {table[int(c)] for c in np.unique(label[0])}
    orbits = {name: o for name, o in catalogue.orbits.items() if name in present}
    after = scene.grid.point(1)
    destinations = attractor_destinations(orbits, lambda states: label_states(
        scene, after, states, 0.0))
    sources = list(destinations)
    depth = max((len(v) for v in destinations.values()), default=0)
    dest = np.full((len(sources), depth), "", dtype=object)
    for i, name in enumerate(sources):
        dest[i, :len(destinations[name])] = destinations[name]
    extra = xr.Dataset({"tip_destination": (("tip_solution", "tip_point"), dest.astype(str),
                                            {"long_name": "label after of each section "
                                                          "point of the solution before "
                                                          "('' past its period)"})},
                       coords={"tip_solution": sources})
    out = xr.merge([ds, matrix, extra], combine_attrs="override")
    out.attrs["tip_before"] = _point_text(scene, 0)
    out.attrs["tip_after"] = _point_text(scene, 1)
    return out


def _point_text(scene, index: int) -> str:
    point = scene.grid.point(index)
    pair = not is_chain(scene.system)  # a chain has no d, phi of its own
    return ", ".join(f"{a} = {v:g}" for a, v in point.items()
                     if a in scene.grid.swept or (pair and a in ("d", "phi")))


def summary(ds) -> dict:
    return {**sweep_summary(ds), "tipping": tipping_summary(ds)}


KINDS = (AnalysisKind(
    "tipping", "tipping probabilities: where basins and solutions go between two points",
    _reader("tipping", TippingAnalysis), plan, sections=sections, shrink=shrink, check=check,
    summary=summary, info_after=tipping_lines,
    outcome_counts=label_counts, compare=compare_sweeps,
    compare_text=sweep_comparison_text,
    variables=(*SWEEP_VARIABLES, "tip_probability"),
    progress_unit="trajectories",
    keys=KEYS,
    plot=PlotSpec("The tipping matrix of a tipping RESULT (and, over a plane, the basins "
                  "before and after).", complete=True,
                  options=(PlotOption("--no-basins", "no_basins", "Leave out the basin "
                                      "panels.", kind="flag"), SHOW_ERROR))),)
