"""What does `auto` cost over plain dopri5 on the non-stiff figure scenes?

    .venv/bin/python benchmarks/bench_auto_overhead.py [--side 40] [--n 300] [--repeats 9]

`auto` takes dopri5's steps and adds a stiffness test (Hairer's, on every 16th accepted
step); on scenes without a stiff phase it never switches, so its labels must equal
dopri5's exactly. Scenes: the figure 6(d) basin (Duffing, phi = 0, d = 6, k_c = 8, c_c =
10; side x side on (x1, x2) in [-12, 12]^2) and the figure 14(c) basin-stability run
(phi = 5.28, d = 10.5; n random states in [-12, 12]^4, t0 = 0). Both run in this one
process through ``sweep.chunks.run_chunk`` (the sweep's own path, catalogue built once and
not timed), alternating the two methods ``--repeats`` times; printed: the ratio of the
minimum CPU times and the median of the back-to-back ratios (CPU time, not wall: the
machine is shared, see the load average).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from _common import load, scene_at, stability_scene  # noqa: E402  (benchmarks/ on the path)

from softimpact_cli.sweep.chunks import run_chunk  # noqa: E402
from softimpact_cli.sweep.runner import prepare_catalogues, sweep_context  # noqa: E402


def compare(name: str, scene, repeats: int) -> str:
    catalogues, names = prepare_catalogues(scene)
    base = sweep_context(scene, catalogues, names, None)
    n = base.grid.size * base.states.shape[0]
    contexts = {m: dataclasses.replace(base, integrator=dataclasses.replace(
        scene.integrator, method=m)) for m in ("dopri5", "auto")}
    run_chunk(dataclasses.replace(base, states=base.states[:2]), 0, 2)  # compile / load
    cpu = {m: [] for m in contexts}
    wall = {m: [] for m in contexts}
    out = {}
    for _ in range(repeats):
        for m, ctx in contexts.items():
            c, w = time.process_time(), time.perf_counter()
            out[m] = run_chunk(ctx, 0, n)
            cpu[m].append(time.process_time() - c)
            wall[m].append(time.perf_counter() - w)
    same = {k: bool(np.array_equal(out["auto"][k], out["dopri5"][k]))
            for k in ("label", "status", "periods_used")}
    ratio = min(cpu["auto"]) / min(cpu["dopri5"])
    paired = np.median(np.array(cpu["auto"]) / np.array(cpu["dopri5"]))
    return (f"{name}: {n} trajectories; CPU min over {repeats}: dopri5 "
            f"{min(cpu['dopri5']):.2f} s, auto {min(cpu['auto']):.2f} s, ratio {ratio:.3f} "
            f"(median of the {repeats} back-to-back ratios {paired:.3f}) "
            f"(wall min {min(wall['dopri5']):.2f} s / {min(wall['auto']):.2f} s); identical "
            f"labels, status, periods: {same}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--side", type=int, default=40)
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--append", type=Path, default=None,
                    help="also append the lines as a section to this Markdown file")
    args = ap.parse_args()
    lines = [f"load average at start {load()}"]
    print(lines[-1], flush=True)
    for name, scene in (("figure 6(d) basin", scene_at(args.side)),
                        ("figure 14(c) stability", stability_scene(args.n))):
        lines.append(compare(name, scene, args.repeats))
        print(lines[-1], flush=True)
    lines.append(f"load average at end {load()}")
    print(lines[-1])
    if args.append:
        with open(args.append, "a") as f:
            f.write("\n## `auto` against plain dopri5 on non-stiff figure scenes\n\n"
                    f"Command: `.venv/bin/python benchmarks/bench_auto_overhead.py --side "
                    f"{args.side} --n {args.n} --repeats {args.repeats}`\n\n"
                    + "\n".join(f"- {line}" for line in lines) + "\n")


if __name__ == "__main__":
    main()
