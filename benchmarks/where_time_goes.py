"""Where a default basin sweep spends its time, measured through public functions only.

A single-process ``run_sweep`` gives the total; its two phases are then run on their own
under cProfile, as the sweep runs them: the catalogue (``prepare_catalogues`` and
``sweep_context``, which finds the orbits that capture trajectories) and classifying every
initial condition (``run_chunk`` on the whole plane). The share inside numba kernels is the
profiled own time of the functions defined in ``softimpact_cli/kernels/`` (a jitted
function shows in cProfile under its Python name and file, e.g. ``orbit.py(classify)``).
Also: how close the integrator runs to bare right-hand-side evaluations.
"""

from __future__ import annotations

import cProfile
import io
import pstats
import time
from pathlib import Path

import numpy as np
from _common import scene_at

from softimpact_cli.analysis.engine import Problem
from softimpact_cli.kernels import orbit as orbit_kernels
from softimpact_cli.sweep.chunks import run_chunk
from softimpact_cli.sweep.runner import prepare_catalogues, run_sweep, sweep_context

KERNELS = str(Path(orbit_kernels.__file__).parent)


def profiled(fn, *args):
    """(fn(*args), wall s, seconds of own time inside the numba kernels, pstats.Stats)."""
    prof = cProfile.Profile()
    t = time.perf_counter()
    prof.enable()
    out = fn(*args)
    prof.disable()
    wall = time.perf_counter() - t
    stats = pstats.Stats(prof)
    in_kernels = sum(row[2] for (path, _, _), row in stats.stats.items()
                     if path.startswith(KERNELS))
    return out, wall, in_kernels, stats


def phases(n_side: int, tmp: Path) -> list[str]:
    """The breakdown of a single-process default run of n_side^2 ICs, as text lines."""
    scene = scene_at(n_side)
    t = time.perf_counter()
    run_sweep(scene, tmp / "profile.h5", workers=1, overwrite=True)
    total = time.perf_counter() - t

    def catalogue():
        catalogues, names = prepare_catalogues(scene)
        return sweep_context(scene, catalogues, names, None)

    context, cat, k_cat, _ = profiled(catalogue)
    n = scene.grid.size * scene.initial_conditions.count
    _, chunks, k_chunk, stats = profiled(run_chunk, context, 0, n)
    rest = max(total - cat - chunks, 0.0)
    buf = io.StringIO()
    stats.stream = buf
    stats.strip_dirs().sort_stats("tottime").print_stats(12)
    top = [ln for ln in buf.getvalue().splitlines() if ln.strip()]
    start = next((i for i, ln in enumerate(top) if ln.lstrip().startswith("ncalls")), 0)
    return [
        f"single-process default run, {n} ICs ({n_side} x {n_side}), wall {total:.2f} s; "
        "each phase then run alone under cProfile (its profiled wall includes the "
        "profiler's overhead on Python code):",
        f"  catalogue, Newton, critical distances, capture orbits: {cat:5.2f} s, of which "
        f"in numba kernels {k_cat:.2f} s ({100 * k_cat / max(cat, 1e-12):.0f} %)",
        f"  classifying the ICs (run_chunk): {chunks:6.2f} s, of which in numba kernels "
        f"{k_chunk:.2f} s ({100 * k_chunk / max(chunks, 1e-12):.0f} %); "
        f"{1e3 * chunks / n:.2f} ms per IC, Python overhead "
        f"{1e6 * (chunks - k_chunk) / n:.0f} us per IC",
        f"  plan, store, HDF5 write, assembly (total minus both): {rest:6.2f} s",
        "  cProfile of the classification, sorted by own time (numba kernels under their "
        "Python names, e.g. orbit.py(classify)):",
        *["    " + ln for ln in top[start:start + 13]],
    ]


def rhs_floor(periods: int = 400, repeats: int = 5) -> str:
    """How close the integrator runs to bare right-hand-side evaluations: one trajectory of
    the figure 6(d) pair on its attractor (no contact), CPU time of the whole integration
    against the same number of bare ``rhs`` calls in a compiled loop (best of repeats)."""
    from numba import njit

    scene = scene_at(2)
    problem = Problem(scene.system, scene.values, scene.integrator)
    T = problem.period
    y0 = np.array([1.0, 0.0, -1.0, 0.0])
    def integrate():
        return orbit_kernels.flow(problem.advance, problem.system.rhs, problem.params,
                                  y0.copy(), 0.0, periods * T, problem.kernel_args(),
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


class StageClock:
    """An ``echo`` for ``run_sweep`` that stamps the stages it announces: the catalogue
    ends when the line starting "catalogue:" is printed, after the "executor:" line."""

    def __init__(self):
        self.stamps: dict[str, float] = {}

    def __call__(self, line: str) -> None:
        self.stamps.setdefault(line.split(":", 1)[0], time.perf_counter())

    def catalogue_s(self) -> float:
        return self.stamps.get("catalogue", 0.0) - self.stamps.get("executor", 0.0)
