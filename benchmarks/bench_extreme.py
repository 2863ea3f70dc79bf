"""Extreme parameters: does the default method (`auto`) converge, or say why not?

    .venv/bin/python benchmarks/bench_extreme.py [--side 8] [--out results/bench/extreme.md]

The corpus is a one-factor-at-a-time design around a base point, plus the hardest corners
(the full cross product of the factors would be ~10^4 cases). Base: Duffing pair at the
defaults (c = 0.05, k1 = 1, k2 = 0.01, F = 1, w = 1.3) with d = 1, phi = pi, k_c = 8,
c_c = 10, contact law "paper" (an impacting setting: the stop matters); bilinear base at
its defaults (k2 = 29, d1 = 1.26, F = 0.518, w = 0.86) with the same coupling. Each case
runs a side x side plane of initial conditions (x1, x2) over the model's catalogue box
(Duffing [-12, 12]^2, bilinear [-3, 3]^2), v1 = v2 = 0, t0 = 0, on 2 worker processes.

Per initial condition, at the production settings (rtol 1e-8, atol 1e-10, convergence_tol
1e-6, max_periods 3000):

* `auto`: status (with its reason), steps taken by each method, method switches, wall;
* plain `dopri5`: status and wall, and whether its result is the same as auto's (same
  outcome, period and orbit to 1e-4, scaled);
* accuracy: the stroboscopic points y(nT), n = 1..FLOW_PERIODS, of auto against a tight
  reference (dopri5, rtol 1e-12, atol 1e-14), max over n and over the initial conditions,
  and again with auto at rtol 1e-10 (an error that shrinks with rtol is the trajectory's
  own sensitivity, not a failure);
* orbit check: each orbit auto reports is integrated q periods with the tight reference;
  the residual |Phi^q(y*) - y*| says whether it is a real periodic orbit (expected ~
  convergence_tol / (1 - |multiplier|)).

A case fails loudly only by a crash; "unresolved" and "diverged" are reported with the
kernel's reason (kernels/codes.py). The table goes to ``--out``.
"""

from __future__ import annotations

import argparse
import math
import multiprocessing as mp
import os
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from softimpact_cli.analysis.engine import Problem, classify_state, flow, record_trajectory  # noqa: E402
from softimpact_cli.config import IntegratorSettings  # noqa: E402
from softimpact_cli.kernels.codes import STATUS_TABLE  # noqa: E402
from softimpact_cli.systems import get_system  # noqa: E402

WORKERS = 2
FLOW_PERIODS = 10
SAME_ORBIT = 1e-4  # auto and dopri5 reached the same orbit (scaled max difference)
TIGHT = dict(method="dopri5", rtol=1e-12, atol=1e-14, max_steps_per_period=2_000_000)

BASE = {"duffing": dict(d=1.0, phi=math.pi, k_c=8.0, c_c=10.0, law="paper"),
        "bilinear": dict(d=1.0, phi=math.pi, k_c=8.0, c_c=10.0, law="paper")}
STIFF = dict(k_c=1e6, c_c=1e3)

