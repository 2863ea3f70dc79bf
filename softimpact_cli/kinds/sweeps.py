"""The sweep kinds: every initial condition of [initial_conditions] at every point of
[grid], classified and labelled; run chunked and resumable by ``sweep.runner``.

basins : starts on a plane (or a list); stability : random samples of the full state
(basin stability); map : coexisting solutions over two parameters, predicted from the
critical distances and found by sampling.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace

from ..analysis.maps import add_chain_map_counts, add_map_counts
from ..config.axes import GRID_AXES, catalogue_axes, every_axis, is_chain, parameter_axes
from ..config.limits import MAX_TRAJECTORIES
from ..config.reader import ConfigError, positive
from ..config.scene import thin
from ..config.sweep import read_grid, read_initial_conditions
from ..report.compare import compare_sweeps, sweep_comparison_text
from ..report.info import stability_summary as shares
from ..report.info import sweep_summary
from ..report.outcomes import label_counts
from ..sweep.check import check_sweep
from ..sweep.plan import Plan, SweepSettings, chunk_size_for
from ..sweep.result import grid_dims
from ..sweep.runner import prepare_catalogues
from .base import AnalysisKind, PlotOption, PlotSpec, Sections


@dataclass(frozen=True)
class SweepAnalysis(SweepSettings):
    """[analysis] kind = "basins" | "stability": every initial condition of
    [initial_conditions] at every point of [grid], classified and labelled."""


@dataclass(frozen=True)
class MapAnalysis(SweepSettings):
    """[analysis] kind = "map": a sweep, then the numbers of coexisting solutions at each
    point, predicted (from d_crit: it needs attractors) and found."""

    @property
    def needs_attractors(self) -> bool:
        return True

    @property
    def after_sweep(self):
        return map_counts


def _reader(kind: str, settings: type[SweepSettings] = SweepAnalysis):
    def read(sec, ctx) -> SweepSettings:
        return settings(kind=kind, label_tol=sec.number("label_tol", 1e-3, positive))
    return read


def sections(analysis, ctx) -> Sections:
    source, doc = ctx.source, ctx.doc
    grid = read_grid(source, doc, ctx.values, ctx.system.bodies, ctx.period, ctx.check_axis,
                     parameter_axes(ctx.system), chain=is_chain(ctx.system))
    initial = read_initial_conditions(source, doc, ctx.system.state_names, ctx.period,
                                      "t0" in grid.swept, "w" in grid.swept)
    total = grid.size * initial.count
    if total > MAX_TRAJECTORIES:
        raise ConfigError(f"{source}: [grid]/[initial_conditions]: {grid.size} grid points"
                          f" x {initial.count} initial conditions = {total} trajectories; "
                          f"at most {MAX_TRAJECTORIES} trajectories per sweep")
    return Sections(analysis, grid, initial, ctx.read_catalogue())


def shrink(analysis, grid, axis: int):
    """--quick: at most ``axis`` values per swept grid axis (endpoints kept; explicit
    panels stay)."""
    if grid is not None and not grid.panels:
        grid = replace(grid, axes={a: thin(v, axis) if a in grid.swept else v
                                   for a, v in grid.axes.items()})
    return analysis, grid, ""


def plan(scene, workers=None, chunk_size=None) -> str:
    size = chunk_size_for(scene, chunk_size, workers or os.cpu_count() or 1)
    return f"{scene.analysis.kind}: " + Plan(scene, size).describe()


def check(scene, sample, seed, result=None) -> dict:
    return check_sweep(scene, sample, seed, result)


def stability_summary(ds) -> dict:
    return {**sweep_summary(ds), "stability": shares(ds)}


def map_counts(ds, scene, catalogue):
    """The map's predicted and found numbers of coexisting solutions at each point (with
    each point's own attractors when the grid sweeps body parameters; a chain's: the
    products each point's stops leave, :func:`add_chain_map_counts`)."""
    if is_chain(scene.system):  # the searches come back from the catalogue cache
        return add_chain_map_counts(ds, scene.system, dict(scene.values),
                                    prepare_catalogues(scene)[0], grid_dims(ds))
    body = [a for a in scene.grid.parameters if a in catalogue_axes(scene.system)]
    lefts = None
    if body:  # the searches come back from the catalogue cache
        axes = catalogue_axes(scene.system)
        lefts = {tuple((a, v) for a, v in zip(axes, key, strict=True) if a in body):
                 list(cat.attractors) for key, cat in prepare_catalogues(scene)[0].items()}
    return add_map_counts(ds, scene.system, dict(scene.values), list(catalogue.attractors),
                          grid_dims(ds), lefts)


SHOW_ERROR = PlotOption("--show-error", "show_error", "Print the result's measured label "
                        "error (its verification line) at the foot.", kind="flag")

# what every complete sweep result holds and info, plot, compare and measure read: the
# labels, the label tables that name their codes, the grid axes (GRID_AXES)
SWEEP_VARIABLES = ("label", "label_code", "label_name", *GRID_AXES)

PLOTS = {
    "basins": PlotSpec(
        "Basins of attraction of a plane sweep RESULT, one panel per grid point.",
        options=(PlotOption("--max-panels", "max_panels", "Largest number of grid points "
                            "drawn as panels.", kind="int>=1", default=36), SHOW_ERROR),
        complete=True, accept=lambda attrs: attrs.get("ic_kind") == "plane",
        expected="a complete sweep over a plane of initial conditions"),
    "stability": PlotSpec(
        "Basin-stability curves with 95% Wilson bands of a stability RESULT.",
        options=(PlotOption("--against", "against", "Grid axis on the horizontal axis "
                            "(default: the swept one).", kind="choice",
                            choices=every_axis()), SHOW_ERROR,
                 PlotOption("--entropy", "entropy", "Also the basin entropy of the shares "
                            "H with its 95% bootstrap band (right-hand axis).",
                            kind="flag"),
                 PlotOption("--attractors", "attractors", "Also a panel with the section "
                            "points of the chaotic and quasi-periodic attractors.",
                            kind="flag")),
        complete=True),
    "map": PlotSpec("Predicted and found numbers of coexisting solutions over two "
                    "parameters.", complete=True),
}


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "label_tol": "a trajectory whose section points lie this close to a catalogue orbit takes its "
                 "label",
}

KINDS = tuple(
    AnalysisKind(name, description, _reader(name, settings), plan, sections=sections,
                 shrink=shrink, check=check, summary=summarise,
                 outcome_counts=label_counts, compare=compare_sweeps,
                 compare_text=sweep_comparison_text, keys=KEYS,
                 progress_unit="trajectories", plot=PLOTS[name], variables=SWEEP_VARIABLES)
    for name, description, summarise, settings in (
        ("basins", "the label of every start on a plane, at every [grid] point", sweep_summary,
         SweepAnalysis),
        ("stability", "basin stability: shares of random starts, 95% Wilson intervals",
         stability_summary, SweepAnalysis),
        ("map", "coexisting solutions over two parameters, predicted and found", sweep_summary,
         MapAnalysis),
    ))
