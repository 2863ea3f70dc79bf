"""Which settings are safe where: label agreement and speed of candidate integrator settings
on the study's planes (figure 6(d), smooth; figures 9, 12(a), 13(a), 14(a), fractal), each
against the tight reference (dopri5 rtol 1e-11, no capture, no cells) on random points.

    .venv/bin/python benchmarks/bench_settings.py [--resolution 100] [--sample 1000]
        [--planes 6d,9,...] [--candidates NAME,...] [--spread]

Every candidate labels the whole plane as a sweep does (``sweep_in_memory``, 2 workers, so
recurrence cells see the chunk order of a real run); its wall time includes the
catalogue. ``--spread`` instead labels the reference points at tighter settings still
(rtol 1e-12, 1e-13, Rodas4): how far the reference itself is from converged, i.e. the
floor below which no setting's disagreement can be told from the reference's own.
This is the measurement behind the defaults (README, "How right is a result"); one line
per (plane, candidate) on stdout.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from _common import (
    PLANES,
    TIGHT,
    WORKERS,
    label_context,
    label_names,
    plane_scene,
    sample_points,
    tight_reference,
)

from softimpact_cli.sweep.in_memory import sweep_in_memory
from softimpact_cli.sweep.runner import prepare_inputs

CANDIDATES = {  # name -> [integrator] keys over the defaults
    "defaults": {},
    "before issue 15": dict(method="auto", rtol=1e-8, atol=1e-10, cell_size=0.0),
    "fast": dict(method="dopri5", rtol=1e-5, atol=1e-7, cell_size=0.05, cell_hits=5),
    "auto 1e-6": dict(rtol=1e-6, atol=1e-8, cell_size=0.0),
    "auto 1e-5": dict(rtol=1e-5, atol=1e-7, cell_size=0.0),
    "auto 1e-8 cells .05x5": dict(rtol=1e-8, atol=1e-10, cell_size=0.05, cell_hits=5),
    "auto 1e-8 cells .02x8": dict(rtol=1e-8, atol=1e-10, cell_size=0.02, cell_hits=8),
    "auto 1e-6 cells .05x5": dict(rtol=1e-6, atol=1e-8, cell_size=0.05, cell_hits=5),
    "auto 1e-6 cells .02x8": dict(rtol=1e-6, atol=1e-8, cell_size=0.02, cell_hits=8),
    "no capture": dict(capture_tol=0.0),
    "auto 1e-10": dict(rtol=1e-10, atol=1e-12),
    "auto 1e-9": dict(rtol=1e-9, atol=1e-11),
    "convergence 1e-9": dict(convergence_tol=1e-9),
    "dopri5 1e-8": dict(method="dopri5"),
    "exact": dict(method="exact"),
    "exact without cells": dict(method="exact", cell_size=0.0),
}
SPREAD = {  # tighter than the reference still
    "rtol 1e-12": dict(rtol=1e-12, atol=1e-14),
    "rtol 1e-13": dict(rtol=1e-13, atol=1e-15),
    "rodas4 1e-11": dict(method="rodas4"),
}


def candidate_line(name: str, resolution: int, picks, ref: list[str], cand: str) -> str:
    scene = plane_scene(name, resolution, CANDIDATES[cand])
    t = time.perf_counter()
    ds = sweep_in_memory(scene, workers=WORKERS)
    wall = time.perf_counter() - t
    got = label_names(ds)
    diff = sum(got[i] != r for i, r in zip(picks.tolist(), ref, strict=True))
    unresolved = int((ds["status"].values != 0).sum())
    return (f"{name:4s} {cand:24s} wall {wall:6.1f} s  {resolution ** 2 / wall:7.0f} ICs/s  "
            f"disagree {diff:3d}/{len(picks)}  not converged {unresolved}")


def spread_line(name: str, resolution: int, picks, ref: list[str], label: str) -> str:
    scene = plane_scene(name, resolution)
    ctx = prepare_inputs(scene, lambda s: None).context
    tighter = replace(ctx, integrator=replace(scene.integrator, **{**TIGHT, **SPREAD[label]}),
                      states=ctx.states[picks], known=None)
    labels, wall = label_context(tighter, WORKERS)
    diff = sum(a != b for a, b in zip(labels, ref, strict=True))
    return f"{name:4s} reference vs {label:14s} disagree {diff:3d}/{len(picks)} ({wall:.0f} s)"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--resolution", type=int, default=100)
    ap.add_argument("--sample", type=int, default=1000)
    ap.add_argument("--planes", default=",".join(PLANES))
    ap.add_argument("--candidates", default=",".join(CANDIDATES))
    ap.add_argument("--spread", action="store_true")
    args = ap.parse_args()
    for name in args.planes.split(","):
        picks = sample_points(args.resolution, args.sample)
        ref = tight_reference(name, args.resolution, picks)
        rows = SPREAD if args.spread else args.candidates.split(",")
        for row in rows:
            line = (spread_line if args.spread else candidate_line)(
                name, args.resolution, picks, ref, row)
            print(line, flush=True)


if __name__ == "__main__":
    main()
