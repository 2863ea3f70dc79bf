"""Work-precision benchmark: error against a tight reference versus wall time, for every
integrator softimpact offers, on three kinds of work.

    .venv/bin/python benchmarks/bench_precision.py [--quick] [--basin-resolution N]

Integrators (atol = rtol / 100 for the adaptive ones):

- RK4 at T/180 ... T/11520 with switch location, and the study's plain scheme
  (``locate_switches = false``, each stage takes its mode from its own state);
- dopri5 at rtol 1e-4 ... 1e-12;
- rodas4 (L-stable Rosenbrock) at rtol 1e-4 ... 1e-10.

Cases:

(a) one Duffing body from (x, v) = (1, 0), 50 forcing periods, no stop: smooth;
(b) a Duffing pair (figure 14(c): phi = 5.28, d = 10.5, k_c = 8, c_c = 10) from
    (-11, 0, 0.7, 0), which settles on the impacting P1: one contact every period;
    (b') a bilinear pair (figure 14(a): w = 0.86, F = 0.518, phi = 1, d = 1.5, k_c = 8,
    c_c = 10) on its impacting P5: 20 contacts and 160 mode switches in 50 periods;
    error = max |difference| over the 51 stroboscopic points and all state variables, to
    dopri5 at rtol 1e-13, atol 1e-15; wall = best of several runs of one call;
(c) the figure 6(d) basin (Duffing, phi = 0, d = 6, k_c = 8, c_c = 10, (x1, x2) in
    [-12, 12]^2, v = 0, t0 = 0) labelled as a sweep labels (``run_chunk``, 2 processes),
    with the cheap end of each family only (``basin_settings``); error = the share of
    labels that differ from a reference basin (dopri5 rtol 1e-11, atol 1e-13,
    convergence_tol 1e-9, max_periods 6000, no capture), cached under results/bench/ as an
    .npz named by a hash of its settings and of the sources that classify.

numba compilation is excluded: every setting runs once untimed first. Output:
results/bench/precision.md (tables, command, machine, load, date) and precision.png.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
import time
from collections import Counter
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
from _common import (
    ROOT,
    TIGHT,
    WORKERS,
    code_version,
    fmt_time,
    label_context,
    load,
    machine,
    scene_at,
)
from _precision_report import write_report

from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kernels.numba_cache import source_hash
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import runner
from softimpact_cli.sweep.chunks import SweepContext

ATOL_PER_RTOL = 1e-2  # atol = rtol / 100 for dopri5 and rodas4
RK4_STEPS = (180, 360, 720, 1440, 2880, 5760, 11520)
DOPRI5_RTOLS = tuple(10.0 ** -k for k in range(4, 13))
RODAS4_RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
TRAJECTORY_REFERENCE = dict(method="dopri5", rtol=1e-13, atol=1e-15)
FLOOR_CHECK_STEPS = 46080  # RK4 with location at T/46080: an independent check of it
BASIN_REFERENCE = TIGHT  # no capture, no recurrence cells
# what decides a label besides the integrator: a change here recomputes the reference
CLASSIFYING_SOURCES = ("analysis/engine.py", "analysis/labels.py", "sweep/chunks.py",
                       "analysis/catalogue.py")
FAMILIES = ("RK4, switches located", "RK4 plain (study's scheme)", "dopri5", "rodas4")


@dataclass(frozen=True)
class Setting:
    """One integrator setting: a line (``family``), a point on it (``label``), and the
    changes to the scene's IntegratorSettings."""

    family: str
    label: str
    changes: tuple[tuple[str, object], ...]

    def on(self, base: IntegratorSettings) -> IntegratorSettings:
        return replace(base, **dict(self.changes))


def rk4(steps: int, located: bool = True) -> Setting:
    return Setting(FAMILIES[0] if located else FAMILIES[1], f"T/{steps}",
                   (("method", "rk4"), ("steps_per_period", steps),
                    ("locate_switches", located)))


def adaptive(method: str, rtol: float) -> Setting:
    return Setting(FAMILIES[2] if method == "dopri5" else FAMILIES[3], f"{rtol:.0e}",
                   (("method", method), ("rtol", rtol), ("atol", rtol * ATOL_PER_RTOL)))


