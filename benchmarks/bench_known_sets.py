"""The known-set probe of the second stage (analysis/section_follow.py, issue 31): the
trajectories/s of Ueda's stability sweep (x'' + 0.05 x' + x^3 = 7.5 sin t, 40 random
starts in [-3, 3]^2, one chunk, in this process) with the probe off (PROBE_PERIODS = 0:
the stage as before it) and on, alternating ROUNDS times so that both see the same load.

    nice .venv/bin/python benchmarks/bench_known_sets.py [ROUNDS]

Measured 2026-11-27 on the shared 2-core machine: 0.654 and 0.701 trajectories/s off,
1.353 and 1.424 on (2 rounds, loaded); 2.049 off, 4.194 on (1 round, less load): 2.0x,
labels equal (40 x chaotic A1, lambda1 +0.0885).
"""

import sys
import time

import numpy as np

from softimpact_cli.analysis import section_follow
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.in_memory import sweep_in_memory

SCENE = """
[system]
model = "duffing"
bodies = 1
c = 0.05
k1 = 0.0
k2 = 1.0
F = 7.5
w = 1.0
[analysis]
kind = "stability"
[initial_conditions]
kind = "random"
box = { x = [-3.0, 3.0], v = [-3.0, 3.0] }
n = 40
seed = 1
[catalogue]
grid = 2
random = 4
[output]
path = "results/bench_known_sets.h5"
"""


def main(rounds: int) -> None:
    scene = parse_scene(SCENE, "bench_known_sets.toml")
    default = section_follow.PROBE_PERIODS
    for r in range(rounds):
        for name, budget in (("probe off", 0), ("probe on", default)):
            section_follow.PROBE_PERIODS = budget
            marks = {}

            def progress(total, initial, marks=marks):
                marks["start"] = time.perf_counter()
                return lambda codes: marks.__setitem__("end", time.perf_counter())

            ds = sweep_in_memory(scene, workers=1, progress=progress)
            took = marks["end"] - marks["start"]
            codes, counts = np.unique(ds["label"].values, return_counts=True)
            labels = dict(zip(codes.tolist(), counts.tolist(), strict=True))
            print(f"round {r + 1}, {name}: {ds['label'].size / took:.3f} trajectories/s "
                  f"({took:.1f} s), labels {labels}, "
                  f"lambda1 {ds['nonperiodic_exponents'].values[0, 0]:+.4f}", flush=True)
    section_follow.PROBE_PERIODS = default


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2)