# (name, model, changes from the base); one factor at a time, then the corners
CASES = [
    ("base", "duffing", {}),
    ("k_c=1e3", "duffing", dict(k_c=1e3)),
    ("k_c=1e5", "duffing", dict(k_c=1e5)),
    ("k_c=1e6", "duffing", dict(k_c=1e6)),
    ("c_c=0", "duffing", dict(c_c=0.0)),
    ("c_c=1e3", "duffing", dict(c_c=1e3)),
    ("d=0.01", "duffing", dict(d=0.01)),
    ("d=100", "duffing", dict(d=100.0)),
    ("F=10", "duffing", dict(F=10.0)),
    ("F=100", "duffing", dict(F=100.0)),
    ("c=1e-3", "duffing", dict(c=1e-3)),
    ("k2=1", "duffing", dict(k2=1.0)),
    ("k2=10", "duffing", dict(k2=10.0)),
    ("no-tension", "duffing", dict(law="no-tension")),
    ("bilinear base", "bilinear", {}),
    ("bilinear k2=1e3", "bilinear", dict(k2=1e3)),
    ("bilinear k2=1e4", "bilinear", dict(k2=1e4)),
    # corners
    ("k_c=1e6 c_c=1e3", "duffing", dict(STIFF)),
    ("k_c=1e6 c_c=1e3 no-tension", "duffing", dict(STIFF, law="no-tension")),
    ("k_c=1e6 c_c=0", "duffing", dict(k_c=1e6, c_c=0.0)),
    ("k_c=8 c_c=1e3 no-tension", "duffing", dict(c_c=1e3, law="no-tension")),
    ("k_c=1e6 c_c=1e3 d=0.01", "duffing", dict(STIFF, d=0.01)),
    ("k_c=1e6 c_c=1e3 F=100", "duffing", dict(STIFF, F=100.0)),
    ("k_c=1e6 c_c=1e3 k2=10", "duffing", dict(STIFF, k2=10.0)),
    ("k_c=1e6 c_c=0 no-tension", "duffing", dict(k_c=1e6, c_c=0.0, law="no-tension")),
    ("bilinear k2=1e4 k_c=1e6 c_c=1e3", "bilinear", dict(STIFF, k2=1e4)),
    ("bilinear k2=1e4 k_c=1e6 c_c=1e3 no-tension", "bilinear",
     dict(STIFF, k2=1e4, law="no-tension")),
]


def load() -> str:
    try:
        return " ".join(f"{v:.2f}" for v in os.getloadavg())
    except OSError:
        return "n/a"


def case_problem(model: str, changes: dict, **integrator) -> Problem:
    system = get_system(model, 2)
    values = {**system.defaults(), **BASE[model], **changes}
    return Problem(system, values, IntegratorSettings(**integrator))


def case_states(model: str, side: int) -> np.ndarray:
    lo, hi = get_system(model, 2).extra["catalogue_box"]["x"]
    x = np.linspace(lo, hi, side)
    x1, x2 = np.meshgrid(x, x, indexing="ij")
    z = np.zeros(x1.size)
    return np.column_stack([x1.ravel(), z, x2.ravel(), z])


def aligned_difference(a, b) -> float:
    """Scaled max difference of two orbits' section points over the cyclic shifts (the
    two runs may stop at different section indices of the same orbit)."""
    if a.shape != b.shape or a.size == 0:
        return math.inf
    scale = max(1.0, float(np.max(np.abs(a))))
    return min(float(np.max(np.abs(np.roll(a, s, axis=0) - b))) for s in range(len(a))) / scale


