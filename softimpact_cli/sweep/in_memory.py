"""Run a sweep scene in memory: the dataset its result file would hold, no file written.

The same plan, catalogue, worker context, chunks and assembly as ``runner.run_sweep``
(shared functions), so labels, periods and statuses are those of the file; what it
skips is the store (no header, no chunk files, no lock), and with it resuming. For
notebooks (``softimpact_cli.kinds.run``); long runs that should survive an interruption go
through ``run_sweep`` (``softimpact_cli.sweep`` in the API, ``softimpact sweep``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np
import xarray as xr

from ..config import Scene
from ..config.axes import GRID_AXES
from ..config.sweep import Grid, InitialConditions
from ..store.provenance import history_line, provenance
from .chunks import result_fields
from .executors import make_executor
from .merge import impacting_numbering, merge_chunk
from .plan import Plan, SweepSettings, chunk_size_for
from .runner import labelled_dataset, prepare_inputs
from .second_stage import progress_codes, unpack


def sweep_in_memory(scene: Scene, workers: int | None = None, scheduler: str | None = None,
                    chunk_size: int | None = None,
                    echo: Callable[[str], None] = lambda s: None,
                    progress: Callable[[int, int], Callable[[np.ndarray], None]] | None = None
                    ) -> xr.Dataset:
    """Run a sweep scene (basins, stability, map) and return its complete dataset.

    ``workers`` local processes (default: all cores; 1 runs here) or a Dask
    ``scheduler``; ``progress(total, initial)`` may return a callable fed with each
    chunk's label codes. The attributes are those a result file carries (``n``,
    ``plan``, ``executor``, provenance; ``resumed`` 0, one session).
    """
    started = time.time()
    t0 = time.perf_counter()
    executor = make_executor(workers, scheduler)
    size = chunk_size_for(scene, chunk_size, getattr(executor, "workers", 8))
    plan = Plan(scene, size)
    plan.check_memory(str(scene.source))
    echo(plan.describe())
    echo(f"executor: {executor.describe()}")
    inputs = prepare_inputs(scene, echo)
    arrays = {k: np.empty(plan.n_total, dtype=t)
              for k, t in result_fields(scene.system).items()}
    orbits: dict = {}
    recurrent: list = []
    numbering = impacting_numbering(inputs.context)
    tick = progress(plan.n_total, 0) if progress else None
    todo = [(i, *plan.chunk(i)) for i in range(plan.n_chunks)]
    done = {}  # merged in flat order below: impacting orbits are numbered in that order
    for index, result in executor.run(inputs.context, todo):
        done[index] = result
        if tick:
            tick(progress_codes(result, plan.chunk(index)[0]))
    for index in sorted(done):
        start, stop = plan.chunk(index)
        merge_chunk(arrays, orbits, numbering, inputs.context, start, stop, done[index])
        recurrent += unpack(done[index])
    ds = labelled_dataset(scene, inputs, arrays, orbits, recurrent)
    ds.attrs.update(provenance(scene, started, time.time(), time.perf_counter() - t0))
    ds.attrs.update({"n": plan.n_total, "n_chunks": plan.n_chunks, "chunk_size": plan.chunk_size,
                     "plan": plan.describe(), "executor": executor.describe(), "resumed": 0,
                     "sessions": 1, "history": history_line(started), "complete": 1})
    return ds


def label_states(scene: Scene, point: dict, states: np.ndarray, t0: float = 0.0,
                 workers: int | None = 1) -> list[str]:
    """Label names of ``states`` (n, dim), imposed at time ``t0``, at the parameter
    ``point`` ({axis: value} over d, phi, k_c, c_c; the scene's values elsewhere) of
    ``scene``'s system, with its integrator and [catalogue] settings: a basins sweep
    over that list of states (any kind's scene will do)."""
    values = {**scene.values, **point, "t0": float(t0)}
    grid = Grid({a: (float(values.get(a, 0.0)),) for a in GRID_AXES}, ())
    # the point's other parameters (a chain's stop.1.d, a body's F) are the scene's values
    # there: the grid above holds d, phi, k_c, c_c and t0 only
    scene = replace(scene, values={**scene.values, **{a: v for a, v in point.items()
                                                      if a in scene.values}})
    ic = InitialConditions(kind="list", state_names=tuple(scene.system.state_names),
                           states=tuple(map(tuple, np.asarray(states, float).tolist())),
                           t0=float(t0))
    analysis = SweepSettings("basins", getattr(scene.analysis, "label_tol", 1e-3))
    ds = sweep_in_memory(replace(scene, grid=grid, initial_conditions=ic,
                                 analysis=analysis), workers=workers)
    table = {int(c): str(n) for c, n in zip(ds["label_code"].values,
                                            ds["label_name"].values, strict=True)}
    return [table[int(c)] for c in ds["label"].values.ravel()]
