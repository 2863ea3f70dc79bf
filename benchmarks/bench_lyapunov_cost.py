"""What Lyapunov exponents cost (docs/validation/lyapunov.md, "Cost"): prints the numbers.

    .venv/bin/python benchmarks/bench_lyapunov_cost.py [--repeats 3]

One core, dopri5, best of ``--repeats`` wall times after one warm-up call (the first call
of a fresh checkout compiles the variational kernels; that time is printed first):

- Ueda's oscillator (x'' + 0.05 x' + x^3 = 7.5 sin t), 2100 periods at rtol 1e-9;
- figure 14(c)'s impacting period-1 orbit of the Duffing pair (phi = 5.28, d = 10.5,
  k_c = 8, c_c = 10), refined by shooting, 220 periods at rtol 1e-10 (its switches);
- the spectrum against a plain trajectory (``engine.flow``) over 1000 periods at the same
  tolerance: the pair at c_c = 10 and c_c = 3, and Ueda's body;
- saltation at every switch against none, and 1 re-orthonormalisation a period against 8.

The 41-value c_c scan is a make target: ``time make lyapunov-fig14c-c-c``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from softimpact_cli.analysis.engine import Problem, classify_state, flow
from softimpact_cli.analysis.lyapunov import lyapunov_spectrum, refine_periodic
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems import get_system

UEDA = {"c": 0.05, "k1": 0.0, "k2": 1.0, "F": 7.5, "w": 1.0}
FIG14C = {"c": 0.05, "k1": 1.0, "k2": 0.01, "F": 1.0, "w": 1.3, "d": 10.5, "phi": 5.28,
          "k_c": 8.0, "c_c": 10.0, "law": "paper"}
FIG14C_START = np.array([-9.7384, 0.5832, 1.3324, -1.7490])
RTOL_9 = IntegratorSettings(method="dopri5", rtol=1e-9, atol=1e-11)
RTOL_10 = IntegratorSettings(method="dopri5", rtol=1e-10, atol=1e-12)
SHOOT = IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13)


def best_wall(call, repeats: int) -> tuple[float, object]:
    """The smallest wall time (s) of ``repeats`` calls, and the last call's value."""
    walls = []
    for _ in range(repeats):
        started = time.perf_counter()
        value = call()
        walls.append(time.perf_counter() - started)
    return min(walls), value


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    repeats = parser.parse_args().repeats

    ueda = Problem(get_system("duffing", 1), UEDA, RTOL_9)
    pair = get_system("duffing", 2)
    cls = classify_state(Problem(pair, FIG14C, SHOOT), FIG14C_START, 0.0)
    orbit, _, residual = refine_periodic(Problem(pair, FIG14C, SHOOT), cls.orbit[0], 0.0, 1)
    impacting = Problem(pair, FIG14C, RTOL_10)
    started = time.perf_counter()
    for problem, start in ((ueda, [2.5, 0.0]), (impacting, orbit)):
        for per_period in (1, 8):
            lyapunov_spectrum(problem, start, periods=2, transient=0, segments=1,
                              per_period=per_period)
        lyapunov_spectrum(problem, start, periods=2, transient=0, segments=1,
                          saltation=False)
        flow(problem, start, 0.0, problem.period)
    print(f"first calls (compile the variational kernels unless cached): "
          f"{time.perf_counter() - started:.1f} s")

    wall, s = best_wall(lambda: lyapunov_spectrum(ueda, [2.5, 0.0], periods=2000,
                                                  transient=100, segments=20), repeats)
    print(f"Ueda, 2100 periods at rtol 1e-9: {wall:.2f} s; exponents "
          f"{s.exponents[0]:+.4f} {s.exponents[1]:+.4f}")

    wall, s = best_wall(lambda: lyapunov_spectrum(impacting, orbit, periods=200,
                                                  transient=20, segments=10), repeats)
    print(f"fig. 14(c) impacting orbit (shooting residual {residual:.0e}), 220 periods at "
          f"rtol 1e-10: {wall:.2f} s, {s.switches} switches, "
          f"{wall / 220 * 1e3:.2f} ms a period")

    print("spectrum / plain trajectory, 1000 periods at the same tolerance:")
    cases = [("pair, c_c = 10", impacting, orbit),
             ("pair, c_c = 3", Problem(pair, {**FIG14C, "c_c": 3.0}, RTOL_10), orbit),
             ("Ueda's body", ueda, np.array([2.5, 0.0]))]
    for name, problem, start in cases:
        plain, _ = best_wall(lambda p=problem, y=start: flow(p, y, 0.0, 1000 * p.period),
                             repeats)
        spectrum, _ = best_wall(lambda p=problem, y=start: lyapunov_spectrum(
            p, y, periods=1000, transient=0, segments=10), repeats)
        print(f"  {name:15s} {spectrum:6.2f} s / {plain:6.2f} s = {spectrum / plain:4.1f}x")

    with_saltation, _ = best_wall(lambda: lyapunov_spectrum(
        impacting, orbit, periods=1000, transient=0, segments=10), repeats)
    without, _ = best_wall(lambda: lyapunov_spectrum(
        impacting, orbit, periods=1000, transient=0, segments=10, saltation=False), repeats)
    print(f"saltation at every switch (pair, 1000 periods): {with_saltation:.2f} s against "
          f"{without:.2f} s without (+{100 * (with_saltation / without - 1):.0f}%)")
    for name, problem, start in cases[::2]:
        eight, _ = best_wall(lambda p=problem, y=start: lyapunov_spectrum(
            p, y, periods=1000, transient=0, segments=10, per_period=8), repeats)
        one, _ = best_wall(lambda p=problem, y=start: lyapunov_spectrum(
            p, y, periods=1000, transient=0, segments=10, per_period=1), repeats)
        print(f"per_period 1 against 8, {name}: {one:.2f} s against {eight:.2f} s "
              f"(-{100 * (1 - one / eight):.0f}%)")


if __name__ == "__main__":
    main()
