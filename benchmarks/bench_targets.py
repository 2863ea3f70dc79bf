"""The speed and accuracy targets of the defaults (issue 15), measured in one run, each
beside the settings before it, the study's method and a scipy loop, as ratios.

    .venv/bin/python benchmarks/bench_targets.py [--resolution 500] [--fractal-resolution 100]
        [--sample 1000] [--cold]

Per plane (figure 6(d) at --resolution, the fractal planes of figures 9, 12(a), 13(a),
14(a) at --fractal-resolution): a whole-plane sweep (2 workers) at today's defaults as
``softimpact sweep`` runs it (tolerance pilot, sweep, verification and any redo, all in
its wall) and at the settings before issue 15 (auto, rtol 1e-8, capture, no cells; the
sweep alone), each against the tight reference on --sample random points (cached); the
study's method (RK4 T/1440, no switch location, 1000 periods) on 40 of those points and a
scipy ``solve_ivp`` loop on 10, as ratios. Then: figure 14(c) basin stability with
N = 1000 (warm), a 10 x 10 basin sweep from the command line (warm), the fixed cost of a
repeated sweep, the integrator's cost over bare right-hand sides, and with --cold the
kernel compilation from an empty numba cache. Writes results/bench/targets.md.
"""

from __future__ import annotations

import argparse
import functools
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import (
    FRACTAL_PLANES,
    ROOT,
    WORKERS,
    fmt_time,
    label_names,
    load,
    machine,
    plane_scene,
    sample_points,
    stability_scene,
    tight_reference,
    write_report,
)
from bench_basin import timed_pool
from scipy_contestant import scipy_label
from study_method import StudyMethod
from where_time_goes import StageClock, rhs_floor

from softimpact_cli.config.axes import catalogue_key
from softimpact_cli.sweep.runner import prepare_catalogues, run_sweep
from softimpact_cli.sweep.verification import sweep_verified

BEFORE = dict(method="auto", rtol=1e-8, atol=1e-10, capture_tol=1e-2, capture_hits=3,
              cell_size=0.0, convergence_tol=1e-6)  # the defaults until issue 15
STUDY_SAMPLE, SCIPY_SAMPLE = 40, 10


def agreement(got: list[str], picks, ref: list[str]) -> tuple[int, int]:
    same = sum(got[i] == r for i, r in zip(picks.tolist(), ref, strict=True))
    return same, len(ref)


def sweep_row(scene, tmp: Path, picks, ref, verified: bool = False) -> dict:
    """Whole-plane sweep: ICs/s and agreement at the sample points. ``verified``: as
    ``softimpact sweep`` runs it (tolerance pilot, sweep, verification and any redo), the
    wall including all of it."""
    t = time.perf_counter()
    if verified:
        ds = sweep_verified(scene, tmp / "plane.h5", workers=WORKERS, overwrite=True)
    else:
        ds = run_sweep(scene, tmp / "plane.h5", workers=WORKERS, overwrite=True)
    wall = time.perf_counter() - t
    same, n = agreement(label_names(ds), picks, ref)
    n_total = ds["label"].size
    verify = {k[len("verify_"):]: v for k, v in ds.attrs.items() if k.startswith("verify_")}
    return {"rate": n_total / wall, "wall": wall, "same": same, "n": n, "verify": verify,
            "pilot": str(ds.attrs.get("pilot_status", "")),
            "pilot_wall": float(ds.attrs.get("pilot_wall_s", 0.0))}


def sample_row(label, states, picks, ref) -> dict:
    """A per-point contestant on the first points of the sample (a 2-process pool)."""
    got, wall = timed_pool(label, states)
    same = sum(a == b for a, b in zip(got, ref[: len(got)], strict=True))
    return {"rate": len(got) / wall, "same": same, "n": len(got)}


