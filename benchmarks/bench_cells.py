"""Recurrence cells on the 4-coordinate presets: the cost of the cell keys (issue 32 item 6).

Cell keys of states up to 4 coordinates are the packing they always were; from 5 to 16
coordinates the key is a slot of the table found by hashing (kernels/cells.py). This
measures that the 4-coordinate path did not get slower, on whatever ``softimpact_cli``
the interpreter imports, so that today's kernels and these run the same script:

    nice .venv/bin/python benchmarks/bench_cells.py [ROUNDS]
    (cd /work/main && nice .venv/bin/python /work/wt-names/benchmarks/bench_cells.py)

1. ``cell_key`` alone, called from a jitted loop as the kernels call it: ns per key of
   200 000 random pair states (a 4-coordinate key), and of 16-coordinate states (new keys:
   each claims a slot);
2. a sweep chunk with recurrence cells on: the figure 6(d) basin plane (Duffing pair,
   d = 6, 48 x 48 starts, cell_size 0.05, cell_hits 5), one chunk in this process,
   trajectories/s; labels are printed as counts so both runs can be compared.

Measured 2026-11-27 on the shared 2-core machine, load average ~10 (four other jobs),
today's kernels (e000db2, an archive in /tmp run with PYTHONPATH) and these alternating
twice, ROUNDS = 2, best of each:

    kernels   cell_key, 4 coordinates   cell_key, 16 (new cells)   figure 6(d) with cells
    today     27 ns, 5 ns               -                          407, 526 trajectories/s
    these     14 ns, 14 ns              1.7 us, 2.3 us             531, 447 trajectories/s

Same labels (2130 x code 0, 174 x code 3; 2187 by cells) in all four runs. The chunk rate
moves by +-25 % with the load between runs, in both directions: no slowdown shows; a key
is ~10 ns against ~2 ms of a trajectory.
"""

from __future__ import annotations

import inspect
import sys
import time
from dataclasses import replace

import numpy as np
from numba import njit

from softimpact_cli.kernels import cells
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.chunks import run_chunk
from softimpact_cli.sweep.runner import prepare_catalogues, sweep_context

SCENE = """
[system]
model = "duffing"
[coupling]
d = 6.0
phi = 0.0
[integrator]
cell_size = 0.05
cell_hits = 5
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [48, 48]
[catalogue]
grid = 8
random = 40
seed = 3
[output]
path = "unused.h5"
"""


@njit
def _keys_today(states, size, table):
    total = 0
    for i in range(states.shape[0]):
        total += cells.cell_key(states[i], size)
    return total


@njit
def _keys_with_table(states, size, table):
    total = 0
    for i in range(states.shape[0]):
        total += cells.cell_key(states[i], size, table)
    return total


def keys_per_second(states: np.ndarray, size: float) -> float:
    """ns per cell_key call inside a jitted loop (as the kernels call it), either signature:
    today's (y, size) or the table's (y, size, table)."""
    today = len(inspect.signature(cells.cell_key.py_func).parameters) == 2
    loop = _keys_today if today else _keys_with_table
    table = cells.new_cells()
    loop(states[:2], size, table)  # compiled before timing
    start = time.perf_counter()
    loop(states, size, table)
    return (time.perf_counter() - start) / len(states) * 1e9


def main(rounds: int) -> None:
    rng = np.random.default_rng(1)
    pair = rng.uniform(-12.0, 12.0, (200_000, 4))
    scene = parse_scene(SCENE, "bench_cells.toml")
    catalogues, names = prepare_catalogues(scene)
    ctx = sweep_context(scene, catalogues, names, None)
    n = ctx.states.shape[0]
    run_chunk(replace(ctx, states=ctx.states[:4]), 0, 4)  # compiled before timing
    best_key, best_rate = np.inf, 0.0
    for _ in range(rounds):
        best_key = min(best_key, keys_per_second(pair, 0.05))
        start = time.perf_counter()
        out = run_chunk(ctx, 0, n)
        best_rate = max(best_rate, n / (time.perf_counter() - start))
    print(f"softimpact_cli from {cells.__file__}")
    print(f"cell_key, 4 coordinates: {best_key:.0f} ns per key (best of {rounds})")
    if cells.MAX_CELL_DIM >= 16:
        wide = rng.uniform(-12.0, 12.0, (200_000, 16))
        print(f"cell_key, 16 coordinates: {keys_per_second(wide, 0.05):.0f} ns per key")
    codes, counts = np.unique(out["label"], return_counts=True)
    print(f"figure 6(d) plane with cells, {n} starts: {best_rate:.1f} trajectories/s "
          f"(best of {rounds}); labels {dict(zip(codes.tolist(), counts.tolist(), strict=True))}; "
          f"by cells {(out['captured'] == 2).sum()}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
