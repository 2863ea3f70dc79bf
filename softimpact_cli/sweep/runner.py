"""Run a sweep scene into a resumable result file."""

from __future__ import annotations

import datetime as _dt
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import xarray as xr

from ..analysis.catalogue import Catalogue, extend_catalogue, require_attractors
from ..analysis.chain_catalogue import extend_chain_catalogue
from ..analysis.critical_distance import critical_distance, uncoupled_pair
from ..config import ConfigError, Scene, forcing_period
from ..config.axes import catalogue_axes, catalogue_key
from ..config.chain_scene import CHAIN
from ..store import open_result
from ..store.catalogues import catalogue_table, scene_body_attractors, scene_chain_searches
from ..store.lock import output_lock
from ..store.provenance import command_line, history_line, provenance
from ..store.sweep_store import (
    DamagedHeader,
    DamagedPart,
    RunIdentity,
    SweepStore,
    result_problem,
)
from ..systems.base import check_bodies
from .chunks import RESULT_FIELDS, SweepContext
from .executors import make_executor
from .merge import impacting_numbering, merge_chunk
from .plan import Plan, chunk_size_for
from .result import point_survival, sweep_dataset
from .second_stage import progress_codes, relabel, unpack


def prepare_catalogues(scene: Scene, progress=None) -> tuple[dict, tuple[str, ...]]:
    """The one-body catalogue, extended to the right body at every phi of the grid; when
    the grid sweeps a body parameter (``config.axes.catalogue_axes``), one search per
    distinct value of those, since the attractors themselves change.

    Returns ({catalogue key: Catalogue} in grid order, names in code order: those of the
    first, then any new name of the others, so that a name has one code throughout).
    """
    system = scene.system
    if system.model == CHAIN:
        return chain_catalogues(scene, progress)
    check_bodies(system.bodies, "prepare_catalogues (a body or a pair's combinations)")
    searches = {}  # body parameters -> the one-body search there
    catalogues = {}
    for values in catalogue_points(scene):
        key = catalogue_key(system, values)
        if key in catalogues:
            continue
        body = tuple(float(values[a]) for a in catalogue_axes(system) if a != "phi")
        if body not in searches:
            at = replace(scene, values={**scene.values, **values})
            searches[body] = scene_body_attractors(at, progress)
        catalogues[key] = extend_catalogue(system, values, scene.integrator, *searches[body])
    names: dict[str, None] = {}
    for cat in catalogues.values():
        names.update(dict.fromkeys(cat.names))
    return catalogues, tuple(names)


def chain_catalogues(scene: Scene, progress=None) -> tuple[dict, tuple[str, ...]]:
    """:func:`prepare_catalogues` of a chain: its bodies searched (through the catalogue
    cache) once per distinct value of the axes a body's attractors depend on
    (``catalogue_axes``: not the stops'), with the products' critical values; which
    survive at each grid point is the result's ``combination_survives``
    (``result.point_survival``; the labels do not depend on it)."""
    system = scene.system
    catalogues = {}
    for values in catalogue_points(scene):
        key = catalogue_key(system, values)
        if key not in catalogues:
            at = replace(scene, values={**scene.values, **values})
            catalogues[key] = extend_chain_catalogue(system, at.values,
                                                     scene_chain_searches(at, progress))
    names: dict[str, None] = {}
    for cat in catalogues.values():
        names.update(dict.fromkeys(cat.names))
    return catalogues, tuple(names)


def catalogue_points(scene: Scene):
    """The scene's parameter values at each grid point (only the axes a catalogue depends
    on need differ; in grid order, repeats included)."""
    grid = scene.grid
    moving = [a for a in grid.swept if a in catalogue_axes(scene.system)]
    if not moving:  # one catalogue (the common case: a pair over d, k_c, c_c or t0)
        yield dict(scene.values)
        return
    for i in range(grid.size):
        point = grid.point(i)
        yield {**scene.values, **{a: point[a] for a in moving}}


