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
atol 1e-13, convergence_tol 1e-9, max_periods 6000) on the same grid points; every
contestant's final orbit is named with the same catalogue (``label_orbit``).

Also: the figure 14(c) basin-stability run (N = 1000, 2 workers; target <= 5 s), and a
profile of softimpact's default run in one process (where the time goes, the share inside
numba kernels). The table goes to ``results/bench/basin_speed.md``.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import multiprocessing as mp
import pstats
import sys
import tempfile
import time
from collections import Counter
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

import numpy as np
from _common import (  # the benchmarks folder is on sys.path when this script runs
    ROOT,
    WORKERS,
    fmt_time,
    label_states,
    load,
    machine,
    scene_at,
    stability_scene,
)

from softimpact_cli.analysis.catalogue import label_orbit
from softimpact_cli.engine import Problem, classify_state, flow
from softimpact_cli.kernels import orbit as orbit_kernels
from softimpact_cli.kernels.status import outcome
from softimpact_cli.labels import DIVERGED, UNRESOLVED, name_of
from softimpact_cli.sweep import executors, runner
from softimpact_cli.sweep.runner import prepare_catalogues, run_sweep

STUDY_PERIODS = 1000  # the study's fixed transient (forcing periods)
STUDY_CLASSIFY_PERIODS = 100  # after it: periods allowed to find the repeat
SCIPY_TRANSIENT = 300
SCIPY_RECORD = 60  # recorded stroboscopic points after the transient
SCIPY_REPEAT_TOL = 1e-5  # section points repeating to this (scaled), rtol 1e-8 integration
MAX_ORBIT_PERIOD = 30

REFERENCE = dict(method="dopri5", rtol=1e-11, atol=1e-13, convergence_tol=1e-9,
                 max_periods=6000)


# ----------------------------------------------------------------------------- helpers

def labels_of(ds) -> tuple[np.ndarray, tuple[str, ...]]:
    names = tuple(str(x) for x in ds["combination_name"].values) \
        if "combination_name" in ds else ()
    return ds["label"].values.reshape(-1), names


def pool(n: int):
    return mp.get_context("fork").Pool(n)


def _name_classification(cls, catalogue, tol) -> str:
    """As ``sweep.chunks.run_chunk`` names an outcome."""
    if cls.status == 0:
        return label_orbit(catalogue, cls.orbit, cls.impacting, tol).name
    return UNRESOLVED if outcome(cls.status) == "unresolved" else DIVERGED


# ------------------------------------------------------- contestant 2: the study's method

_STUDY = {}


def _study_one(state) -> str:
    g = _STUDY
    T = g["flow"].period
    t_end = STUDY_PERIODS * T
    status, y, _ = flow(g["flow"], state, 0.0, t_end)
    if status != 0:
        return UNRESOLVED if outcome(status) == "unresolved" else DIVERGED
    cls = classify_state(g["classify"], y, t_end)
    return _name_classification(cls, g["catalogue"], g["tol"])


def study_problems(scene):
    study = Problem(scene.system, dict(scene.values), scene.integrator).with_integrator(
        method="rk4", steps_per_period=1440, locate_switches=False)
    return study, study.with_integrator(max_periods=STUDY_CLASSIFY_PERIODS,
                                        max_orbit_period=MAX_ORBIT_PERIOD)


# ------------------------------------------------------------- contestant 3: plain scipy

_SCIPY = {}


