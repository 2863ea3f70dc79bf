"""Kernel speed of this checkout against another one (say main before a refactor), as ratios.

    .venv/bin/python benchmarks/bench_refactor.py --base /path/to/other/checkout
    make bench-compare BASE=<git revision>       # checks the revision out in a temp folder

Both checkouts run in this checkout's venv (the other one's package first on PYTHONPATH,
so it imports its own sources and compiles into its own numba cache folder), in separate
processes, alternating, ``--rounds`` times; each process times the public
``engine.classify_state`` on a fixed set of initial conditions for every integration
method (no known orbits: only integration and the convergence test) and keeps its best
of ``--repeat`` passes. A ratio > 1 means this checkout is faster. The counters of every
trajectory (steps, right-hand sides, switches, ...) must agree between the checkouts: a
refactor that changes them is not a refactor, and the script says so.

Scenes: the Duffing pair of figure 6(d) (d = 6, phi = 0; mostly free flight) and the
bilinear pair of figure 12(c) (d = 1, phi = 0.36424; contact at every period), initial
conditions on a grid of their (x1, x2) plane with v1 = v2 = 0.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve()
ROOT = HERE.parents[1]

SCENES = {
    "duffing 6(d)": ("duffing", dict(d=6.0, phi=0.0, k_c=8.0, c_c=10.0), 12.0),
    "bilinear 12(c)": ("bilinear", dict(w=0.86, F=0.518, d=1.0, phi=0.36424, k_c=8.0,
                                        c_c=10.0), 2.5),
}
# method -> (integrator settings, initial conditions per side of the grid)
METHODS = {
    "auto": (dict(method="auto"), 8),
    "dopri5": (dict(method="dopri5"), 8),
    "rodas4": (dict(method="rodas4"), 4),
    "rk4 located T/1440": (dict(method="rk4", steps_per_period=1440), 3),
    "rk4 plain T/1440": (dict(method="rk4", steps_per_period=1440, locate_switches=False), 3),
}


def measure(repeat: int) -> dict:
    """In the checkout on sys.path: {scene/method: [best seconds, counters of every IC]}."""
    from softimpact_cli.analysis.engine import Problem, classify_state
    from softimpact_cli.config import IntegratorSettings
    from softimpact_cli.systems import get_system

    out = {}
    for scene, (model, values, half) in SCENES.items():
        system = get_system(model, 2)
        for method, (settings, side) in METHODS.items():
            problem = Problem(system, {**system.defaults(), **values},
                              IntegratorSettings(**settings))
            axis = np.linspace(-half, half, side)
            states = [[x1, 0.0, x2, 0.0] for x1 in axis for x2 in axis]
            classify_state(problem, states[0])  # compile or load from the cache
            best, counters = np.inf, None
            for _ in range(repeat):
                t = time.perf_counter()
                runs = [classify_state(problem, s) for s in states]
                best = min(best, time.perf_counter() - t)
                counters = [[r.status, r.period, *r.counters.values()] for r in runs]
            out[f"{scene} / {method}"] = [best, counters]
    return out


def run_in(checkout: Path | None, repeat: int) -> dict:
    """``measure`` in a fresh process importing the package of ``checkout`` (None: this)."""
    env = dict(os.environ)
    if checkout is not None:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(checkout),
                                                          env.get("PYTHONPATH")]))
    cmd = [sys.executable, str(HERE), "--worker", "--repeat", str(repeat)]
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True,
                          cwd=checkout or ROOT)
    return json.loads(done.stdout.splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", type=Path, help="the other checkout (its root folder)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        import softimpact_cli

        print(f"package: {Path(softimpact_cli.__file__).parent}", file=sys.stderr)
        print(json.dumps(measure(args.repeat)))
        return
    if args.base is None:
        parser.error("--base is required")
    base_pkg = run_in(args.base.resolve(), 1)  # warm both caches before timing
    this_pkg = run_in(None, 1)
    best = {"base": {}, "this": {}}
    for _ in range(args.rounds):
        for who, where in (("base", args.base.resolve()), ("this", None)):
            for key, (seconds, _) in run_in(where, args.repeat).items():
                best[who][key] = min(seconds, best[who].get(key, np.inf))
    print(f"load average {os.getloadavg()[0]:.2f}; base {args.base}; best of "
          f"{args.rounds} x {args.repeat} passes\n")
    print("| scene / method | base s | this s | speed ratio | counters |")
    print("|---|---:|---:|---:|---|")
    ratios = []
    for key in best["this"]:
        b, t = best["base"][key], best["this"][key]
        same = "identical" if base_pkg[key][1] == this_pkg[key][1] else "DIFFER"
        ratios.append(b / t)
        print(f"| {key} | {b:.3f} | {t:.3f} | {b / t:.3f} | {same} |")
    print(f"\ngeometric mean of the ratios: {np.exp(np.mean(np.log(ratios))):.3f}; "
          f"lowest {min(ratios):.3f}")


if __name__ == "__main__":
    main()