def run_one(task):
    """Everything measured for one initial condition of one case (in a worker)."""
    case_index, y0 = task
    _, model, changes = CASES[case_index]
    auto = case_problem(model, changes)
    dopri5 = case_problem(model, changes, method="dopri5")
    tight = case_problem(model, changes, **TIGHT)
    t = time.perf_counter()
    a = classify_state(auto, y0)
    wall_auto = time.perf_counter() - t
    status_dopri5, wall_dopri5, same = a.status, math.nan, True
    if a.counters["stiff_steps"] > 0:  # else auto took dopri5's steps exactly (tests/kernels)
        t = time.perf_counter()
        d = classify_state(dopri5, y0)
        wall_dopri5 = time.perf_counter() - t
        status_dopri5 = d.status
        same = (a.status == d.status
                and (a.status != 0 or aligned_difference(a.orbit, d.orbit) < SAME_ORBIT))
    # accuracy at the stroboscopic points against the tight reference
    rr = record_trajectory(tight, y0, 0.0, FLOW_PERIODS, 1)
    flow_error = {}
    for rtol in (1e-8, 1e-10):  # an error that shrinks with rtol is sensitivity, not a bug
        ra = record_trajectory(auto.with_integrator(rtol=rtol, atol=rtol * 1e-2), y0, 0.0,
                               FLOW_PERIODS, 1)
        flow_error[rtol] = math.nan
        if ra.status == 0 and rr.status == 0:
            flow_error[rtol] = float(np.max(np.abs(ra.section_y - rr.section_y))
                                     / max(1.0, np.max(np.abs(rr.section_y))))
    residual = math.nan
    if a.status == 0:  # is the reported orbit a periodic orbit of the tight flow?
        st, y, _ = flow(tight, a.orbit[0], 0.0, a.period * auto.period)
        residual = (float(np.max(np.abs(y - a.orbit[0])) / max(1.0, np.max(np.abs(y))))
                    if st == 0 else math.inf)
    c = a.counters
    return dict(case=case_index, status=a.status, period=a.period, wall_auto=wall_auto,
                steps=c["steps"], stiff=c["stiff_steps"], switches=c["method_switches"],
                status_dopri5=status_dopri5, wall_dopri5=wall_dopri5, same=same,
                flow_error=flow_error[1e-8], flow_error_fine=flow_error[1e-10],
                residual=residual)


def warm_up() -> None:
    """Compile (or load) every kernel a worker will run, for both models, outside the
    timings: one stiff initial condition each, with the dopri5 comparison forced."""
    for model, changes in (("duffing", STIFF), ("bilinear", STIFF)):
        y0 = np.array([2.0, 0.0, -2.0, 0.0])
        for pr in (case_problem(model, changes), case_problem(model, changes, method="dopri5"),
                   case_problem(model, changes, **TIGHT)):
            classify_state(pr.with_integrator(max_periods=2), y0)
            record_trajectory(pr, y0, 0.0, 1, 1)
            flow(pr, y0, 0.0, 1.0)


def status_text(counts: Counter) -> str:
    """'64 converged' or '60 converged, 4 unresolved (step budget ...)'."""
    parts = []
    for code in sorted(counts):
        kind = STATUS_TABLE[code][0]
        reason = "" if code == 0 else f" [{short_reason(code)}]"
        parts.append(f"{counts[code]} {kind}{reason}")
    return ", ".join(parts)


def short_reason(code: int) -> str:
    return {1: "no period within max_periods", 2: "non-finite or beyond bound",
            3: "step budget", 4: "chattering", 5: "step underflow"}[code]


def summarise(rows: list[dict], chosen: list[int]) -> list[str]:
    out = []
    for i in chosen:
        name, model, _ = CASES[i]
        r = [x for x in rows if x["case"] == i]
        steps = sum(x["steps"] for x in r)
        stiff = sum(x["stiff"] for x in r)
        switches = sum(x["switches"] for x in r)
        counts = Counter(x["status"] for x in r)
        flows = [x["flow_error"] for x in r if not math.isnan(x["flow_error"])]
        fine = [x["flow_error_fine"] for x in r if not math.isnan(x["flow_error_fine"])]
        resid = [x["residual"] for x in r if not math.isnan(x["residual"])]
        wa = sum(x["wall_auto"] for x in r)
        ran = [x for x in r if not math.isnan(x["wall_dopri5"])]
        wd = (f"{sum(x['wall_dopri5'] for x in ran):.2f}" + (
            f" ({len(ran)} ICs; auto on them {sum(x['wall_auto'] for x in ran):.2f})"
            if len(ran) < len(r) else "")) if ran else "= auto"
        same = sum(x["same"] for x in ran)
        d_counts = Counter(x["status_dopri5"] for x in r)
        d_note = "" if d_counts == counts else f" (dopri5: {status_text(d_counts)})"
        out.append(
            f"| {name} | {model} | {steps - stiff} / {stiff} ({switches}) | "
            f"{status_text(counts)}{d_note} | {wa:.2f} | {wd} | "
            f"{f'{same}/{len(ran)}' if ran else '(identical)'} | "
            f"{fmt(max(flows)) if flows else 'n/a'} "
            f"({fmt(float(np.median(flows))) if flows else ''}; {len(flows)}) | "
            f"{fmt(max(fine)) if fine else 'n/a'} | {fmt(max(resid)) if resid else 'n/a'} |")
    return out