def capturable_orbits(scene: Scene, catalogues: dict) -> dict | None:
    """Per catalogue key, the stable non-impacting orbits a trajectory may be captured
    by, each as (section points (q, dim) in time order, d_crit); None when capture is off.

    One body: every stable attractor (d_crit = -inf, there is no stop). A pair: every
    combination of two stable attractors with its critical distance, located on the flow
    (``analysis.critical_distance``); which of them exist depends on d, decided per grid
    point by ``SweepContext.known_orbits``.
    """
    if scene.integrator.capture_tol <= 0.0:
        return None
    if scene.system.model == CHAIN:  # each stop's critical values, not a pair's d_crit
        return chain_capturable_orbits(catalogues)
    check_bodies(scene.system.bodies, "capturable_orbits (d_crit of a pair's x1 - x2 - d)")
    axes = catalogue_axes(scene.system)
    known = {}
    for key, cat in catalogues.items():
        if scene.system.bodies == 1:
            known[key] = [(a.points, -np.inf) for a in cat.attractors if a.stable]
            continue
        values = {**scene.values, **dict(zip(axes, key, strict=True))}
        problem = uncoupled_pair(scene.system, values, values["phi"])
        known[key] = [(c.orbit, critical_distance(problem, c.orbit[0], len(c.orbit), 256)[0])
                      for c in cat.combinations if c.left.stable and c.right.stable]
    return known


def chain_capturable_orbits(catalogues: dict) -> dict:
    """:func:`capturable_orbits` of a chain: per catalogue key, its stable products (every
    body on a stable attractor: with no stop touched the bodies are uncoupled, so the
    product is a stable orbit of the chain), each as (joint section points (q, 2n),
    critical values (n_stops,)); which exist at a grid point follows from its stops
    (``SweepContext.known_orbits``)."""
    return {key: [(p.orbit, row) for p, row in zip(cat.products, cat.critical, strict=True)
                  if all(a.stable for a in p.attractors)]
            for key, cat in catalogues.items()}


def sweep_context(scene: Scene, catalogues: dict, names: tuple[str, ...],
                  t0_per_sample: np.ndarray | None) -> SweepContext:
    """What every worker needs: the scene's grid, states, catalogues and capture orbits."""
    ic = scene.initial_conditions
    if t0_per_sample is not None:
        t0 = t0_per_sample
    elif "t0" in scene.grid.swept:
        t0 = None
    else:
        t0 = np.full(ic.count, float(ic.t0))
    return SweepContext(
        model=scene.system.model, bodies=scene.system.bodies, values=dict(scene.values),
        integrator=scene.integrator, grid=scene.grid, states=ic.array(), t0=t0,
        catalogues=catalogues, names=names, label_tol=scene.analysis.label_tol,
        known=capturable_orbits(scene, catalogues), chain=scene.system.extra.get("chain"),
    )


@dataclass(frozen=True)
class SweepInputs:
    """What a sweep computes before its chunks: the catalogue per phi (``first``: the one
    the result stores), the label names, the random start times (None unless t0 is random)
    and the workers' context."""

    catalogues: dict
    names: tuple[str, ...]
    first: Catalogue
    t0_per_sample: np.ndarray | None
    context: SweepContext


def empty_catalogue_line(catalogue: Catalogue, second_stage: bool) -> str:
    """What a sweep says before its chunks when the catalogue search found no periodic
    non-impacting solution: how its starts ended, and what the labels can still be (the
    search runs the first pass only, so a chaotic attractor leaves its starts
    unresolved there, and the sweep's second stage names it)."""
    counts = ", ".join(f"{k} {v}" for k, v in catalogue.counts.items())
    later = ("impacting periodic orbits, attractors that are not periodic (the second "
             "stage names them after the last chunk), unresolved or diverged" if second_stage
             else "impacting periodic orbits, unresolved or diverged")
    return (f"catalogue: no periodic non-impacting solution among {catalogue.n_samples} "
            f"initial conditions ({counts}; the search runs the first pass only); labels "
            f"will be {later}")


