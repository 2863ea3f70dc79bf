"""[analysis] kind = "catalogue": the attractors of one body and the pair's combinations; on a
chain, each body's attractors, their products and which survive the stops
(``analysis.chain_catalogue``)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import ClassVar

from ..analysis.catalogue import catalogue_dataset, sample_states
from ..analysis.chain_catalogue import ChainCatalogue, chain_catalogue_dataset
from ..config.chain_scene import CHAIN
from ..config.limits import MAX_SEED
from ..config.reader import positive
from ..config.sweep import read_box
from ..report.info import catalogue_summary, format_catalogue
from ..store.catalogues import build_catalogue
from .base import AnalysisKind, PlotSpec, read_t0


@dataclass(frozen=True)
class CatalogueAnalysis:
    """[analysis] kind = "catalogue": the one-body attractors (and a pair's combinations).

    Initial conditions: a ``grid`` x ``grid`` lattice plus ``random`` uniform samples over
    ``box`` (x and v ranges), imposed at ``t0``.
    """

    kind: str
    box: Mapping[str, tuple[float, float]]
    grid: int = 16
    random: int = 200
    seed: int = 0
    t0: float = 0.0
    match_tol: float = 1e-3
    # it runs the attractor search without a [catalogue] section (the compile notice
    # counts the search's kernels: analysis.warmup)
    searches_attractors: ClassVar[bool] = True


def read(sec, ctx) -> CatalogueAnalysis:
    analysis = CatalogueAnalysis(
        kind="catalogue",
        box=read_box(sec, "box", ("x", "v"), ctx.system.extra["catalogue_box"]),
        grid=sec.integer("grid", 16, 0, 2000),
        random=sec.integer("random", 200, 0, 10_000_000),
        seed=sec.integer("seed", 0, 0, MAX_SEED),
        t0=read_t0(sec, ctx.period),
        match_tol=sec.number("match_tol", 1e-3, positive),
    )
    if analysis.grid == 0 and analysis.random == 0:
        raise sec.fail("grid", "grid and random are both 0: no initial conditions")
    return analysis


def run(scene, progress=None, **_):
    a = scene.analysis
    states = sample_states(a.box, a.grid, a.random, a.seed)
    searches = scene.system.bodies if scene.system.model == CHAIN else 1
    tick = progress(searches * len(states)) if progress else None
    cat = build_catalogue(scene.system, dict(scene.values), scene.integrator, states, a.t0,
                          a.match_tol, tick)
    if isinstance(cat, ChainCatalogue):
        return chain_catalogue_dataset(cat, scene.system)
    return catalogue_dataset(cat, scene.system, scene.integrator)


def plan(scene, workers=None, chunk_size=None) -> str:
    a = scene.analysis
    if scene.system.model == CHAIN:
        return (f"catalogue: each of the {scene.system.bodies} bodies searched alone from "
                f"{a.grid} x {a.grid} grid + {a.random} random initial conditions at t0 = "
                f"{a.t0:g}; their products, each stop's critical values")
    return (f"catalogue: {a.grid} x {a.grid} grid + {a.random} random initial conditions of "
            f"one body at t0 = {a.t0:g}")


# what each [analysis] key means (the scene-key reference)
KEYS = {
    "box": "where the starts are drawn: {x = [lo, hi], v = [lo, hi]}",
    "grid": "a grid x grid lattice of starts ...",
    "random": "... plus this many random starts",
    "seed": "seed of the random starts",
    "t0": 'the time at which the state is imposed: a number or "a*T/b" (the section stays at t = '
          '0 mod T)',
    "match_tol": "two orbits closer than this on the section are one attractor",
}

KINDS = (AnalysisKind("catalogue", "the attractors of one body and the pair's combinations",
                      read, plan, run=run, summary=catalogue_summary, report=format_catalogue,
                      progress_unit="initial conditions", keys=KEYS,
                      variables=("attractor_name", "attractor_period", "attractor_points"),
                      plot=PlotSpec("Attractors on the phase plane and one panel per "
                                    "combination of a catalogue RESULT.")),)
