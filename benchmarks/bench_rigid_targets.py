"""Issue 33's speed target: a rigid-impact basin plane against the same plane with the
stiff soft stop that approximates it, the ratio measured in one run.

    .venv/bin/python benchmarks/bench_rigid_targets.py [--size 200]
        [--out results/bench/rigid_targets.md]

The impact oscillator x'' + 2 zeta x' + x = cos(w t) (zeta = 0.05, w = 1.2) with a wall at
sigma = 1.2 A (A the free orbit's amplitude), where the free orbit and a period-1
impacting orbit coexist: a ``--size`` x ``--size`` plane of (x1, v1) in [-3, 2] x [-4, 4],
each start classified as a basin sweep classifies it (``classify_state`` with the scene's
integrator), once with ``law = "rigid"``, r = 0.8, once with the soft wall (law "paper")
k_c = 1e6, c_c = 2 zeta_c sqrt(k_c), zeta_c = -ln r / sqrt(pi^2 + ln^2 r) (a linear
spring-dashpot's restitution r), on its default integrator (the exact flow of a
piecewise-linear system) and on "auto" (dopri5 switching to rodas4 where stiff: what a
nonlinear stop law costs). CPU seconds of this process (one core), after a warm-up
that compiles or loads both kernels; the share of starts whose outcomes (status, period,
impacting or not) agree. Writes the table to ``--out`` and prints it.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np
from _common import ROOT, load, machine, write_report

from softimpact_cli.analysis.engine import Problem, classify_state
from softimpact_cli.kinds.scene import parse_scene

ZETA, W, R, K_C = 0.05, 1.2, 0.8, 1e6
AMPLITUDE = 1.0 / np.sqrt((1.0 - W * W) ** 2 + (2.0 * ZETA * W) ** 2)
SIGMA = 1.2 * AMPLITUDE
ZETA_C = -np.log(R) / np.sqrt(np.pi ** 2 + np.log(R) ** 2)


def scene_text(law: str, method: str | None = None) -> str:
    """The oscillator with a wall stop of ``law`` ("rigid" or the stiff "paper"), on the
    integrator ``method`` (None: the scene's default)."""
    keys = (f"r = {R}" if law == "rigid" else
            f"k_c = {K_C!r}\nc_c = {float(2.0 * ZETA_C * np.sqrt(K_C))!r}")
    return (f'[system]\nmodel = "chain"\nbodies = 1\nc = {2 * ZETA}\nk1 = 1.0\nF = 1.0\n'
            f'phi = "pi/2"\nw = {W}\n\n[[stop]]\nbody = 1\nwall = {float(SIGMA)!r}\n'
            f'side = "right"\nlaw = "{law}"\n{keys}\n\n'
            '[analysis]\nkind = "trajectory"\nstate = [0.0, 0.0]\nperiods = 1\n'
            + (f'\n[integrator]\nmethod = "{method}"\n' if method else ""))


def plane_starts(size: int) -> list[np.ndarray]:
    return [np.array([x, v]) for x in np.linspace(-3.0, 2.0, size)
            for v in np.linspace(-4.0, 4.0, size)]


def classify_plane(law: str, starts: list[np.ndarray], method: str | None = None
                   ) -> tuple[float, str, list[tuple]]:
    """(CPU seconds, the method run, outcomes (status, period, impacting)) of the plane
    with ``law``."""
    scene = parse_scene(scene_text(law, method), f"<bench_rigid_targets {law}>")
    problem = Problem(scene.system, scene.values, scene.integrator)
    classify_state(problem, starts[0])  # compile or load the kernel
    start = time.process_time()
    outcomes = [(c.status, c.period, c.contacts > 0)
                for c in (classify_state(problem, y) for y in starts)]
    return time.process_time() - start, scene.integrator.method, outcomes


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=200, help="side of the plane (starts: size^2)")
    ap.add_argument("--out", default=str(ROOT / "results" / "bench" / "rigid_targets.md"))
    args = ap.parse_args(argv)
    if args.size < 2:
        ap.error(f"--size: must be >= 2, got {args.size}")
    command = "benchmarks/bench_rigid_targets.py " + " ".join(
        sys.argv[1:] if argv is None else argv)
    start_load = load()
    starts = plane_starts(args.size)
    rigid_s, rigid_method, rigid = classify_plane("rigid", starts)
    what = (f"impact oscillator (w = {W}, wall 1.2 A, r = {R}), {args.size} x {args.size} "
            "basin plane (x1, v1)")
    rows = [(f"{what}: rigid stop ({rigid_method}, impacts located)", f"{rigid_s:.2f} s CPU",
             "measured")]
    # the linear soft wall is piecewise linear: its default is the exact flow, where k_c
    # costs nothing; "auto" integrates it as any nonlinear stop law would be
    for method in (None, "auto"):
        soft_s, soft_method, soft = classify_plane("paper", starts, method)
        agree = np.mean([a == b for a, b in zip(rigid, soft, strict=True)])
        rows.append((f"{what}: stiff soft stop k_c = 1e6, same restitution ({soft_method})",
                     f"{soft_s:.2f} s CPU; ratio soft / rigid {soft_s / rigid_s:.2f}; "
                     f"outcomes agree on {100 * agree:.1f}% of starts",
                     "rigid faster" if soft_s > rigid_s else "rigid NOT faster"))
    lines = ["# Issue 33 target: rigid impacts against the stiff soft stop", "",
             f"Command: `.venv/bin/python {command.strip()}`", "",
             f"Machine: {machine()}. Date: {time.strftime('%Y-%m-%d %H:%M')}. Load average "
             f"at start {start_load}, at end {load()} (a shared machine: CPU seconds).", "",
             "| target | measured | verdict |", "|---|---|---|",
             *[f"| {t} | {m} | {v} |" for t, m, v in rows], ""]
    write_report(args.out, lines)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
