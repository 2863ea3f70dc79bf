"""A sweep's plan: grid points x initial conditions, flattened and cut into chunks.

Flat index ``i = point * n_ic + ic`` with grid points in C order over GRID_AXES and
initial conditions in C order over their own dims. A chunk is a contiguous range of
flat indices, so its results are slices of the final arrays.
"""

from __future__ import annotations

import os
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..config import ConfigError, Scene

# bytes per integrated initial condition in the result (label, period, periods_used,
# status, max_penetration, contacts) plus the chunk files' overhead
BYTES_PER_IC = 4 + 2 + 4 + 1 + 4 + 4 + 8


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
        return self.n_total * BYTES_PER_IC + self.n_ic * 8 * len(self.scene.system.state_names)

    def describe(self) -> str:
        g = self.scene.grid
        swept = ", ".join(f"{a} x{len(g.axes[a])}" for a in g.swept) or "one point"
        if g.panels:
            swept = f"panels over {', '.join(g.swept)}"
        return (f"plan: {self.n_points} grid points ({swept}) x {self.n_ic} initial "
                f"conditions = {self.n_total} trajectories in {self.n_chunks} chunks of "
                f"<= {self.chunk_size}; result about {_size(self.result_bytes)}")

    def check_resources(self, out: Path, source: str) -> None:
        """Refuse a result that would not fit in memory or on disk."""
        need = self.result_bytes
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
        if 3 * need > memory:
            raise ConfigError(f"{source}: [grid]/[initial_conditions]: the result needs about "
                              f"{_size(need)} (x3 while assembling), more than this machine's "
                              f"{_size(memory)} memory; reduce the grid or resolution")
        probe = out.parent if str(out.parent) else Path(".")
        while not probe.exists():
            probe = probe.parent
        free = shutil.disk_usage(probe).free
        if 2 * need > free:
            raise ConfigError(f"{source}: [output] path: the result needs about {_size(2 * need)}"
                              f" on disk while written; only {_size(free)} free at {probe}")


def _size(n: float) -> str:
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if n < 1024:
            return f"{n:.1f} {unit}"
        n /= 1024
    return f"{n:.1f} PiB"


def default_chunk_size(n_total: int, workers: int) -> int:
    """About 16 chunks per worker, between 16 and 2000 trajectories each."""
    return int(np.clip(n_total // max(1, 16 * workers), 16, 2000))