def fmt(x: float) -> str:
    return "inf" if math.isinf(x) else f"{x:.1e}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--side", type=int, default=8, help="initial conditions per axis")
    ap.add_argument("--out", type=Path, default=ROOT / "results/bench/extreme.md")
    ap.add_argument("--cases", default="", help="comma-separated case numbers (default all)")
    args = ap.parse_args()
    chosen = [int(c) for c in args.cases.split(",") if c] or list(range(len(CASES)))
    tasks = [(i, y0) for i in chosen for y0 in case_states(CASES[i][1], args.side)]
    load_start = load()
    print(f"{len(chosen)} cases x {args.side}^2 initial conditions on {WORKERS} workers "
          f"(load {load_start})", flush=True)
    with mp.get_context("fork").Pool(WORKERS, initializer=warm_up) as pool:
        t = time.perf_counter()
        rows = []
        for k, row in enumerate(pool.imap_unordered(run_one, tasks, chunksize=4), 1):
            rows.append(row)
            if k % 200 == 0:
                print(f"  {k}/{len(tasks)}", flush=True)
        wall = time.perf_counter() - t
    header = [
        "| case | model | auto steps explicit / stiff (method switches) | auto status over the "
        "plane | auto wall (s) | dopri5 wall (s) | same result as dopri5 | 10-period error "
        "vs tight ref: max (median; ICs) | same at rtol 1e-10: max | orbit residual under "
        "tight ref |",
        "|---|---|---|---|---:|---:|---|---|---|---|"]
    lines = summarise(rows, chosen)
    text = "\n".join([
        "# Extreme corpus: `auto` on stiff stops and extreme parameters", "",
        f"Command: `.venv/bin/python benchmarks/bench_extreme.py --side {args.side}`", "",
        f"Each case: {args.side} x {args.side} initial conditions (x1, x2) over the model's "
        "catalogue box, v1 = v2 = 0, t0 = 0; production settings (rtol 1e-8, atol 1e-10, "
        "convergence_tol 1e-6, max_periods 3000). Walls are summed over the initial "
        "conditions (one process each; 2 workers).", "",
        *header, *lines, "",
        f"Whole corpus: {wall:.1f} s on {WORKERS} workers; load average {load_start} at start,"
        f" {load()} at end (shared machine: timings indicative).", "",
        "Columns: steps summed over the plane (explicit = dopri5 steps inside auto, stiff = "
        "Rodas4 steps); plain dopri5 runs only on the initial conditions where auto took a "
        "stiff step (elsewhere auto takes exactly dopri5's steps, checked bit for bit in "
        "tests/kernels/test_auto.py): '= auto' / '(identical)' when there was none; "
        "'same result as dopri5': same status, and for converged runs the same "
        f"period and orbit to {SAME_ORBIT:g} (scaled); '10-period error': max over n <= "
        f"{FLOW_PERIODS} and the initial conditions of |y_auto(nT) - y_ref(nT)| / max(1, |y|), "
        "reference dopri5 at rtol 1e-12, atol 1e-14 (ICs: how many both finished); the next "
        "column reruns auto at rtol 1e-10, atol 1e-12: an error that shrinks ~100-fold is the "
        "trajectory's sensitivity (fast, large oscillations, many impacts), not a method "
        "failure; 'orbit "
        "residual': max over the converged runs of |Phi_ref^q(y*) - y*| / max(1, |y|) for the "
        "orbit point y* auto reported.", ""])
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text)
    print(text)


if __name__ == "__main__":
    main()
