"""The chain family's speed targets (issue 32), each measured in one run with its figure.

    .venv/bin/python benchmarks/bench_chain_targets.py [--only a,b] [--periods 3000]
        [--plane 16] [--repeats 3] [--out results/bench/chain_targets.md]

Parts (``--only``, default all):
- ``presets``: figure 6(d)'s pair trajectory and figure 12(a)'s plane, each preset against
  its chain form (``bench_chain.compare``: CPU seconds, the ratio preset / chain; the
  target: the presets no slower than today, i.e. the kernels they run are the presets'
  own, measured against the chain form that would replace them);
- ``six``: a six-body chain's trajectory of 1000 periods (64 samples per period);
- ``fresh``: a model never seen before (a body count, kinks, stops and laws drawn from the
  clock) as a subprocess ``softimpact sweep`` of a trajectory after a warm install: its wall
  time (target <= 5 s) and no "compiling" line;
- ``three``: a three-body Duffing chain, basin stability N = 1000 in [-4, 4]^6 and a
  200 x 200 basin plane (x1, x2), each a sweep on 2 workers; "not available: <refusal>"
  while the kinds refuse a chain;
- ``compile``: the install's compilation from an empty ``NUMBA_CACHE_DIR``, the presets'
  kernels (duffing, bilinear) and the family's (chain) each in a fresh cache, serially
  (``python -m softimpact_cli.analysis.warmup --serial --models=...``): CPU seconds of the
  process (a loaded machine stretches wall time, not CPU time).

Writes the table to ``--out`` and prints it.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _common import ROOT, WORKERS, load, machine, write_report
from bench_chain import (
    AUTO,
    FIG6D,
    FIG12A,
    bilinear_chain,
    compare,
    cpu,
    duffing_chain,
    plane,
    trajectory,
)

from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.config.reader import ConfigError
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.runner import run_sweep
from softimpact_cli.systems import get_system
from softimpact_cli.systems.chain import ChainModel, Stop, chain_system, chain_values

PARTS = ("presets", "six", "fresh", "three", "compile")
SOFTIMPACT = ROOT / ".venv" / "bin" / "softimpact"
FRESH_SECONDS = 5.0

THREE_BODY = """\
[system]
model = "chain"
bodies = 3
c = 0.05
k1 = 1.0
k2 = 0.01
F = 1.0
w = 1.3
phi = [0.0, "5*pi/8", "5*pi/4"]

[[stop]]
between = [1, 2]
d = 2.0

[[stop]]
between = [2, 3]
d = 2.0
"""
STABILITY = """
[analysis]
kind = "stability"

[initial_conditions]
kind = "random"
box = {{ x1 = [-4.0, 4.0], v1 = [-4.0, 4.0], x2 = [-4.0, 4.0], v2 = [-4.0, 4.0], \
x3 = [-4.0, 4.0], v3 = [-4.0, 4.0] }}
n = {n}
seed = 1
"""
BASINS = """
[analysis]
kind = "basins"