def trajectory_settings(quick: bool) -> list[Setting]:
    """Every setting for cases (a) and (b); a thinned set with ``quick``."""
    steps = RK4_STEPS[::2] if quick else RK4_STEPS
    rtols = DOPRI5_RTOLS[::2] if quick else DOPRI5_RTOLS
    stiff = RODAS4_RTOLS[:3:2] if quick else RODAS4_RTOLS
    return ([rk4(n) for n in steps] + [rk4(n, False) for n in steps]
            + [adaptive("dopri5", r) for r in rtols] + [adaptive("rodas4", r) for r in stiff])


def basin_settings(quick: bool) -> list[Setting]:
    """Settings for the basin (c). A whole basin per setting, so the cheap end of each
    family, where agreement may break (dopri5 from rtol 1e-3): RK4 at T/1440 alone would
    take about 12 minutes on 2 shared cores, and finer steps only cost more."""
    if quick:
        return [rk4(180), rk4(180, False), adaptive("dopri5", 1e-3),
                adaptive("dopri5", 1e-6), adaptive("rodas4", 1e-4)]
    return ([rk4(180), rk4(360), rk4(180, False)]
            + [adaptive("dopri5", r) for r in (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10)]
            + [adaptive("rodas4", r) for r in (1e-4, 1e-6)])


# ------------------------------------------------------------------ (a), (b): trajectories

@dataclass(frozen=True)
class TrajectoryCase:
    key: str
    title: str
    scene: str  # TOML text of a trajectory scene (the state is the case's)
    state: tuple[float, ...]
    periods: int = 50


DUFFING_ONE = '[system]\nmodel = "duffing"\nbodies = 1\n'
DUFFING_14C = '[system]\nmodel = "duffing"\n[coupling]\nd = 10.5\nphi = 5.28\nk_c = 8.0\n' \
              'c_c = 10.0\n'
BILINEAR_14A = '[system]\nmodel = "bilinear"\nw = 0.86\nF = 0.518\n[coupling]\nd = 1.5\n' \
               'phi = 1.0\nk_c = 8.0\nc_c = 10.0\n'
TRAJECTORY_CASES = (
    TrajectoryCase("a", "(a) one Duffing body, smooth", DUFFING_ONE, (1.0, 0.0)),
    TrajectoryCase("b", "(b) Duffing pair, fig. 14(c), to the impacting P1", DUFFING_14C,
                   (-11.0, 0.0, 0.7, 0.0)),
    # a point of the impacting P5 (to 1e-6): no chaotic transient to amplify errors
    TrajectoryCase("b'", "(b') bilinear pair, fig. 14(a), on the impacting P5", BILINEAR_14A,
                   (-0.260152, 0.377108, 0.744494, 0.04457)),
)


def case_problem(case: TrajectoryCase, changes: dict) -> Problem:
    state = ", ".join(map(str, case.state))
    scene = parse_scene(case.scene + f'[analysis]\nkind = "trajectory"\nstate = [{state}]\n',
                        f"<case {case.key}>")
    return Problem(scene.system, dict(scene.values), replace(scene.integrator, **changes))


def best_time(call, min_time: float, max_repeats: int = 50) -> tuple[object, float]:
    """(result, best wall time in s) of ``call()``: one untimed run (numba compilation or
    cache load), then repeats until ``min_time`` s are spent (at least 3, at most
    ``max_repeats``); the minimum is the least disturbed by other jobs."""
    result = call()
    best, spent, n = np.inf, 0.0, 0
    while n < 3 or (spent < min_time and n < max_repeats):
        t = time.perf_counter()
        result = call()
        wall = time.perf_counter() - t
        best, spent, n = min(best, wall), spent + wall, n + 1
    return result, best


