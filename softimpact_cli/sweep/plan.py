"""A sweep's plan: grid points x initial conditions, flattened and cut into chunks.

Flat index ``i = point * n_ic + ic`` with grid points in C order over GRID_AXES and
initial conditions in C order over their own dims. A chunk is a contiguous range of
flat indices, so its results are slices of the final arrays.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..config import Scene
from ..config.space import OVERHEAD_BYTES, check_disk, check_memory, size_text
from .chunks import CELL_BLOCK

# bytes per trajectory of the per-trajectory variables (label, status, period, periods_used,
# contacts, max_penetration, captured, steps, stiff_steps: chunks.RESULT_FIELDS)
BYTES_PER_IC = 4 + 1 + 2 + 4 + 4 + 4 + 1 + 4 + 4
# labels assumed for the representative orbits (attractor_points: labels x grid points x
# max_orbit_period x dim floats); catalogues of the study have at most a dozen
LABELS_ESTIMATE = 16


@dataclass(frozen=True)
class SweepSettings:
    """What a sweep reads of its scene's [analysis] (``scene.analysis``): a sweep kind's
    settings give the same names, and its hooks, so that the sweep knows no kind.

    kind : the kind's name (stored as the result's ``analysis``)
    label_tol : tolerance of matching a converged orbit to the catalogue
    needs_attractors : stop before any chunk or file when the catalogue is empty
    after_sweep(ds, scene, catalogue) -> Dataset, or None : the kind's variables added to
        the labelled dataset (the map's solution counts, the tipping matrix)
    """

    kind: str
    label_tol: float = 1e-3

    @property
    def needs_attractors(self) -> bool:
        return False

    @property
    def after_sweep(self) -> Callable | None:
        return None


@dataclass(frozen=True)
class Plan:
    scene: Scene
    chunk_size: int

    @property
    def n_points(self) -> int:
        return self.scene.grid.size

    @property
    def n_ic(self) -> int:
        return self.scene.initial_conditions.count

    @property
    def n_total(self) -> int:
        return self.n_points * self.n_ic

    @property
    def n_chunks(self) -> int:
        return -(-self.n_total // self.chunk_size)

    def chunk(self, index: int) -> tuple[int, int]:
        start = index * self.chunk_size
        return start, min(start + self.chunk_size, self.n_total)

    @property
    def result_bytes(self) -> int:
        """Upper estimate of the stored result, uncompressed, counting every variable:
        the per-trajectory arrays, the coordinates, the initial states and start times of
        samples, the representative orbits, the map counts and a fixed overhead."""
        sc = self.scene
        grid, ic = sc.grid, sc.initial_conditions
        dim = len(sc.system.state_names)
        total = self.n_total * BYTES_PER_IC + OVERHEAD_BYTES
        total += 8 * (grid.size * len(grid.axes) if grid.panels
                      else sum(len(v) for v in grid.axes.values()))
        if ic.kind == "plane":
            total += 8 * sum(ic.resolution)
        else:  # sample index, initial_state, per-sample t0
            total += 8 * self.n_ic * (2 + dim)
        total += 8 * LABELS_ESTIMATE * grid.size * sc.integrator.max_orbit_period * dim
        if sc.analysis.after_sweep is not None:  # the kind's per-point variables
            total += 3 * 8 * grid.size  # (the map's predicted, found, found_nonimpacting)
        return total

    def describe(self) -> str:
        g = self.scene.grid
        swept = ", ".join(f"{a} x{len(g.axes[a])}" for a in g.swept) or "one point"
        if g.panels:
            swept = f"panels over {', '.join(g.swept)}"
        return (f"plan: {self.n_points} grid points ({swept}) x {self.n_ic} initial "
                f"conditions = {self.n_total} trajectories in {self.n_chunks} chunks of "
                f"<= {self.chunk_size}; result at most {size_text(self.result_bytes)}")

    def check_memory(self, source: str) -> None:
        """Refuse a result that would not fit in memory while assembled."""
        check_memory(self.result_bytes, f"{source}: [grid]/[initial_conditions]",
                     "reduce the grid or resolution")

    def check_resources(self, out: Path, source: str) -> None:
        """Refuse a result that would not fit in memory or on disk (estimates are upper
        bounds: the result is stored compressed). Call after ``check_writable``, which
        finds the paths that cannot be written at all."""
        self.check_memory(source)
        check_disk(out, self.result_bytes, 2, "chunk files and the final file")


def default_chunk_size(n_total: int, workers: int, block: int = 1) -> int:
    """About 16 chunks per worker, between 16 and 2000 trajectories each, rounded up to a
    multiple of ``block``."""
    size = int(np.clip(n_total // max(1, 16 * workers), 16, 2000))
    return -(-size // block) * block


def chunk_size_for(scene: Scene, given: int | None, workers: int) -> int:
    """The chunk size of a sweep: ``given`` (--chunk-size) or the default for ``workers``,
    rounded up to a multiple of CELL_BLOCK when the scene uses recurrence cells, so that
    chunks hold whole blocks and the labels do not depend on the chunk size or on the
    number of workers (``chunks.run_chunk`` starts a table at every block)."""
    block = CELL_BLOCK if scene.integrator.cell_size > 0.0 else 1
    if given:
        return -(-given // block) * block
    return default_chunk_size(scene.grid.size * scene.initial_conditions.count, workers, block)