def prepare_inputs(scene: Scene, echo: Callable[[str], None] = lambda s: None
                   ) -> SweepInputs:
    """The catalogues, names and worker context of a sweep scene (says what it found)."""
    catalogues, names = prepare_catalogues(scene)
    if scene.analysis.needs_attractors:  # stop before any chunk or file
        require_attractors(next(iter(catalogues.values())), scene.analysis.kind,
                           str(scene.source))
    echo(f"catalogue search: {next(iter(catalogues.values())).source}")
    echo(f"catalogue: {len(names)} solutions: {', '.join(names)}" if names else
         empty_catalogue_line(next(iter(catalogues.values())),
                              scene.integrator.section_periods > 0))
    ic = scene.initial_conditions
    t0_per_sample = None
    if ic.t0 is None:
        t0_per_sample = ic.random_t0(forcing_period(scene.values))
    context = sweep_context(scene, catalogues, names, t0_per_sample)
    return SweepInputs(catalogues, names, next(iter(catalogues.values())), t0_per_sample,
                       context)


def labelled_dataset(scene: Scene, inputs: SweepInputs, arrays: dict, orbits: dict,
                     recurrent: list | None = None) -> xr.Dataset:
    """The sweep's dataset from its flat arrays (RESULT_FIELDS, plan order) and orbits:
    labels, the kind's extra variables (``after_sweep``) and the catalogue. ``recurrent``:
    the second stage's recurrent trajectories of every chunk (``second_stage.unpack``),
    named here in flat-index order (``second_stage.relabel``: labels and orbits updated)."""
    table = relabel(inputs.context, arrays["label"], orbits, recurrent or [],
                    tuple(scene.system.state_names))
    ds = sweep_dataset(scene, arrays, orbits, inputs.names, inputs.t0_per_sample)
    if table.data_vars:
        ds = xr.merge([ds, table], combine_attrs="override", compat="override")
    after = scene.analysis.after_sweep  # the kind's hook: e.g. the map's solution counts
    if after is not None:
        ds = after(ds, scene, inputs.first)
    catalogue_vars = catalogue_table(inputs.first, scene.system, scene.integrator)
    ds = xr.merge([ds, catalogue_vars], combine_attrs="override", compat="override")
    if scene.system.model == CHAIN:  # which products survive depends on each point's stops
        ds = point_survival(ds, scene.system, dict(scene.values), inputs.catalogues)
    ds.attrs["catalogue_source"] = inputs.first.source  # "computed" or "cache <key>"
    # the search's own counts (the merge keeps the sweep's attrs): report/outcomes.py
    ds.attrs["catalogue_n_samples"] = inputs.first.n_samples
    ds.attrs.update({f"catalogue_count_{k}": v for k, v in inputs.first.counts.items()})
    return ds


MAX_ROUNDS = 4  # rounds of chunk computing (later ones redo parts lost during the run)


def _header(scene: Scene, plan: Plan, catalogue: Catalogue, started: float,
            history: str) -> xr.Dataset:
    ds = catalogue_table(catalogue, scene.system, scene.integrator)
    ds.attrs.update(provenance(scene, started, started, 0.0))
    ds.attrs.update({"complete": 0, "analysis": scene.analysis.kind, "n": plan.n_total,
                     "n_chunks": plan.n_chunks, "chunk_size": plan.chunk_size,
                     "plan": plan.describe(), "history": history})
    return ds


def _epoch(iso) -> float | None:
    """An ISO time attribute as epoch seconds (None if absent or unreadable)."""
    try:
        return _dt.datetime.fromisoformat(str(iso)).timestamp()
    except ValueError:
        return None


def _check_chunk_size(given: int | None, stored: int, out: Path) -> None:
    if given is not None and given != stored:
        raise ConfigError(f"{out}: --chunk-size {given} differs from the interrupted run's "
                          f"{stored}; resume without --chunk-size (a run keeps its chunk size)"
                          f", or pass --overwrite to start again with {given}")


def _count(n: int, what: str) -> str:
    return f"{n} {what}" + ("" if n == 1 else "s")