def run_trajectory_case(case: TrajectoryCase, settings: list[Setting], periods: int | None = None,
                        min_time: float = 0.3, floor_check: bool = True) -> dict:
    """Error and wall time of every setting on ``case``.

    Returns {"rows": [{family, label, error, wall, rhs, contacts, status}], "floor": the
    reference's own error estimate (max difference to RK4 at T/46080 with location, or
    nan), "contacts": contacts of the reference run}.
    """
    periods = periods or case.periods
    ref = record_trajectory(case_problem(case, TRAJECTORY_REFERENCE), case.state, 0.0,
                            periods, 1)
    floor = np.nan
    if floor_check:
        check = record_trajectory(case_problem(case, dict(rk4(FLOOR_CHECK_STEPS).changes)),
                                  case.state, 0.0, periods, 1)
        floor = float(np.max(np.abs(check.section_y - ref.section_y)))
    rows = []
    for s in settings:
        problem = case_problem(case, dict(s.changes))
        tr, wall = best_time(lambda p=problem: record_trajectory(p, case.state, 0.0, periods, 1),
                             min_time)
        error = float(np.max(np.abs(tr.section_y - ref.section_y))) if tr.status == 0 \
            else np.inf
        rows.append(dict(family=s.family, label=s.label, error=error, wall=wall,
                         rhs=tr.counters["rhs_evaluations"], contacts=int(tr.contacts.sum()),
                         status=tr.status))
    return dict(rows=rows, floor=floor, contacts=int(ref.contacts.sum()), periods=periods)


# ------------------------------------------------------------------------- (c): the basin

def basin_context(scene, catalogues: dict, names: tuple[str, ...],
                  integrator: IntegratorSettings) -> SweepContext:
    """The context a sweep of ``scene`` hands its workers (capture orbits included),
    with ``integrator``."""
    return runner.sweep_context(replace(scene, integrator=integrator), catalogues, names, None)


def reference_settings(base: IntegratorSettings) -> IntegratorSettings:
    """The basin reference: tight dopri5, and no capture near known attractors (the
    reference must converge by itself)."""
    return replace(base, **BASIN_REFERENCE)


def reference_key(scene, names: tuple[str, ...], integrator: IntegratorSettings) -> str:
    """A hash of everything that decides the reference labels: the scene, the reference
    integrator settings, the catalogue's names, the kernel and system sources and the
    modules that classify and name."""
    package = ROOT / "softimpact_cli"
    digest = hashlib.sha256(json.dumps(dict(
        scene=scene.text, integrator=asdict(integrator), names=list(names),
        label_tol=scene.analysis.label_tol, kernels=source_hash(package)),
        sort_keys=True).encode())
    for rel in CLASSIFYING_SOURCES:
        digest.update((package / rel).read_bytes())
    return digest.hexdigest()[:16]


def reference_basin(scene, catalogues, names, cache_dir: Path, echo=print) -> dict:
    """The reference labels of the whole basin, from the cache or computed (2 processes)
    and cached. Returns {labels (N,) str array, wall s, cached bool, path}."""
    integrator = reference_settings(scene.integrator)
    path = cache_dir / f"precision_reference_{reference_key(scene, names, integrator)}.npz"
    if path.exists():
        with np.load(path, allow_pickle=False) as z:
            return dict(labels=z["labels"], wall=float(z["wall"]), cached=True, path=path)
    echo(f"    computing the reference basin ({scene.initial_conditions.count} ICs, "
         f"{WORKERS} workers; cached as {path.name}) ...")
    labels, wall = label_context(basin_context(scene, catalogues, names, integrator),
                                 chunks_per_worker=16)
    labels = np.array(labels)
    cache_dir.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".partial.npz")
    np.savez_compressed(tmp, labels=labels, wall=wall, settings=json.dumps(
        asdict(integrator)), scene=scene.text, date=time.strftime("%Y-%m-%d %H:%M"))
    tmp.replace(path)
    return dict(labels=labels, wall=wall, cached=False, path=path)


