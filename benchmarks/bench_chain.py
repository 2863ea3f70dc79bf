"""Speed of the chain family's kernel against the presets' specialised ones, in one process.

    .venv/bin/python benchmarks/bench_chain.py [--periods P] [--plane N] [--repeats R]

1. figure 6(d)'s pair (Duffing, d = 6, phi = 0, k_c = 8, c_c = 10): one trajectory of P
   periods from (8, 0, -4, 0) recorded (64 samples per period), preset vs its chain form;
2. figure 12(a)'s plane (bilinear, d = 10, phi = pi, w = 0.86, F = 0.518): an N x N lattice
   of (x1, x2) in [-2.5, 2.5]^2, v = 0, each start classified (``classify_state``, method
   "auto": the explicit kernels both forms share; the scene's default "exact" flow reads
   the modes' matrices, not the rhs), preset vs chain;
3. the family alone: a 6-body chain's trajectory of 1000 periods, and a 3-body chain's
   N = 1000 random starts in its 6-dimensional box classified.

CPU time (``time.process_time``, robust to the other processes of a shared machine), the
forms interleaved R times and the minimum kept. The ratio is preset time / chain time
(>= 0.95: the chain is no more than 5 % slower). Kernels are compiled by a warm-up first.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from softimpact_cli.analysis.engine import Problem, classify_state, record_trajectory  # noqa: E402
from softimpact_cli.config import IntegratorSettings  # noqa: E402
from softimpact_cli.systems import get_system  # noqa: E402
from softimpact_cli.systems.chain import (  # noqa: E402
    ChainModel,
    Kink,
    Stop,
    chain_system,
    chain_values,
)

FIG6D = {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0, "w": 1.3, "d": 6.0, "phi": 0.0,
         "k_c": 8.0, "c_c": 10.0, "law": "paper"}
FIG12A = {"c": 0.02, "k1": 1.0, "k2": 29.0, "F": 0.518, "w": 0.86, "d1": 1.26, "d": 10.0,
          "phi": np.pi, "k_c": 8.0, "c_c": 10.0, "law": "paper"}
AUTO = IntegratorSettings(method="auto", cell_size=0.0)


def duffing_chain(v):
    model = ChainModel(2, stops=(Stop(1, 2),))
    return chain_system(model), chain_values(
        model, v["w"], {"c": v["c"], "k1": v["k1"], "k2": v["k2"], "F": v["F"],
                        "phi": [0.0, v["phi"]]},
        stop_values=[{"d": v["d"], "k_c": v["k_c"], "c_c": v["c_c"]}])


def bilinear_chain(v):
    model = ChainModel(2, kinks=(Kink(1, "left"), Kink(2, "right")), stops=(Stop(1, 2),))
    return chain_system(model), chain_values(
        model, v["w"], {"c": v["c"], "k1": v["k1"], "k2": 0.0, "F": v["F"],
                        "phi": [0.0, v["phi"]]},
        kinks=[{"x": -v["d1"], "k": v["k2"]}, {"x": v["d1"], "k": v["k2"]}],
        stop_values=[{"d": v["d"], "k_c": v["k_c"], "c_c": v["c_c"]}])


def cpu(func):
    start = time.process_time()
    out = func()
    return time.process_time() - start, out


def trajectory(problem, y0, periods):
    return lambda: record_trajectory(problem, y0, 0.0, periods, 64)


def plane(problem, n):
    xs = np.linspace(-2.5, 2.5, n)
    starts = [np.array([a, 0.0, b, 0.0]) for a in xs for b in xs]
    return lambda: [(c.status, c.period) for c in (classify_state(problem, y) for y in starts)]


def compare(name, preset_run, chain_run, repeats):
    """Best CPU seconds of each form and whether their outcomes agree (printed as a row)."""
    preset_run(), chain_run()  # warm-up: compile
    best_p, best_c = np.inf, np.inf
    for _ in range(repeats):
        t_p, out_p = cpu(preset_run)
        t_c, out_c = cpu(chain_run)
        best_p, best_c = min(best_p, t_p), min(best_c, t_c)
    same = "same" if _same(out_p, out_c) else "DIFFERENT"
    print(f"| {name} | {best_p:.3f} | {best_c:.3f} | {best_p / best_c:.3f} | {same} |")
    return best_p, best_c, same


def _same(a, b):
    if isinstance(a, list):
        return a == b
    return bool(np.max(np.abs(a.section_y - b.section_y)) < 1e-6)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--periods", type=int, default=400)
    parser.add_argument("--plane", type=int, default=16)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--family", action="store_true", help="also the family alone")
    parser.add_argument("--family-only", action="store_true", help="the family alone")
    args = parser.parse_args()
    if args.family_only:
        family()
        return
    print("| case | preset CPU s | chain CPU s | ratio preset/chain | outcomes |")
    print("| --- | --- | --- | --- | --- |")
    y0 = np.array([8.0, 0.0, -4.0, 0.0])
    duffing = Problem(get_system("duffing", 2), FIG6D, AUTO)
    member = Problem(*duffing_chain(FIG6D), AUTO)
    compare(f"fig 6(d) trajectory, {args.periods} periods",
            trajectory(duffing, y0, args.periods), trajectory(member, y0, args.periods),
            args.repeats)
    bilinear = Problem(get_system("bilinear", 2), FIG12A, AUTO)
    member = Problem(*bilinear_chain(FIG12A), AUTO)
    compare(f"fig 12(a) plane {args.plane}x{args.plane}, classified",
            plane(bilinear, args.plane), plane(member, args.plane), args.repeats)
    if args.family:
        family()


def family():
    six = ChainModel(6, stops=tuple(Stop(i, i + 1) for i in range(1, 6)))
    values = chain_values(six, 1.3, {"k2": 0.01, "F": 1.5, "phi": [0.9 * i for i in range(6)]},
                          stop_values=[{"d": 0.5}] * 5)
    problem = Problem(chain_system(six), values, AUTO)
    y0 = np.linspace(-2.0, 2.0, 12)
    record_trajectory(problem, y0, 0.0, 2, 64)
    seconds, traj = cpu(trajectory(problem, y0, 1000))
    print(f"6-body chain, trajectory of 1000 periods (64 samples/period): {seconds:.2f} s CPU, "
          f"{int(traj.contacts.sum())} contacts, status {traj.status}")
    three = ChainModel(3, stops=(Stop(1, 2), Stop(2, 3)))
    values = chain_values(three, 1.3, {"k2": 0.01, "phi": [0.0, 5 * np.pi / 8, 5 * np.pi / 4]},
                          stop_values=[{"d": 2.0}] * 2)
    problem = Problem(chain_system(three), values, IntegratorSettings(cell_size=0.0))
    rng = np.random.default_rng(1)
    starts = rng.uniform(-4.0, 4.0, (1000, 6))
    classify_state(problem, starts[0])
    seconds, out = cpu(lambda: [classify_state(problem, y).period for y in starts])
    print(f"3-body chain, N = 1000 random starts in [-4, 4]^6 classified (one process): "
          f"{seconds:.2f} s CPU; periods found {sorted(set(out))}")


if __name__ == "__main__":
    main()
