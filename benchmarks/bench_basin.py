"""Speed benchmark: the figure 6(d) basin (Duffing pair, phi = 0, d = 6, k_c = 8, c_c = 10,
(x1, x2) in [-12, 12]^2, v1 = v2 = 0, t0 = 0), three ways, measured side by side in one run.

    .venv/bin/python benchmarks/bench_basin.py [--resolution N] [--sample M] [--scipy-sample K]

Contestants (every one on 2 worker processes, so that ICs/s compare like with like):

1. softimpact's defaults: ``run_sweep`` on the scene (dopri5 with switch location, stop as
   soon as the section points repeat), the whole grid, wall time including the catalogue
   search and the HDF5 result (numba compilation excluded by a warm-up run).
2. the study's method on softimpact's kernels: RK4 at T/1440 without switch location, a
   fixed transient of 1000 forcing periods (no early stop), then classification of the
   final state; a random subsample of M initial conditions, extrapolated to the grid.
3. a plain scipy loop: ``solve_ivp`` (RK45 or DOP853, rtol 1e-8, atol 1e-10) with terminal
   events at x1 - x2 = d, restarted with the contact state flipped, a fixed transient of
   300 periods, then 60 recorded stroboscopic points to classify; a subsample of K.

Label agreement is measured against a tight reference (softimpact, dopri5 rtol 1e-11,
atol 1e-13, convergence_tol 1e-9, max_periods 6000, no capture, no recurrence cells:
``_common.TIGHT``) on the same grid points; every
contestant's final orbit is named with the same catalogue (``label_orbit``).

Also: the figure 14(c) basin-stability run (N = 1000, 2 workers; target <= 5 s), and a
profile of softimpact's default run in one process (where the time goes, the share inside
numba kernels). The table goes to ``results/bench/basin_speed.md``.
"""

from __future__ import annotations

import argparse
import functools
import multiprocessing as mp
import sys
import tempfile
import time
from collections import Counter
from dataclasses import replace
from pathlib import Path

import numpy as np
from _common import (  # the benchmarks folder is on sys.path when this script runs
    ROOT,
    TIGHT,
    WORKERS,
    fmt_time,
    label_states,
    load,
    machine,
    scene_at,
    stability_scene,
)
from scipy_contestant import RECORD as SCIPY_RECORD
from scipy_contestant import TRANSIENT as SCIPY_TRANSIENT
from scipy_contestant import scipy_label
from study_method import TRANSIENT_PERIODS as STUDY_PERIODS
from study_method import StudyMethod
from where_time_goes import StageClock, phases, rhs_floor

from softimpact_cli.analysis.labels import name_of
from softimpact_cli.config.axes import catalogue_key
from softimpact_cli.sweep.runner import prepare_catalogues, run_sweep

REFERENCE = TIGHT  # no capture, no cells: the reference converges by itself


def labels_of(ds) -> tuple[np.ndarray, tuple[str, ...]]:
    names = tuple(str(x) for x in ds["combination_name"].values) \
        if "combination_name" in ds else ()
    return ds["label"].values.reshape(-1), names


_TASK = None  # the labelling function of the pool below (inherited by the forked workers)


def _run_task(state) -> str:
    return _TASK(state)


def timed_pool(label, states) -> tuple[list[str], float]:
    """``label(state)`` on each state on a fork pool of WORKERS; (labels, wall s)."""
    global _TASK
    _TASK = label
    t = time.perf_counter()
    with mp.get_context("fork").Pool(WORKERS) as p:
        out = p.map(_run_task, [np.array(s) for s in states], chunksize=1)
    return out, time.perf_counter() - t


def reference_labels(scene, catalogues, names, states) -> tuple[list[str], float]:
    """The tight reference, labelled exactly as a sweep labels (run_chunk), on 2 workers."""
    return label_states(scene, catalogues, names, states, replace(scene.integrator,
                                                                  **REFERENCE))


def agreement(got: list[str], ref: list[str]) -> tuple[int, int, str]:
    same = sum(a == b for a, b in zip(got, ref, strict=True))
    diffs = Counter(f"{b} -> {a}" for a, b in zip(got, ref, strict=True) if a != b)
    return same, len(ref), "; ".join(f"{k} x{v}" for k, v in diffs.most_common(4))