def run_basin_case(resolution: int, settings: list[Setting], cache_dir: Path,
                   echo=print) -> dict:
    """Label the figure 6(d) basin with every setting; share of labels that differ from
    the reference, wall time and ICs/s on a pool of 2 processes."""
    scene = scene_at(resolution)
    catalogues, names = runner.prepare_catalogues(scene)
    n = scene.initial_conditions.count
    # warm-up in this process (the pool's workers are forked from it): every method's
    # kernels compiled or loaded from numba's cache before anything is timed
    warm = replace(scene, initial_conditions=replace(scene.initial_conditions,
                                                     resolution=(2, 1)))
    for s in settings + [Setting("", "", tuple(BASIN_REFERENCE.items()))]:
        label_context(basin_context(warm, catalogues, names, s.on(scene.integrator)), 1)
    ref = reference_basin(scene, catalogues, names, cache_dir, echo)
    rows = []
    for s in settings:
        labels, wall = label_context(basin_context(scene, catalogues, names,
                                                   s.on(scene.integrator)),
                                     chunks_per_worker=16)
        differ = [f"{r} -> {g}" for r, g in zip(ref["labels"], labels, strict=True) if r != g]
        rows.append(dict(family=s.family, label=s.label, error=len(differ) / n, wall=wall,
                         rate=n / wall, differ=len(differ),
                         top=", ".join(f"{k} x{v}" for k, v in
                                       Counter(differ).most_common(3)),
                         unresolved=sum(g == "unresolved" for g in labels)))
        echo(f"    {s.family:28s} {s.label:8s} {100 * rows[-1]['error']:6.2f} % differ, "
             f"{wall:6.1f} s ({n / wall:.0f} ICs/s)   [load {load()}]")
    shares = Counter(ref["labels"].tolist())
    return dict(rows=rows, n=n, resolution=resolution, reference=ref,
                reference_shares=dict(shares.most_common()), catalogue=names)


# ------------------------------------------------------------------------------------ main

def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="smoke run: fewer settings, short timings, a 40 x 40 basin")
    ap.add_argument("--basin-resolution", type=int, default=None,
                    help="basin grid side (default 100; 40 with --quick); 0 skips the basin")
    ap.add_argument("--out", default=None,
                    help="output path without suffix (default results/bench/precision, "
                         "or results/bench/precision_quick with --quick)")
    args = ap.parse_args(argv)
    resolution = args.basin_resolution if args.basin_resolution is not None else \
        (40 if args.quick else 100)
    out = Path(args.out or ROOT / "results" / "bench" /
               ("precision_quick" if args.quick else "precision"))
    command = "benchmarks/bench_precision.py " + " ".join(sys.argv[1:] if argv is None
                                                           else argv)
    d = IntegratorSettings()
    meta = dict(command=command.strip(), machine=machine(), load_start=load(),
                code=code_version(), nice=os.nice(0),
                date=time.strftime("%Y-%m-%d %H:%M"), quick=args.quick,
                defaults=f"convergence_tol {d.convergence_tol:g}, max_periods "
                         f"{d.max_periods}, capture_tol {d.capture_tol:g}, capture_hits "
                         f"{d.capture_hits}")
    print(f"machine: {meta['machine']}\nload average at start: {meta['load_start']}")
    t_start = time.perf_counter()

    trajectories = {}
    for case in TRAJECTORY_CASES:
        print(f"\n{case.title} ...", flush=True)
        res = run_trajectory_case(case, trajectory_settings(args.quick),
                                  min_time=0.05 if args.quick else 0.3,
                                  floor_check=not args.quick)
        res["load"] = load()
        trajectories[case.key] = (case, res)
        for r in res["rows"]:
            print(f"    {r['family']:28s} {r['label']:8s} error {r['error']:9.2e}  "
                  f"{1e3 * r['wall']:8.2f} ms")
        print(f"    reference vs RK4 T/{FLOOR_CHECK_STEPS}: {res['floor']:.1e}   [load {load()}]")

    basin = None
    if resolution > 0:
        print(f"\n(c) figure 6(d) basin, {resolution} x {resolution}, {WORKERS} workers ...",
              flush=True)
        basin = run_basin_case(resolution, basin_settings(args.quick),
                               ROOT / "results" / "bench")
    meta["load_end"] = load()
    meta["total"] = fmt_time(time.perf_counter() - t_start)
    md, png = write_report(out, meta, trajectories, basin)
    print(f"\nwritten: {md}\n         {png}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