def scipy_one(state, values, method="RK45", catalogue=None, tol=1e-3,
              transient=SCIPY_TRANSIENT, record=SCIPY_RECORD) -> str:
    """What a Python user would write: solve_ivp with a terminal event on x1 - x2 = d,
    restarted with the contact flag flipped; fixed transient, then stroboscopic points."""
    from scipy.integrate import solve_ivp

    c, k1, k2, F, w = (float(values[k]) for k in ("c", "k1", "k2", "F", "w"))
    d, phi, kc, cc = (float(values[k]) for k in ("d", "phi", "k_c", "c_c"))
    T = 2 * np.pi / w

    def rhs(t, y, contact):
        x1, v1, x2, v2 = y
        fc = kc * (x1 - x2 - d) + cc * (v1 - v2) if contact else 0.0
        return [v1, F * np.sin(w * t) - c * v1 - k1 * x1 - k2 * x1 ** 3 - fc,
                v2, F * np.sin(w * t + phi) - c * v2 - k1 * x2 - k2 * x2 ** 3 + fc]

    def gap(t, y, contact):
        return y[0] - y[2] - d

    gap.terminal = True
    t, y = 0.0, np.array(state, dtype=float)
    contact = bool(y[0] - y[2] >= d)
    t_rec0 = transient * T
    t_end = (transient + record) * T
    strobe_t = t_rec0 + T * np.arange(record + 1)
    strobe = []
    impacting = False  # any contact during the recorded periods
    events = 0
    while t < t_end:
        gap.direction = -1.0 if contact else 1.0
        t_eval = strobe_t[strobe_t > t] if t > 0.0 or t_rec0 > 0.0 else strobe_t
        sol = solve_ivp(rhs, (t, t_end), y, method=method, rtol=1e-8, atol=1e-10,
                        events=gap, args=(contact,), t_eval=t_eval)
        if sol.status == -1:
            return DIVERGED
        if len(sol.t):
            strobe.extend(np.asarray(sol.y).T)
        if sol.status == 1:  # event: flip the contact state and restart there
            t, y = float(sol.t_events[0][0]), sol.y_events[0][0].copy()
        else:  # reached t_end, the last of t_eval
            t, y = t_end, sol.y[:, -1]
        if contact and t > t_rec0:  # in contact during part of the recorded window
            impacting = True
        if sol.status == 1:
            contact = not contact
            events += 1
            if events > 200 * (transient + record):  # chattering: give up
                return UNRESOLVED
        if not np.all(np.isfinite(y)) or np.max(np.abs(y)) > 1e6:
            return DIVERGED
    pts = np.array(strobe)
    n = len(pts) - 1
    scale = max(1.0, float(np.max(np.abs(pts[n]))))
    q = 0
    for cand in range(1, MAX_ORBIT_PERIOD + 1):
        if n < 2 * cand:
            break
        if np.max(np.abs(pts[n - cand + 1:n + 1] - pts[n - 2 * cand + 1:n - cand + 1])) \
                <= SCIPY_REPEAT_TOL * scale:
            q = cand
            break
    if q == 0:
        return UNRESOLVED
    if catalogue is None:
        return f"P{q}{' impacting' if impacting else ''}"
    return label_orbit(catalogue, pts[n - q + 1:n + 1], impacting, tol).name


def _scipy_one(state) -> str:
    g = _SCIPY
    return scipy_one(state, g["values"], g["method"], g["catalogue"], g["tol"])


# -------------------------------------------------------------------------- benchmark

def timed_pool(func, states, setup: dict, store: dict) -> tuple[list[str], float]:
    """Run ``func`` on each state on a fork pool of WORKERS; (labels, wall)."""
    store.clear()
    store.update(setup)
    t = time.perf_counter()
    with pool(WORKERS) as p:
        out = p.map(func, [np.array(s) for s in states], chunksize=1)
    return out, time.perf_counter() - t


def reference_labels(scene, catalogues, names, states) -> tuple[list[str], float]:
    """The tight reference, labelled exactly as a sweep labels (run_chunk), on 2 workers."""
    from dataclasses import replace

    return label_states(scene, catalogues, names, states, replace(scene.integrator,
                                                                  **REFERENCE))


def agreement(got: list[str], ref: list[str]) -> tuple[int, int, str]:
    same = sum(a == b for a, b in zip(got, ref, strict=True))
    diffs = Counter(f"{b} -> {a}" for a, b in zip(got, ref, strict=True) if a != b)
    return same, len(ref), "; ".join(f"{k} x{v}" for k, v in diffs.most_common(4))


@contextmanager
def kernel_timer(acc: dict):
    """Time every call into the numba kernels (engine calls them as orbit.<name>)."""
    saved = {}
    for name in ("classify", "classify_near", "flow", "record"):
        fn = getattr(orbit_kernels, name)
        saved[name] = fn

        def wrapped(*args, _fn=fn, **kw):
            t = time.perf_counter()
            try:
                return _fn(*args, **kw)
            finally:
                acc[acc["phase"]] = acc.get(acc["phase"], 0.0) + time.perf_counter() - t
        setattr(orbit_kernels, name, wrapped)
    try:
        yield acc
    finally:
        for name, fn in saved.items():
            setattr(orbit_kernels, name, fn)


