"""Run a validated scene: its kind's run, timed, with provenance; the plan of a scene."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from ..config import Scene
from ..store import provenance
from ..sweep.verification import not_applicable
from . import get as kind_of

if TYPE_CHECKING:  # importing softimpact_cli imports this module: xarray only when run
    import xarray as xr


def run_scene(scene: Scene, progress=None, **options) -> xr.Dataset:
    """Run the scene's analysis (not a sweep kind: those run through ``sweep.run_sweep``)
    and return its dataset with provenance attributes.

    ``progress(total)`` may return a callable that is called with the number of units
    done (the CLI passes a tqdm bar); analyses never print. ``options`` (workers,
    scheduler, echo) go to the kinds that take them.
    """
    kind = kind_of(scene.analysis.kind)
    if kind.sweep:
        raise ValueError(f"{kind.name} is a sweep kind: run it with sweep.run_sweep")
    started = time.time()
    t0 = time.perf_counter()
    ds = kind.run(scene, progress, **{k: v for k, v in options.items() if k in kind.options})
    wall = time.perf_counter() - t0
    attrs = provenance(scene, started, time.time(), wall)
    if "parameters" in ds.attrs:  # a run that states its own parameter point (a design's
        del attrs["parameters"]   # pick) keeps it
    ds.attrs.update(attrs)

    # a kind that runs a sweep inside (fractality) keeps that sweep's verification
    ds.attrs.setdefault("verify_status", not_applicable(kind))
    return ds


def plan_text(scene: Scene, workers: int | None = None, chunk_size: int | None = None) -> str:
    """What running ``scene`` will compute, as text (``sweep --dry-run``); runs nothing."""
    lines = [kind_of(scene.analysis.kind).plan(scene, workers, chunk_size)]
    if scene.catalogue is not None:
        c = scene.catalogue
        lines.append(f"catalogue: {c.grid} x {c.grid} grid + {c.random} random initial "
                     "conditions of one body")
    lines.append(f"output: {scene.output}")
    return "\n".join(lines)