def plane_rows(name: str, resolution: int, sample: int, tmp: Path) -> dict:
    print(f"\n[figure {name}] {resolution} x {resolution}", flush=True)
    picks = sample_points(resolution, sample)
    ref = tight_reference(name, resolution, picks)
    rows = {}
    for key, keys in (("defaults", {}), ("before", BEFORE)):
        rows[key] = sweep_row(plane_scene(name, resolution, keys), tmp, picks, ref,
                              verified=key == "defaults")
        print(f"    {key}: {rows[key]['rate']:.0f} ICs/s, agreement "
              f"{rows[key]['same']}/{rows[key]['n']}", flush=True)
    scene = plane_scene(name, resolution, BEFORE)
    catalogues, _ = prepare_catalogues(scene)
    catalogue = catalogues[catalogue_key(scene.system, scene.values)]
    states = scene.initial_conditions.array()[picks]
    study = StudyMethod.of(scene, catalogue)
    rows["study"] = sample_row(study.label, states[:STUDY_SAMPLE], picks, ref)
    rows["scipy"] = sample_row(functools.partial(
        scipy_label, values=dict(scene.values), catalogue=catalogue,
        tol=scene.analysis.label_tol, model=scene.system.model, bodies=scene.system.bodies),
        states[:SCIPY_SAMPLE], picks, ref)
    return rows


def cli_sweep_wall(tmp: Path) -> tuple[float, float]:
    """Wall of `softimpact sweep` on a 10 x 10 basin, first and second run (warm kernels)."""
    cmd = [str(ROOT / ".venv" / "bin" / "softimpact"), "sweep",
           str(ROOT / "configs" / "demo_basins.toml"), "--resolution", "10", "-q",
           "--workers", "1", "--overwrite", "-o", str(tmp / "ten.h5")]
    walls = []
    for _ in range(2):
        t = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        walls.append(time.perf_counter() - t)
    return walls[0], walls[1]


def repeated_fixed_cost(tmp: Path) -> float:
    """Seconds from the executor line to the catalogue line of a repeated small sweep."""
    scene = plane_scene("6d", 10)
    run_sweep(scene, tmp / "first.h5", workers=1, overwrite=True)
    clock = StageClock()
    run_sweep(scene, tmp / "second.h5", workers=1, overwrite=True, echo=clock)
    return clock.catalogue_s()


def stability_wall(tmp: Path) -> float:
    scene = stability_scene(1000)
    run_sweep(scene, tmp / "s1.h5", workers=WORKERS, overwrite=True)
    t = time.perf_counter()
    run_sweep(scene, tmp / "s2.h5", workers=WORKERS, overwrite=True)
    return time.perf_counter() - t


def cold_compile() -> float:
    """Wall of the kernel warm-up from an empty numba cache, in a fresh process."""
    with tempfile.TemporaryDirectory() as cache:
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "softimpact_cli.analysis.warmup"], check=True,
                       env={**os.environ, "NUMBA_CACHE_DIR": cache}, capture_output=True)
        return time.perf_counter() - t


def compiled_at_install() -> bool:
    """Whether ``make install`` runs the kernel warm-up (its recipe, read from the Makefile)."""
    text = (ROOT / "Makefile").read_text()
    recipe = text.split("$(STAMP): pyproject.toml", 1)[-1].split("\n\n", 1)[0]
    return "softimpact_cli.analysis.warmup" in recipe


def pct(same: int, n: int) -> str:
    return f"{100 * same / n:.1f} % ({same}/{n})"