@contextmanager
def phase_timer(acc: dict):
    """Wall time of the sweep's phases: catalogue, chunks (classification), the rest."""
    prep, chunk = runner.prepare_catalogues, executors.run_chunk
    capturable = runner.capturable_orbits

    def timed(fn):
        def run(*a, **kw):
            acc["phase"] = "catalogue_kernels"
            t = time.perf_counter()
            try:
                return fn(*a, **kw)
            finally:
                acc["catalogue"] = acc.get("catalogue", 0.0) + time.perf_counter() - t
                acc["phase"] = "other_kernels"
        return run

    def timed_chunk(*a, **kw):
        acc["phase"] = "chunk_kernels"
        t = time.perf_counter()
        try:
            return chunk(*a, **kw)
        finally:
            acc["chunks"] = acc.get("chunks", 0.0) + time.perf_counter() - t
            acc["phase"] = "other_kernels"

    runner.prepare_catalogues, executors.run_chunk = timed(prep), timed_chunk
    runner.capturable_orbits = timed(capturable)
    try:
        yield acc
    finally:
        runner.prepare_catalogues, executors.run_chunk = prep, chunk
        runner.capturable_orbits = capturable


def profile_default(n_side: int, tmp: Path) -> tuple[str, list[str]]:
    """Single-process default run of n_side^2 ICs: phases, kernel share, cProfile top."""
    scene = scene_at(n_side)
    acc = {"phase": "other_kernels"}
    with phase_timer(acc), kernel_timer(acc):
        t = time.perf_counter()
        run_sweep(scene, tmp / "profile.h5", workers=1, overwrite=True)
        total = time.perf_counter() - t
    n = n_side * n_side
    cat, chunks = acc.get("catalogue", 0.0), acc.get("chunks", 0.0)
    k_cat, k_chunk = acc.get("catalogue_kernels", 0.0), acc.get("chunk_kernels", 0.0)
    rest = total - cat - chunks
    k_all = k_cat + k_chunk + acc.get("other_kernels", 0.0)
    lines = [
        f"single-process default run, {n} ICs ({n_side} x {n_side}), wall {total:.2f} s:",
        f"  catalogue, Newton, critical distances: {cat:5.2f} s ({100 * cat / total:4.1f} %), "
        f"of which in numba kernels {k_cat:.2f} s ({100 * k_cat / max(cat, 1e-12):.0f} %)",
        f"  classifying the ICs (run_chunk):      {chunks:6.2f} s ({100 * chunks / total:4.1f} %), "
        f"of which in numba kernels {k_chunk:.2f} s ({100 * k_chunk / max(chunks, 1e-12):.0f} %)"
        f"; {1e3 * chunks / n:.2f} ms per IC, Python overhead "
        f"{1e6 * (chunks - k_chunk) / n:.0f} us per IC",
        f"  plan, store, HDF5 write, assembly:    {rest:6.2f} s ({100 * rest / total:4.1f} %)",
        f"  numba kernels overall: {100 * k_all / total:.0f} % of the wall time",
    ]
    prof = cProfile.Profile()
    prof.enable()
    run_sweep(scene, tmp / "profile.h5", workers=1, overwrite=True)
    prof.disable()
    buf = io.StringIO()
    stats = pstats.Stats(prof, stream=buf).strip_dirs().sort_stats("tottime")
    stats.print_stats(12)
    top = [ln for ln in buf.getvalue().splitlines() if ln.strip()]
    start = next((i for i, ln in enumerate(top) if ln.lstrip().startswith("ncalls")), 0)
    lines.append("  cProfile (same run again, sorted by own time; numba kernels show under "
                 "their Python names, e.g. orbit.py(classify)):")
    lines += ["    " + ln for ln in top[start:start + 13]]
    return "\n".join(lines), lines