def _bad_parts_note(bad: dict[int, str]) -> str:
    shown = [f"chunk {i}: {why}" for i, why in sorted(bad.items())[:6]]
    if len(bad) > len(shown):
        shown.append(f"{len(bad) - len(shown)} more")
    verb = "was" if len(bad) == 1 else "were"
    return (f"resume: {_count(len(bad), 'chunk file')} {verb} damaged or foreign "
            f"({'; '.join(shown)}); recomputing {'it' if len(bad) == 1 else 'them'}")


def _assemble(store: SweepStore, plan: Plan, identity: RunIdentity, context: SweepContext
              ) -> tuple[dict, dict, dict[float, float], list]:
    """(flat arrays, orbits, {session start: its last part written}, recurrent
    trajectories) from verified parts. A part that fails verification is deleted and
    DamagedPart names it."""
    arrays = {k: np.empty(plan.n_total, dtype=t) for k, t in RESULT_FIELDS.items()}
    orbits: dict = {}
    recurrent: list = []
    sessions: dict[float, float] = {}
    numbering = impacting_numbering(context)
    for index in range(plan.n_chunks):
        start, stop = plan.chunk(index)
        try:
            chunk, meta = store.read_chunk(index, identity)
        except DamagedPart as why:
            store.drop_chunk(index)
            raise DamagedPart(f"chunk {index}: {why}") from None
        merge_chunk(arrays, orbits, numbering, context, start, stop, chunk)
        recurrent += unpack(chunk)
        first, last = float(meta["session_started"]), float(meta["written"])
        sessions[first] = max(sessions.get(first, first), last)
    return arrays, orbits, sessions, recurrent


def run_sweep(scene: Scene, out: Path, workers: int | None = None, scheduler: str | None = None,
              resume: bool = False, overwrite: bool = False, chunk_size: int | None = None,
              echo: Callable[[str], None] = lambda s: None,
              progress: Callable[[int, int], Callable[[np.ndarray], None]] | None = None,
              attrs: dict | None = None) -> xr.Dataset:
    """Run (or resume) a sweep scene into ``out``; return the complete dataset.

    ``attrs``: global attributes the complete result is written with (what a caller
    knows before the end, such as the verification's status, costs no second write).

    ``progress(total, initial)`` may return a callable fed with each chunk's label codes.
    The output is locked for the whole run: a second run on it is refused (ConfigError
    naming the holder's pid). ``resume`` verifies every chunk file and redoes the bad
    ones; with nothing to resume it starts a new run (and says so).
    """
    with output_lock(out, command_line()):
        return _run_sweep(scene, Path(out), workers, scheduler, resume, overwrite,
                          chunk_size, echo, progress, attrs or {})


def refuse_existing(out: Path, overwrite: bool) -> None:
    """ConfigError when a new run would replace the result ``out`` without --overwrite."""
    if not overwrite and SweepStore(out).exists():
        raise ConfigError(f"{out}: result exists; pass --overwrite to replace it, or "
                          "--resume to finish an interrupted run")