[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-4.0, 4.0], [-4.0, 4.0]]
resolution = [{n}, {n}]
"""


def presets_rows(periods: int, side: int, repeats: int) -> list[tuple[str, str, str]]:
    """Figure 6(d)'s trajectory and figure 12(a)'s plane: preset vs chain form."""
    y0 = np.array([8.0, 0.0, -4.0, 0.0])
    cases = [
        (f"fig 6(d) pair trajectory, {periods} periods: preset vs chain form",
         trajectory(Problem(get_system("duffing", 2), FIG6D, AUTO), y0, periods),
         trajectory(Problem(*duffing_chain(FIG6D), AUTO), y0, periods)),
        (f"fig 12(a) plane {side} x {side} classified: preset vs chain form",
         plane(Problem(get_system("bilinear", 2), FIG12A, AUTO), side),
         plane(Problem(*bilinear_chain(FIG12A), AUTO), side)),
    ]
    rows = []
    for name, preset_run, chain_run in cases:
        best_p, best_c, same = compare(name, preset_run, chain_run, repeats)
        ratio = best_p / best_c
        verdict = ("the chain form could replace the preset" if ratio >= 0.95 else
                   "ratio < 0.95: the preset keeps its own kernels (today's), so it is not "
                   "slower than today")
        rows.append((name, f"{best_p:.3f} s vs {best_c:.3f} s CPU: ratio preset/chain "
                           f"{ratio:.2f}, {same} outcomes", verdict))
    return rows


def six_row() -> tuple[str, str, str]:
    six = ChainModel(6, stops=tuple(Stop(i, i + 1) for i in range(1, 6)))
    values = chain_values(six, 1.3, {"k2": 0.01, "F": 1.5, "phi": [0.9 * i for i in range(6)]},
                          stop_values=[{"d": 0.5}] * 5)
    problem = Problem(chain_system(six), values, AUTO)
    y0 = np.linspace(-2.0, 2.0, 12)
    record_trajectory(problem, y0, 0.0, 2, 64)  # compile / load
    seconds, traj = cpu(trajectory(problem, y0, 1000))
    return ("6-body chain (5 stops), trajectory of 1000 periods, 64 samples/period",
            f"{seconds:.2f} s CPU, {int(traj.contacts.sum())} contacts, status "
            f"{traj.status}", "measured")


def fresh_scene(rng: np.random.Generator) -> tuple[str, str]:
    """A chain with a body count, kinks, stops and laws drawn by ``rng``: (TOML, summary)."""
    bodies = int(rng.integers(2, 8))
    laws = ("paper", "no-tension", "hunt-crossley")
    lines = ["[system]", 'model = "chain"', f"bodies = {bodies}", "c = 0.05", "k1 = 1.0",
             f"k2 = {rng.uniform(0.0, 0.05):.4f}", "F = 1.0", "w = 1.3",
             f"phi = [{', '.join(f'{v:.3f}' for v in rng.uniform(0, 2 * np.pi, bodies))}]"]
    if rng.random() < 0.5:
        lines.append(f"k_x5 = {rng.uniform(0.0, 1e-3):.5f}")
    kinks = int(rng.integers(0, 3))
    for _ in range(kinks):
        side = rng.choice(["left", "right"])
        x = rng.uniform(0.5, 2.0) * (1 if side == "right" else -1)
        lines += ["", "[[kink]]", f"body = {int(rng.integers(1, bodies + 1))}",
                  f'side = "{side}"', f"x = {x:.3f}", f"k = {rng.uniform(1, 10):.3f}"]
    used = []
    for i in range(1, bodies):
        law = str(rng.choice(laws))
        used.append(law)
        lines += ["", "[[stop]]", f"between = [{i}, {i + 1}]", f"d = {rng.uniform(0.5, 2):.3f}",
                  f'law = "{law}"']
    wall_law = str(rng.choice(laws))
    used.append(wall_law)
    lines += ["", "[[stop]]", f"body = {bodies}", f"wall = {rng.uniform(1.0, 3.0):.3f}",
              'side = "right"', f'law = "{wall_law}"']
    lines += ["", "[analysis]", 'kind = "trajectory"',
              f"state = [{', '.join(f'{v:.3f}' for v in rng.uniform(-2, 2, 2 * bodies))}]",
              "periods = 200"]
    summary = (f"{bodies} bodies, {kinks} kink(s), {bodies} stops "
               f"({', '.join(sorted(set(used)))})")
    return "\n".join(lines) + "\n", summary


def fresh_row(tmp: Path) -> tuple[str, str, str]:
    """A never-seen chain's first trajectory, from the command line, after a warm install."""
    warm, _ = fresh_scene(np.random.default_rng(0))  # the install's kernels, loaded once
    (tmp / "warm.toml").write_text(warm)
    subprocess.run([str(SOFTIMPACT), "sweep", str(tmp / "warm.toml"), "-q", "--overwrite",
                    "-o", str(tmp / "warm.h5")], check=True, capture_output=True)
    text, summary = fresh_scene(np.random.default_rng(time.time_ns()))
    (tmp / "fresh.toml").write_text(text)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run([str(SOFTIMPACT), "sweep", str(tmp / "fresh.toml"), "--overwrite",
                          "-o", str(tmp / "fresh.h5")], capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    compiled = "compiling" in (run.stdout + run.stderr)
    ok = run.returncode == 0 and not compiled
    return (f"never-seen chain ({summary}): first trajectory of 200 periods, "
            "`softimpact sweep` subprocess",
            f"{wall:.2f} s wall, {seconds:.2f} s CPU (exit {run.returncode}), "
            f"{'a compiling line' if compiled else 'no compiling line'}",
            f"<= {FRESH_SECONDS:g} s: wall {'met' if ok and wall <= FRESH_SECONDS else 'NOT met'}"
            f", CPU {'met' if ok and seconds <= FRESH_SECONDS else 'NOT met'} (a loaded "
            "machine stretches the wall)")


def three_rows(tmp: Path, n_stability: int, side: int) -> list[tuple[str, str, str]]:
    """Basin stability and a basin plane of a three-body Duffing chain, as sweeps; "not
    available: <refusal>" while the kind refuses a chain."""
    rows = []
    for what, text in ((f"3-body Duffing chain, basin stability N = {n_stability} in "
                        f"[-4, 4]^6 ({WORKERS} workers)", STABILITY.format(n=n_stability)),
                       (f"3-body Duffing chain, {side} x {side} basin plane (x1, x2) "
                        f"({WORKERS} workers)", BASINS.format(n=side))):
        try:
            scene = parse_scene(THREE_BODY + text, "<bench_chain_targets>")
        except ConfigError as refusal:
            rows.append((what, f"not available: {refusal}", "after the chain's sweep kinds"))
            continue
        start = time.perf_counter()
        ds = run_sweep(scene, tmp / "three.h5", workers=WORKERS, overwrite=True)
        wall = time.perf_counter() - start
        labels = ds["label"].size if "label" in ds else "?"
        rows.append((what, f"{wall:.1f} s wall ({labels} starts, catalogue included)",
                     "measured"))
    return rows


def warmup_cpu(models: str) -> tuple[float, float]:
    """(CPU s, wall s) of the serial warm-up of ``models`` from an empty numba cache."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "softimpact_cli.analysis.warmup", "--serial",
                        f"--models={models}", "-q"], check=True, capture_output=True,
                       env={**os.environ, "NUMBA_CACHE_DIR": cache})
        wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime), wall


def compile_rows() -> list[tuple[str, str, str]]:
    rows = []
    for models, what in (("duffing,bilinear", "the presets' kernels (duffing, bilinear)"),
                         ("chain", "the chain family's kernels (every chain)")):
        seconds, wall = warmup_cpu(models)
        rows.append((f"install compile, {what}, empty cache, serial",
                     f"{seconds:.0f} s CPU ({wall:.0f} s wall)", "measured"))
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default=",".join(PARTS), help=f"parts: {', '.join(PARTS)}")
    ap.add_argument("--periods", type=int, default=3000)
    ap.add_argument("--plane", type=int, default=16, help="side of figure 12(a)'s plane")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--stability", type=int, default=1000)
    ap.add_argument("--basin-side", type=int, default=200)
    ap.add_argument("--out", default=str(ROOT / "results" / "bench" / "chain_targets.md"))
    args = ap.parse_args(argv)
    parts = args.only.split(",")
    unknown = sorted(set(parts) - set(PARTS))
    if unknown:
        ap.error(f"--only: unknown part(s) {', '.join(unknown)}; parts: {', '.join(PARTS)}")
    command = "benchmarks/bench_chain_targets.py " + " ".join(
        sys.argv[1:] if argv is None else argv)
    start_load = load()
    tmp = Path(tempfile.mkdtemp(prefix="bench_chain_targets_"))
    rows = []
    if "presets" in parts:
        rows += presets_rows(args.periods, args.plane, args.repeats)
    if "six" in parts:
        rows.append(six_row())
    if "fresh" in parts:
        rows.append(fresh_row(tmp))
    if "three" in parts:
        rows += three_rows(tmp, args.stability, args.basin_side)
    if "compile" in parts:
        rows += compile_rows()
    lines = ["# Issue 32 targets: the chain family", "",
             f"Command: `.venv/bin/python {command.strip()}`", "",
             f"Machine: {machine()}. Date: {time.strftime('%Y-%m-%d %H:%M')}. Load average "
             f"at start {start_load}, at end {load()} (a shared machine: CPU seconds where "
             "given).", "", "| target | measured | verdict |", "|---|---|---|",
             *[f"| {t} | {m} | {v} |" for t, m, v in rows], ""]
    write_report(args.out, lines)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