def rhs_floor(periods: int = 400, repeats: int = 5) -> str:
    """How close the integrator runs to bare right-hand-side evaluations: one trajectory of
    the figure 6(d) pair on its attractor (no contact), CPU time of the whole integration
    against the same number of bare ``rhs`` calls in a compiled loop (best of repeats)."""
    from numba import njit

    scene = scene_at(2)
    problem = Problem(scene.system, scene.values, scene.integrator)
    T = problem.period
    y0 = np.array([1.0, 0.0, -1.0, 0.0])
    A, b, rel, contact = problem.kernel_args()

    def integrate():
        return orbit_kernels.flow(problem.advance, problem.system.rhs, problem.params,
                                  y0.copy(), 0.0, periods * T, A, b, rel, contact,
                                  problem.options())

    @njit
    def bare(rhs, p, n, h):
        y = np.array([1.0, 0.0, -1.0, 0.0])
        out = np.zeros(4)
        acc = 0.0
        for i in range(n):
            rhs(i * h, y, p, 0, out)
            acc += out[1]
            y[0] += 1e-12 * out[0]  # the state changes, so no call is hoisted out
        return acc

    counters = integrate()[3]
    n_rhs, n_steps = int(counters[3]), int(counters[1])
    bare(problem.system.rhs, problem.params, 10, T / 100)
    t_int = t_bare = np.inf
    for _ in range(repeats):
        t = time.process_time()
        integrate()
        t_int = min(t_int, time.process_time() - t)
        t = time.process_time()
        bare(problem.system.rhs, problem.params, n_rhs, T / 100)
        t_bare = min(t_bare, time.process_time() - t)
    return (f"integrator against bare right-hand sides ({periods} periods on the attractor, "
            f"{problem.integrator.method}, {n_steps} steps, {n_rhs} evaluations): "
            f"{1e9 * t_int / n_rhs:.0f} ns per evaluation inside the integrator, "
            f"{1e9 * t_bare / n_rhs:.0f} ns bare: the integrator costs {t_int / t_bare:.1f}x "
            "its right-hand sides (error estimate, dense output, switch watch, contact "
            "maximum, step control)")


def stability_run(n: int, tmp: Path) -> tuple[float, float, dict]:
    scene = stability_scene(n)
    acc = {"phase": "other_kernels"}
    with phase_timer(acc):
        t = time.perf_counter()
        ds = run_sweep(scene, tmp / "stability.h5", workers=WORKERS, overwrite=True)
        wall = time.perf_counter() - t
    codes, names = labels_of(ds)
    shares = Counter(name_of(c, names) for c in codes)
    return wall, acc.get("catalogue", 0.0), dict(shares.most_common())


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
    T = 2 * np.pi / float(scene.values["w"])
    tmp = Path(tempfile.mkdtemp(prefix="bench_basin_"))

    # warm-up: compile / load every kernel the contestants use (excluded from timings)
    t = time.perf_counter()
    run_sweep(scene_at(4), tmp / "warm.h5", workers=WORKERS)
    study_flow, study_cls = study_problems(scene)
    flow(study_flow, states[0], 0.0, T)
    classify_state(study_cls, states[0], 0.0)
    print(f"warm-up (numba compile/cache load, small sweep): {time.perf_counter() - t:.1f} s")

    t = time.perf_counter()
    catalogues, names = prepare_catalogues(scene)
    t_cat = time.perf_counter() - t
    catalogue = catalogues[float(scene.values["phi"])]
    tol = scene.analysis.label_tol
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
    study, wall_study = timed_pool(_study_one, states[idx_study], {
        "flow": study_flow, "classify": study_cls, "catalogue": catalogue, "tol": tol}, _STUDY)
    print(f"    wall {wall_study:.1f} s ({len(idx_study) / wall_study:.2f} ICs/s)")

    # 3. scipy
    print(f"[3] scipy solve_ivp {args.scipy_method} (rtol 1e-8, events, {SCIPY_TRANSIENT} + "
          f"{SCIPY_RECORD} periods) on {len(idx_scipy)} ICs ...", flush=True)
    sp, wall_sp = timed_pool(_scipy_one, states[idx_scipy], {
        "values": dict(scene.values), "method": args.scipy_method, "catalogue": catalogue,
        "tol": tol}, _SCIPY)
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
        text, lines = profile_default(args.profile_side, tmp)
        floor = rhs_floor()
        lines.append("  " + floor)
        text += "\n  " + floor
        print(text)
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
