"""What capture near known orbits costs and saves (docs/validation/numerics.md, "Capture
near known orbits"): prints, per figure scene, the label changes and the periods and CPU.

    .venv/bin/python benchmarks/bench_capture.py [--points 300] [--resolution 100]
        [--scenes 6a,6d,12a,13a,14a,14c]

On ``--points`` random points of a ``--resolution`` x ``--resolution`` plane of each scene
(t0 = 0, the seed of benchmarks/_common.sample_points), three labellings of the same
starts, as a sweep labels them (``run_chunk``, 2 workers), recurrence cells off in all:

- capture: the scene's [integrator] defaults (capture_tol 1e-2, capture_hits 3);
- full convergence: the same without capture (no known orbits);
- the tight reference: dopri5 rtol 1e-10, atol 1e-12, convergence_tol 1e-7, no capture.

One line per scene: labels capture changed, each labelling's disagreements with the
reference, the ratio of periods integrated and of the labelling's CPU (wall time of the
2-worker pool) without capture over with it.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

import numpy as np
from _common import WORKERS, load, plane_scene, sample_points

from softimpact_cli.analysis.labels import name_of
from softimpact_cli.sweep import executors
from softimpact_cli.sweep.runner import prepare_inputs

SCENES = {  # name -> (scene file, the grid panel that replaces the scene's [grid])
    "6a": ("configs/figures/fig06_duffing_basins.toml", {"d": 22.0, "phi": 0.0}),
    "6d": ("configs/demo_basins.toml", None),
    "12a": ("configs/figures/fig12_bilinear_basins.toml", {"d": 10.0, "phi": "pi"}),
    "13a": ("configs/figures/fig13_bilinear_basins.toml", {"d": 10.0, "phi": "pi"}),
    "14a": ("configs/figures/fig14ab_bilinear_impacting.toml", {"k_c": 8.0}),
    "14c": ("configs/figures/fig14cd_duffing_impacting.toml", {"c_c": 10.0}),
}
NO_CELLS = dict(cell_size=0.0)
NO_CAPTURE = dict(capture_tol=0.0, cell_size=0.0)
REFERENCE = dict(method="dopri5", rtol=1e-10, atol=1e-12, convergence_tol=1e-7,
                 capture_tol=0.0, cell_size=0.0)


def scene_plane(name: str, resolution: int):
    """Scene ``name`` (a key of SCENES) on one panel, ``resolution`` x ``resolution``, t0 = 0."""
    return plane_scene(name, resolution, planes=SCENES)


def label(ctx, integrator: dict, picks, capture: bool):
    """(label names, periods integrated per start, wall time in s) of the starts ``picks``
    of ``ctx`` with ``integrator`` keys over the scene's; known orbits only if ``capture``."""
    ctx = replace(ctx, integrator=replace(ctx.integrator, **integrator),
                  states=ctx.states[picks],
                  t0=None if ctx.t0 is None else np.asarray(ctx.t0)[picks],
                  known=ctx.known if capture else None)
    n = len(picks)
    size = max(1, -(-n // (4 * WORKERS)))
    chunks = [(i, s, min(s + size, n)) for i, s in enumerate(range(0, n, size))]
    codes, periods = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64)
    started = time.perf_counter()
    for index, result in executors.LocalExecutor(WORKERS).run(ctx, chunks):
        start = chunks[index][1]
        codes[start:start + len(result["label"])] = result["label"]
        periods[start:start + len(result["label"])] = result["periods_used"]
    wall = time.perf_counter() - started
    return [name_of(c, ctx.names) for c in codes], periods, wall


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=300)
    ap.add_argument("--resolution", type=int, default=100)
    ap.add_argument("--scenes", default=",".join(SCENES))
    args = ap.parse_args()
    print(f"load {load()}; {args.points} points per scene", flush=True)
    for name in args.scenes.split(","):
        ctx = prepare_inputs(scene_plane(name, args.resolution), lambda s: None).context
        picks = sample_points(args.resolution, args.points)
        for settings, capture in ((NO_CELLS, True), (NO_CAPTURE, False), (REFERENCE, False)):
            label(ctx, settings, picks[:2], capture)  # compiles the kernels, untimed
        captured, periods_c, wall_c = label(ctx, NO_CELLS, picks, capture=True)
        full, periods_f, wall_f = label(ctx, NO_CAPTURE, picks, capture=False)
        reference, _, _ = label(ctx, REFERENCE, picks, capture=False)
        changed = sum(a != b for a, b in zip(captured, full, strict=True))
        off_c = sum(a != b for a, b in zip(captured, reference, strict=True))
        off_f = sum(a != b for a, b in zip(full, reference, strict=True))
        print(f"{name:4s} capture changed {changed}/{len(picks)} labels; against the "
              f"reference: with capture {off_c}, without {off_f}; periods "
              f"{periods_f.sum() / periods_c.sum():.2f}x fewer, CPU "
              f"{wall_f / wall_c:.2f}x less ({wall_c:.1f} s against {wall_f:.1f} s)",
              flush=True)


if __name__ == "__main__":
    main()