def plane_table(name: str, rows: dict, n_grid: int) -> list[str]:
    before = rows["before"]["rate"]
    out = [f"| {name} | {key} | {r['rate']:.1f} | {fmt_time(n_grid / r['rate'])} | "
           f"{r['rate'] / before:.2f}x | {pct(r['same'], r['n'])} |"
           for key, r in rows.items()]
    d = rows["defaults"]
    v = d["verify"]
    if v:
        out.append(f"| {name} | defaults' own verification | | {fmt_time(v['wall_s'])} | | "
                   f"{v.get('status', '?')}: {v.get('disagreements', '?')}/"
                   f"{v.get('sample', '?')} disagree, {v.get('rungs', 0)} redo(s) |")
    if d["pilot"]:
        out.append(f"| {name} | defaults' tolerance pilot | | {fmt_time(d['pilot_wall'])} "
                   f"| | {d['pilot']} |")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--resolution", type=int, default=500)
    ap.add_argument("--fractal-resolution", type=int, default=100)
    ap.add_argument("--sample", type=int, default=1000)
    ap.add_argument("--planes", default="6d," + ",".join(FRACTAL_PLANES))
    ap.add_argument("--cold", action="store_true", help="also time a cold kernel compile")
    ap.add_argument("--out", default=str(ROOT / "results" / "bench" / "targets.md"))
    args = ap.parse_args(argv)
    command = "benchmarks/bench_targets.py " + " ".join(sys.argv[1:] if argv is None else argv)
    start_load = load()
    tmp = Path(tempfile.mkdtemp(prefix="bench_targets_"))
    for name in ("6d", "9", "14a"):  # compile / load (auto; the exact flow, body and pair)
        run_sweep(plane_scene(name, 4), tmp / "warm.h5", workers=WORKERS, overwrite=True)
    table = ["| plane | contestant | ICs/s (2 workers) | grid wall | vs before | agreement "
             "with the tight reference |", "|---|---|---:|---:|---:|---|"]
    targets = []
    for name in args.planes.split(","):
        res = args.resolution if name == "6d" else args.fractal_resolution
        rows = plane_rows(name, res, args.sample, tmp)
        table += plane_table(name, rows, res * res)
        d = rows["defaults"]
        share = d["same"] / d["n"]
        if name == "6d":
            targets.append(("figure 6(d) defaults: >= 4167 ICs/s, >= 99.9 % agreement",
                            f"{d['rate']:.0f} ICs/s, {100 * share:.1f} %",
                            d["rate"] >= 4167 and share >= 0.999))
        else:
            speedup = d["rate"] / rows["before"]["rate"]
            targets.append((f"figure {name} defaults: >= 3x before, >= 99.5 % agreement",
                            f"{speedup:.2f}x, {100 * share:.1f} %",
                            speedup >= 3 and share >= 0.995))
    wall = stability_wall(tmp)
    targets.append(("basin stability 14(c), N = 1000, warm: <= 1.5 s", f"{wall:.2f} s",
                    wall <= 1.5))
    first, second = cli_sweep_wall(tmp)
    targets.append(("10 x 10 basin sweep from the command line, warm: <= 2 s",
                    f"{second:.2f} s (first run {first:.2f} s)", second <= 2.0))
    fixed = repeated_fixed_cost(tmp)
    targets.append(("fixed cost of a repeated small sweep (catalogue): < 0.3 s",
                    f"{fixed:.3f} s", fixed < 0.3))
    floor = rhs_floor()
    ratio = float(floor.rsplit("costs ", 1)[1].split("x")[0])
    targets.append(("right-hand side inside the integrator: <= 2.5x a bare one",
                    f"{ratio:.1f}x", ratio <= 2.5))
    if args.cold:
        cold = cold_compile()
        at_install = compiled_at_install()
        targets.append(("cold start, every kernel compiled: <= 60 s, or done once at install",
                        f"{cold:.0f} s on {os.cpu_count()} cores"
                        + (", done once by `make install`" if at_install else ""),
                        cold <= 60 or at_install))
    lines = ["# Issue 15 targets", "", f"Command: `.venv/bin/python {command.strip()}`", "",
             f"Machine: {machine()}. Date: {time.strftime('%Y-%m-%d %H:%M')}. Load average "
             f"at start {start_load}, at end {load()} (a shared machine: timings indicative).",
             "", "| target | measured | met |", "|---|---|---|",
             *[f"| {t} | {m} | {'yes' if ok else 'no'} |" for t, m, ok in targets], "",
             "## Per plane", "", *table, "",
             "Before: the defaults until issue 15 (auto, rtol 1e-8, atol 1e-10, capture "
             "1e-2 x 3, no recurrence cells). The study's method and scipy ran on the first "
             f"{STUDY_SAMPLE} and {SCIPY_SAMPLE} sample points (rates extrapolate); the "
             "sweeps' walls include the catalogue and the HDF5 result; the defaults' walls "
             "also the tolerance pilot, the verification and any redo it made (what "
             "`softimpact sweep` does), the rows below them what those took.", "",
             f"Integrator cost: {floor}", ""]
    write_report(args.out, lines)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