def stability_run(n: int, tmp: Path) -> tuple[float, float, dict]:
    """The figure 14(c)-style basin stability on WORKERS: (wall s, catalogue s, shares)."""
    clock = StageClock()
    t = time.perf_counter()
    ds = run_sweep(stability_scene(n), tmp / "stability.h5", workers=WORKERS,
                   overwrite=True, echo=clock)
    wall = time.perf_counter() - t
    codes, names = labels_of(ds)
    shares = Counter(name_of(c, names) for c in codes)
    return wall, clock.catalogue_s(), dict(shares.most_common())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--resolution", type=int, default=200, help="grid side (default 200)")
    ap.add_argument("--sample", type=int, default=40,
                    help="ICs for the study's method (default 40)")
    ap.add_argument("--scipy-sample", type=int, default=10, help="ICs for scipy (default 10)")
    ap.add_argument("--ref-sample", type=int, default=200,
                    help="grid points with a tight reference, for softimpact's agreement "
                         "(default 200; the study and scipy samples are among them)")
    ap.add_argument("--scipy-method", default="RK45", choices=("RK45", "DOP853"))
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--profile-side", type=int, default=14,
                    help="profile a single-process run of side^2 ICs (default 14: 196)")
    ap.add_argument("--stability-n", type=int, default=1000)
    ap.add_argument("--skip-stability", action="store_true")
    ap.add_argument("--skip-profile", action="store_true")
    ap.add_argument("--stability-only", action="store_true",
                    help="only the basin-stability timing (after a warm-up); writes nothing")
    ap.add_argument("--fast-rtol", type=float, default=1e-5,
                    help="softimpact's fast contestant: dopri5 rtol (default 1e-5)")
    ap.add_argument("--fast-cells", type=float, default=0.05,
                    help="softimpact's fast contestant: recurrence cell side (default 0.05; "
                         "0 for none)")
    ap.add_argument("--skip-fast", action="store_true", help="no fast contestant")
    ap.add_argument("--out", default=str(ROOT / "results" / "bench" / "basin_speed.md"))
    args = ap.parse_args(argv)

    command = "benchmarks/bench_basin.py " + " ".join(sys.argv[1:] if argv is None else argv)
    load_start = load()
    print(f"machine: {machine()}")
    print(f"load average at start: {load_start} (the machine is shared: timings are indicative)")
    if args.stability_only:
        tmp = Path(tempfile.mkdtemp(prefix="bench_stability_"))
        stability_run(min(args.stability_n, 50), tmp)  # warm-up
        wall, cat, shares = stability_run(args.stability_n, tmp)
        print(f"figure 14(c) basin stability, N = {args.stability_n}, {WORKERS} workers: wall "
              f"{wall:.1f} s (catalogue {cat:.1f} s; target <= 5 s); {shares}")
        for p in sorted(tmp.rglob("*"), reverse=True):
            p.unlink() if p.is_file() else p.rmdir()
        tmp.rmdir()
        return 0
    n = args.resolution
    scene = scene_at(n)
    N = n * n
    states = scene.initial_conditions.array()
    tmp = Path(tempfile.mkdtemp(prefix="bench_basin_"))

    # warm-up: compile / load every kernel the contestants use (excluded from timings)
    t = time.perf_counter()
    run_sweep(scene_at(4), tmp / "warm.h5", workers=WORKERS)
    print(f"warm-up (numba compile/cache load, small sweep): {time.perf_counter() - t:.1f} s")

    t = time.perf_counter()
    catalogues, names = prepare_catalogues(scene)
    t_cat = time.perf_counter() - t
    catalogue = catalogues[catalogue_key(scene.system, scene.values)]
    tol = scene.analysis.label_tol
    study_method = StudyMethod.of(scene, catalogue)
    study_method.label(states[0])  # compiles RK4 (excluded from the timing, as above)
    print(f"catalogue ({t_cat:.1f} s, one process): {', '.join(names)}")

    # the sample points: random grid points; the study's and scipy's samples are among them
    rng = np.random.default_rng(args.seed)
    n_ref = min(N, max(args.ref_sample, args.sample, args.scipy_sample))
    idx = rng.choice(N, size=n_ref, replace=False)
    idx_study, idx_scipy = idx[:min(args.sample, n_ref)], idx[:min(args.scipy_sample, n_ref)]

    # 1. softimpact defaults, whole grid
    print(f"\n[1] softimpact defaults: run_sweep on {n} x {n} = {N} ICs, {WORKERS} workers ...",
          flush=True)
    t = time.perf_counter()
    ds = run_sweep(scene, tmp / "basin.h5", workers=WORKERS)
    wall_si = time.perf_counter() - t
    codes, ds_names = labels_of(ds)
    si_labels = [name_of(c, ds_names) for c in codes]
    print(f"    wall {wall_si:.1f} s ({N / wall_si:.0f} ICs/s); labels "
          f"{dict(Counter(si_labels).most_common())}")

    # 1b. softimpact with a looser tolerance and recurrence cells, whole grid
    fast_settings = (f"dopri5 rtol {args.fast_rtol:g}, atol {args.fast_rtol / 100:g}, "
                     f"cells {args.fast_cells:g} x 5 hits, capture")
    if not args.skip_fast:
        fast_scene = replace(scene, integrator=replace(
            scene.integrator, rtol=args.fast_rtol, atol=args.fast_rtol / 100,
            cell_size=args.fast_cells, cell_hits=5))
        print(f"[1b] softimpact fast ({fast_settings}) on {N} ICs ...", flush=True)
        t = time.perf_counter()
        ds_fast = run_sweep(fast_scene, tmp / "fast.h5", workers=WORKERS)
        wall_fast = time.perf_counter() - t
        codes_fast, fast_names = labels_of(ds_fast)
        fast_labels = [name_of(c, fast_names) for c in codes_fast]
        print(f"    wall {wall_fast:.1f} s ({N / wall_fast:.0f} ICs/s)")

    # reference on the sample points
    print(f"[ref] tight dopri5 reference on {n_ref} sample points ...", flush=True)
    ref, wall_ref = reference_labels(scene, catalogues, names, states[idx])
    ref_by = dict(zip(idx.tolist(), ref, strict=True))
    print(f"    wall {wall_ref:.1f} s ({n_ref / wall_ref:.1f} ICs/s)")

    # 2. study's method
    print(f"[2] study's method (RK4 T/1440, no switch location, {STUDY_PERIODS} periods) on "
          f"{len(idx_study)} ICs ...", flush=True)
    study, wall_study = timed_pool(study_method.label, states[idx_study])
    print(f"    wall {wall_study:.1f} s ({len(idx_study) / wall_study:.2f} ICs/s)")

    # 3. scipy
    print(f"[3] scipy solve_ivp {args.scipy_method} (rtol 1e-8, events, {SCIPY_TRANSIENT} + "
          f"{SCIPY_RECORD} periods) on {len(idx_scipy)} ICs ...", flush=True)
    sp, wall_sp = timed_pool(functools.partial(
        scipy_label, values=dict(scene.values), method=args.scipy_method,
        catalogue=catalogue, tol=tol), states[idx_scipy])
    print(f"    wall {wall_sp:.1f} s ({len(idx_scipy) / wall_sp:.2f} ICs/s)")

    rows = []
    rate_si = N / wall_si
    for name, n_run, wall, got, pts in [
        ("softimpact defaults (dopri5 + switch location, early stop)", N, wall_si,
         [si_labels[i] for i in idx], idx),
        (f"study's method on softimpact kernels (RK4 T/1440, no location, "
         f"{STUDY_PERIODS} T)", len(idx_study), wall_study, study, idx_study),
        (f"scipy solve_ivp {args.scipy_method} + events ({SCIPY_TRANSIENT} T transient)",
         len(idx_scipy), wall_sp, sp, idx_scipy),
        ("reference (softimpact dopri5 rtol 1e-11, early stop)", n_ref, wall_ref, None, idx),
    ] + ([] if args.skip_fast else [
        (f"softimpact fast ({fast_settings})", N, wall_fast, [fast_labels[i] for i in idx],
         idx)]):
        rate = n_run / wall
        if got is None:
            agree = "(reference)"
            diffs = ""
        else:
            same, total, diffs = agreement(list(got), [ref_by[i] for i in pts.tolist()])
            agree = f"{100 * same / total:.1f} % ({same}/{total})"
        rows.append((name, "measured" if n_run == N else f"{n_run} ICs, extrapolated",
                     rate, N / rate, agree, diffs))
    rate_study, rate_sp = rows[1][2], rows[2][2]

    header = ("| contestant | basis | ICs/s (2 workers) | full grid wall | label agreement "
              "with reference |")
    sep = "|---|---|---:|---:|---|"
    table = [header, sep] + [f"| {r[0]} | {r[1]} | {r[2]:.2f} | {fmt_time(r[3])} | {r[4]} |"
                             for r in rows]
    ratios = [f"softimpact vs the study's method: {rate_si / rate_study:.0f}x faster "
              f"({fmt_time(N / rate_study)} -> {fmt_time(wall_si)})",
              f"softimpact vs scipy {args.scipy_method}: {rate_si / rate_sp:.0f}x faster "
              f"({fmt_time(N / rate_sp)} -> {fmt_time(wall_si)})"]
    if not args.skip_fast:
        rate_fast = N / wall_fast
        ratios += [f"softimpact fast vs the study's method: {rate_fast / rate_study:.0f}x, vs "
                   f"scipy: {rate_fast / rate_sp:.0f}x, vs softimpact defaults: "
                   f"{rate_fast / rate_si:.1f}x ({fmt_time(wall_fast)} for the grid)"]
    disagreements = [f"{r[0].split(' (')[0]}: {r[5]}" for i, r in enumerate(rows)
                     if r[5] and i != 3]
    notes = [
        f"grid: {n} x {n} = {N} ICs on (x1, x2) in [-12, 12]^2, v1 = v2 = 0, t0 = 0; "
        "phi = 0, d = 6, k_c = 8, c_c = 10 (figure 6(d)).",
        f"softimpact's wall includes its catalogue search ({t_cat:.1f} s in one process) and "
        "the HDF5 result; the others reuse that catalogue for naming and are not charged "
        "for it. numba compilation is excluded (warm-up run first).",
        "every contestant ran on a 2-process pool; samples are random grid points (seed "
        f"{args.seed}), the scipy sample is the first {len(idx_scipy)} of the study sample, "
        f"which is the first {len(idx_study)} of the {n_ref} reference points.",
        "label agreement: the share of sample points whose label equals the tight "
        "reference's (same catalogue, same `label_orbit`, tolerance "
        f"{tol}); the study's method and scipy decide impacting vs not from contact in the "
        "final periods, then match the last stroboscopic point to the catalogue.",
        f"load average at start {load_start}, at end {load()}: the machine is shared, so "
        "timings are indicative.",
    ]

    print("\n" + "\n".join(table))
    print("\n" + "\n".join(ratios))
    if disagreements:
        print("disagreements (reference -> contestant): " + " | ".join(disagreements))

    extra = []
    if not args.skip_stability:
        print(f"\n[stability] figure 14(c)-style basin stability, N = {args.stability_n}, "
              f"{WORKERS} workers ...", flush=True)
        wall, cat, shares = stability_run(args.stability_n, tmp)
        verdict = "meets" if wall <= 5.0 else "misses"
        line = (f"figure 14(c) basin stability (Duffing, phi = 5.28, d = 10.5, k_c = 8, "
                f"c_c = 10, N = {args.stability_n} in [-12, 12]^4, t0 = 0): wall {wall:.1f} s "
                f"on {WORKERS} workers (catalogue {cat:.1f} s of it); {verdict} the <= 5 s "
                f"target. Shares: " + ", ".join(f"{k} {v}" for k, v in shares.items()))
        print("    " + line)
        extra += ["", "## Basin stability (figure 14(c) scene)", "", line]

    if not args.skip_profile:
        print(f"\n[profile] softimpact defaults, one process, {args.profile_side ** 2} ICs ...",
              flush=True)
        lines = phases(args.profile_side, tmp)
        lines.append("  " + rhs_floor())
        print("\n".join(lines))
        extra += ["", "## Where softimpact's default run spends its time", "", "```",
                  *lines, "```"]

    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    md = ["# Basin speed benchmark (figure 6(d))", "",
          f"Command: `.venv/bin/python {command.strip()}`", "",
          f"Machine: {machine()}. Date: {time.strftime('%Y-%m-%d %H:%M')}.", "",
          *table, "", *[f"- {r}" for r in ratios], "",
          *([f"Disagreements (reference -> contestant): {' | '.join(disagreements)}", ""]
            if disagreements else []),
          "Notes:", "", *[f"- {x}" for x in notes], *extra, ""]
    out.write_text("\n".join(md))
    print(f"\nwritten: {out}")
    for p in sorted(tmp.rglob("*"), reverse=True):
        p.unlink() if p.is_file() else p.rmdir()
    tmp.rmdir()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