def _run_sweep(scene, out, workers, scheduler, resume, overwrite, chunk_size, echo, progress,
               attrs):
    session = time.time()
    store = SweepStore(out)
    executor = make_executor(workers, scheduler)
    size = chunk_size_for(scene, chunk_size, getattr(executor, "workers", 8))
    if chunk_size:  # as the run uses it (whole cell blocks), for the resume checks below
        chunk_size = size
    header = None
    if resume:
        try:
            header, damaged = store.header(), None
        except DamagedHeader as why:  # damaged: what is wrong with the header, if anything
            header, damaged = None, f"is unreadable ({why})"
        if header is not None and header.attrs.get("scene_sha256") != scene.sha256:
            raise ConfigError(f"{out}: was started from another scene (hash differs); "
                              "resume with the same scene, or --overwrite")
        if header is not None and int(header.attrs.get("complete", 0)) == 1:
            # the chunks go only once the result they belong to is checked complete
            problem = result_problem(header, Plan(scene, size).n_total)
            if problem is None:
                if not store.parts.exists():
                    raise ConfigError(f"{out}: is complete already; nothing to resume")
                store.remove_parts()
                echo(f"resume: {out} is complete; removed the chunk folder {store.parts} "
                     "that an interrupted clean-up left behind")
                return open_result(out)
            if not store.parts.exists():
                raise ConfigError(f"{out}: says it is complete but {problem}, and no chunk "
                                  "files are kept; pass --overwrite to compute it again")
            header, damaged = None, f"says it is complete but {problem}"
        if header is not None:
            size = int(header.attrs["chunk_size"])
            _check_chunk_size(chunk_size, size, out)
        elif store.parts.exists():
            stored = store.stored_chunk_size(scene.sha256)
            if stored:
                _check_chunk_size(chunk_size, stored, out)
                size = stored
            echo(f"resume: the result header {out} {damaged or 'is missing'}; rewriting it "
                 "and keeping the chunk files that verify")
        else:
            echo(f"resume: the result header {out} {damaged}; starting a new run" if damaged
                 else f"nothing to resume at {out}; starting a new run")
            resume = False
    else:
        refuse_existing(out, overwrite)
    plan = Plan(scene, size)
    plan.check_resources(out, str(scene.source))
    echo(plan.describe())
    echo(f"executor: {executor.describe()}")

    inputs = prepare_inputs(scene, echo)
    context, first = inputs.context, inputs.first
    identity = RunIdentity(scene.sha256, plan.chunk_size, plan.n_total)
    good: dict = {}
    if not resume:
        if overwrite:
            store.remove()
        header = _header(scene, plan, first, session, history_line(session))
        store.start(header)
    else:
        if header is None:  # unreadable or missing: a new one, the first start from parts
            header = _header(scene, plan, first, session, history_line(session))
        else:
            header.attrs["history"] = "\n".join(
                filter(None, [str(header.attrs.get("history", "")), history_line(session)]))
        store.write_header(header)
        if store.ensure_parts():
            echo(f"resume: the chunk folder {store.parts} was missing; recomputing every chunk")
        good, bad = store.verify(identity)
        if bad:
            echo(_bad_parts_note(bad))
        if good:
            echo(f"resuming: {len(good)} of {plan.n_chunks} chunks already done")
    tick = progress(plan.n_total, sum(plan.chunk(i)[1] - plan.chunk(i)[0] for i in good)) \
        if progress else None
    for attempt in range(MAX_ROUNDS):
        todo = [(i, *plan.chunk(i)) for i in range(plan.n_chunks) if i not in store.done()]
        if todo and attempt:
            echo(f"{_count(len(todo), 'chunk file')} went missing or broke during the run; "
                 "recomputing them")
        for index, result in (executor.run(context, todo) if todo else ()):
            if store.ensure_parts():
                echo(f"the chunk folder {store.parts} vanished during the run; recreated it")
            store.write_chunk(index, result, identity, session)
            if tick:  # codes: progress counts the unresolved and the recurrent too
                tick(progress_codes(result, plan.chunk(index)[0]))
        if len(store.done() & set(range(plan.n_chunks))) < plan.n_chunks:
            continue
        try:
            arrays, orbits, sessions, recurrent = _assemble(store, plan, identity, context)
            break
        except DamagedPart as why:
            echo(f"{why}; recomputing it")
    else:
        raise ConfigError(f"{store.parts}: chunk files keep vanishing or breaking while the "
                          "sweep runs (another program removing them?); run again with "
                          "--resume")

    ds = labelled_dataset(scene, inputs, arrays, orbits, recurrent)
    # wall time and start over every session that contributed parts (a session counts
    # until its last part written; this one until now)
    now = time.time()
    sessions[session] = now
    wall = sum(last - start for start, last in sessions.items())
    started = min(t for t in (_epoch(header.attrs.get("started")), *sessions) if t is not None)
    ds.attrs.update(provenance(scene, started, now, wall))
    ds.attrs.update({"n": plan.n_total, "n_chunks": plan.n_chunks, "chunk_size": plan.chunk_size,
                     "plan": plan.describe(), "executor": executor.describe(),
                     "resumed": int(bool(good)), "sessions": len(sessions),
                     "history": header.attrs["history"], "complete": 1})
    ds.attrs.update(attrs)
    store.finish(ds)
    return ds
