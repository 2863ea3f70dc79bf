"""Catalogues through the catalogue cache (``catalogue_cache``): the one-body search of
``analysis.catalogue`` read back bit for bit when an entry verifies, else searched and
stored. The analyses never write files; these functions are what the kinds and the sweep
call for a scene's catalogue.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..analysis.catalogue import (
    BodySearch,
    Catalogue,
    body_catalogue,
    body_problem,
    catalogue_dataset,
    catalogue_states,
    extend_catalogue,
    require_attractors,
    search_arrays,
    search_from_arrays,
    search_key_material,
)
from ..analysis.chain_catalogue import (
    ChainCatalogue,
    build_chain_catalogue,
    chain_catalogue_dataset,
    extend_chain_catalogue,
)
from ..analysis.chain_dcrit import body_problem as chain_body_problem
from ..analysis.engine import Problem
from ..config import IntegratorSettings
from ..config.chain_scene import CHAIN
from ..config.scene import forcing_period
from ..systems import System
from ..systems.base import check_bodies
from . import catalogue_cache


def scene_catalogue(scene) -> Catalogue | ChainCatalogue:
    """The [catalogue] search of a scene that needs one (dcrit, bifurcation, design...; a
    chain's: each body's, :func:`scene_chain_searches`); one line (ConfigError) and
    nothing further computed when it finds no attractor."""
    if scene.system.model == CHAIN:
        cat = extend_chain_catalogue(scene.system, dict(scene.values),
                                     scene_chain_searches(scene))
        require_attractors(cat, scene.analysis.kind, str(scene.source))
        return cat
    search = scene_body_attractors(scene)
    cat = extend_catalogue(scene.system, dict(scene.values), scene.integrator, *search)
    require_attractors(cat, scene.analysis.kind, str(scene.source))
    return cat


def with_catalogue(ds: xr.Dataset, cat: Catalogue, scene, *,
                   joints: bool = True) -> xr.Dataset:
    """A kind's result ``ds`` with the catalogue ``cat`` it was computed from merged in
    (``ds``'s attributes and values win), named after the scene's kind and with its
    forcing period T = 2 pi / w (s). ``joints=False`` leaves out the joint orbits
    (``combination_orbit`` and the ``joint_point`` dimension)."""
    table = catalogue_dataset(cat, scene.system, scene.integrator)
    if not joints:
        table = table.drop_vars(["combination_orbit"]).drop_dims("joint_point")
    ds = xr.merge([ds, table], combine_attrs="override", compat="override")
    ds.attrs["analysis"] = scene.analysis.kind
    ds.attrs["forcing_period"] = forcing_period(scene.values)
    return ds


def catalogue_table(cat: Catalogue | ChainCatalogue, system: System,
                    integrator: IntegratorSettings) -> xr.Dataset:
    """The catalogue's dataset: a preset's (``catalogue_dataset``) or a chain's
    (``chain_catalogue_dataset``)."""
    if isinstance(cat, ChainCatalogue):
        return chain_catalogue_dataset(cat, system)
    return catalogue_dataset(cat, system, integrator)


def scene_chain_searches(scene, progress=None) -> list[BodySearch]:
    """Each body of a chain scene searched alone over its [catalogue] section's initial
    conditions at t0 = 0, through the catalogue cache (in body order)."""
    c, states = scene.catalogue, catalogue_states(scene)
    return [cached_body_search(chain_body_problem(scene.system, scene.values, i,
                                                  scene.integrator), states, 0.0,
                               c.match_tol, progress)
            for i in range(1, scene.system.bodies + 1)]


def scene_body_attractors(scene, progress=None, states=None) -> BodySearch:
    """The one-body search every scene's catalogue starts from, over its [catalogue]
    section's initial conditions (``states``, when the caller drew them already) at
    t0 = 0, through the catalogue cache."""
    c = scene.catalogue
    states = catalogue_states(scene) if states is None else states
    problem = body_problem(scene.system, scene.values, scene.integrator)
    return cached_body_search(problem, states, 0.0, c.match_tol, progress)


def build_catalogue(system: System, values: dict, integrator: IntegratorSettings,
                    states: np.ndarray, t0: float = 0.0, match_tol: float = 1e-3,
                    progress=None) -> Catalogue | ChainCatalogue:
    """The full catalogue: left attractors, and for a pair the right ones and combinations;
    for a chain (``model = "chain"``) its :class:`ChainCatalogue` (each body searched
    through the cache; ``progress`` gets N ticks per body)."""
    if system.model == CHAIN:
        return build_chain_catalogue(system, values, integrator, states, t0, match_tol,
                                     progress, search=cached_body_search)
    check_bodies(system.bodies, "build_catalogue (left and right attractors)")
    problem = body_problem(system, values, integrator)
    search = cached_body_search(problem, states, t0, match_tol, progress)
    return extend_catalogue(system, values, integrator, *search)


def cached_body_search(problem: Problem, states: np.ndarray, t0: float = 0.0,
                       match_tol: float = 1e-3, progress=None) -> BodySearch:
    """:func:`body_catalogue` through the catalogue cache (``store.catalogue_cache``):
    read back bit for bit when an entry of :func:`search_key_material` verifies, else
    searched and stored. ``progress`` gets every sample at once on a hit."""
    def search() -> dict[str, np.ndarray]:
        left, counts = body_catalogue(problem, states, t0, match_tol, progress)
        return search_arrays(BodySearch(left, counts, len(states), "computed"))

    material = search_key_material(problem, states, t0, match_tol)
    arrays, source = catalogue_cache.cached(material, search)
    if progress is not None and source.startswith("cache"):
        progress(len(states))
    return search_from_arrays(arrays, source)
