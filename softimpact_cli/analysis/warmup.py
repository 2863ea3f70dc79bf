"""Compile the numerical kernels ahead of time, and say so before a run that compiles them.

numba compiles each kernel on first use (minutes on 2 cores) and keeps the machine code
in a disk cache keyed by the kernel sources (``kernels.numba_cache``); later runs load it in
a fraction of a second. :func:`announce_compilation` prints one line on stderr when the
cache lacks a kernel the scene needs, so that the first run is not silent;
:func:`compile_all` (``python -m softimpact_cli.analysis.warmup``, run by ``make install``) runs a
tiny problem through every kernel signature the command line uses, so that no run compiles.

The test is cheap (a few ``stat`` calls) and exact for a fresh cache: numba writes one
index file per jitted function when it first saves that function's machine code, so a
missing index file means that function will be compiled. It does not tell the signatures
within one index apart: a run that pairs a cached system with a cached method for the
first time compiles (about a minute) without notice; after :func:`compile_all` none does.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..config import IntegratorSettings
from ..kernels import IMPACT_ADVANCE, METHODS, method_traits, orbit
from ..kernels.numba_cache import SAVES_LOCKED
from ..systems import REGISTRY, System, get_system, variational
from ..systems.chain import ChainModel, Kink, Stop, chain_system, chain_values
from .catalogue import SHOOTING, amplitude, orbit_points, refine_orbit
from .engine import Problem, RecurrenceCells, classify_state, flow, record_trajectory
from .lyapunov import lyapunov_spectrum
from .shooting import OrbitMap
from .step_stability import rk4_step_warning

COLD_MINUTES = 3  # measured: the demo's first sweep on a busy 2-core machine (issue 20)
NOTICE = ("softimpact: compiling numerical kernels (first run only, about {minutes} min on "
          "2 cores); cached in {folder}")

_announced = False


def _index_path(dispatcher) -> Path | None:
    """The numba index file of a cached jitted function (None when it has no disk cache,
    e.g. under NUMBA_DISABLE_JIT=1)."""
    cache_file = getattr(getattr(dispatcher, "_cache", None), "_cache_file", None)
    path = getattr(cache_file, "_index_path", None)
    return Path(path) if path else None


def _scene_kernels(model: str, bodies: int, method: str, catalogue: bool,
                   system=None) -> list:
    """The jitted functions a run of (model, bodies) (or of ``system``: a chain) with
    ``method`` calls first: the trajectory kernels, the method, the system, and the
    catalogue's variational equations."""
    system = system if system is not None else get_system(model, bodies)
    advance = (IMPACT_ADVANCE if system.extra.get("rigid") else
               {name: module.advance for name, module in METHODS.items()})[method]
    kernels = [orbit.classify_near, orbit.record, advance, system.rhs]
    if catalogue and system.model != "chain":
        body = get_system(model, 1)
        kernels += [orbit.flow, body.rhs, variational.variational_rhs(body)]
    return kernels


def missing_kernels(model: str = "duffing", bodies: int = 2, method: str = "auto",
                    catalogue: bool = True, system=None) -> list[str]:
    """Names of the kernels a run needs whose compiled code is not in the disk cache
    (``catalogue``: the run finds attractors first, as every kind but trajectory does;
    ``system``: the run's, when it is not a registered preset)."""
    missing = []
    for dispatcher in _scene_kernels(model, bodies, method, catalogue, system):
        path = _index_path(dispatcher)
        if path is not None and not path.is_file():
            missing.append(f"{dispatcher.py_func.__module__}.{dispatcher.__name__}")
    return missing


def cache_folder() -> Path | None:
    """The folder of this source version's compiled kernels (None without a disk cache)."""
    path = _index_path(orbit.classify_near)
    return path.parent.parent if path is not None else None


def compile_notice(scene=None) -> str | None:
    """The notice for a run of ``scene`` (a loaded scene, or None for the default pair),
    or None when every kernel it needs is cached."""
    if scene is None:
        model, bodies, method, catalogue = "duffing", 2, "auto", True
    else:
        model, bodies = scene.system.model, scene.system.bodies
        method = scene.integrator.resolved_method
        catalogue = (scene.catalogue is not None  # a catalogue kind searches without one
                     or getattr(scene.analysis, "searches_attractors", False))
    system = scene.system if scene is not None else None
    if not missing_kernels(model, bodies, method, catalogue, system):
        return None
    return NOTICE.format(minutes=COLD_MINUTES, folder=cache_folder())


def announce_compilation(scene=None, stream=None) -> None:
    """Print the compile notice on stderr once per process when this run will compile."""
    global _announced
    if _announced:
        return
    message = compile_notice(scene)
    if message:
        _announced = True
        print(message, file=stream or sys.stderr, flush=True)


@dataclass(frozen=True)
class Step:
    """One warm-up step: what it compiles and the seconds it took."""

    what: str
    seconds: float


def _steps(model: str | None = None) -> list:
    """(description, callable) pairs covering every kernel signature the CLI uses, for
    one model (None: all)."""
    def run_system(system, method):
        problem = Problem(system, defaults_of(system),
                          IntegratorSettings(method=method, max_periods=2, cell_size=0.5))
        state = np.zeros(system.dim)
        state[0] = 0.5
        cells = RecurrenceCells(problem.integrator.cell_size, 1, problem.integrator.max_periods)
        cells.remember(classify_state(problem, state, recurrence=cells), 1)  # cells path
        record_trajectory(problem, state, 0.0, 1, 4)
        flow(problem, state, 0.0, 0.25 * problem.period)

    def run_catalogue(system):  # the catalogue's steps after the search, at any x0
        problem = Problem(system, system.defaults(), SHOOTING)
        x0 = np.array([0.5, 0.0])
        refine_orbit(problem, x0, 1, max_iter=1)  # variational equations
        orbit_points(problem, x0, 2)
        amplitude(problem, x0, 1, samples=8)

    def run_lyapunov(system):  # Benettin on the variational equations (kind lyapunov)

        state = np.zeros(system.dim)
        state[0] = 0.5
        lyapunov_spectrum(Problem(system, defaults_of(system), SHOOTING), state, periods=2,
                          transient=0, segments=2, per_period=2)

    def run_rigid_variational(system):  # kinds lyapunov and continuation, rigid stops
        run_lyapunov(system)
        state = np.array([0.0, 1.0])  # an impact within the period: the reset's S
        OrbitMap(system, defaults_of(system), "stop.1.wall", 1).evaluate(state, 0.4)

    steps = []
    if model in (None, "chain"):  # the family: one set of kernels serves every chain
        chain = warmup_chain()
        for method in METHODS:
            steps.append((f"chain: {method}", lambda m=method: run_system(chain, m)))
        steps.append(("chain: Lyapunov exponents (Benettin, saltation)",
                      lambda: run_lyapunov(chain)))
        rigid = warmup_rigid_chain()  # each method wrapped in the impact loop
        for method in METHODS:
            if not method_traits(method).closed_form:  # a rigid stop is not linear
                steps.append((f"chain with a rigid stop: {method}",
                              lambda m=method: run_system(rigid, m)))
        # Benettin and the flow with the impact loop of dopri5 on the variational
        # equations: kinds lyapunov and continuation (the shooting's monodromy), and a
        # trajectory the first pass leaves unresolved, judged by its Lyapunov spectrum
        # (nonperiodic.section_spectrum; without it, 14 s of compiling the first time,
        # 2026-11-27)
        steps.append(("chain with a rigid stop: Lyapunov exponents (Benettin) and the "
                      "shooting's monodromy (the impact loop on the variational equations)",
                      lambda: run_rigid_variational(rigid)))
    for (name, bodies), system in sorted(REGISTRY.items()):
        if model is not None and name != model:
            continue
        kind = "pair" if bodies == 2 else "body"
        steps.append((f"{name} {kind}: rk4 step check",
                      lambda s=system: rk4_step_warning(Problem(s, s.defaults()))))
        for method in METHODS:
            if method_traits(method).closed_form and not system.piecewise_linear:
                continue
            steps.append((f"{name} {kind}: {method}", lambda s=system, m=method: run_system(s, m)))
        if bodies == 1:
            steps.append((f"{name} catalogue (Newton, variational equations)",
                          lambda s=system: run_catalogue(s)))
        steps.append((f"{name} {kind}: Lyapunov exponents (Benettin, saltation)",
                      lambda s=system: run_lyapunov(s)))
    return steps


# A chain that reaches every branch of the family's kernels: a kink, a stop between
# bodies, a wall stop; linear (so method "exact" compiles too). Its values by name.
_WARMUP_CHAIN = ChainModel(2, kinks=(Kink(1, "left"),),
                           stops=(Stop(1, 2), Stop(2, side="right", law="no-tension")))
_WARMUP_VALUES = chain_values(_WARMUP_CHAIN, 1.0, {}, kinks=[{"x": -1.0, "k": 2.0}],
                              stop_values=[{"d": 1.0}, {"wall": 1.0}])


def warmup_chain() -> System:
    return chain_system(_WARMUP_CHAIN)


# One body and a rigid wall (kernels/impacts.py): the impact loop of every method, which
# classify, record and flow take as their advance (one compiled set for every rigid chain).
_RIGID_CHAIN = ChainModel(1, stops=(Stop(1, side="right", law="rigid"),))
_RIGID_VALUES = chain_values(_RIGID_CHAIN, 1.0, {}, stop_values=[{"wall": 0.4, "r": 0.8}])


def warmup_rigid_chain() -> System:
    return chain_system(_RIGID_CHAIN)


def defaults_of(system: System) -> dict:
    """Parameter values to warm a system up with (a chain's have no defaults for its
    kinks' and stops' positions)."""
    if system.model != "chain":
        return system.defaults()
    return dict(_RIGID_VALUES if system.extra.get("rigid") else _WARMUP_VALUES)


def _timed(what: str, run) -> Step:
    start = time.perf_counter()
    run()
    return Step(what, time.perf_counter() - start)


def _report(step: Step, verbose: bool) -> Step:
    if verbose:
        print(f"  {step.what}: {step.seconds:.1f} s", file=sys.stderr, flush=True)
    return step


def _run_steps(model: str | None, verbose: bool) -> list[Step]:
    return [_report(_timed(what, run), verbose) for what, run in _steps(model)]


def _run_step(index: int) -> Step:
    """Warm-up step number ``index`` (in a worker process)."""
    return _timed(*_steps()[index])


def compile_all(verbose: bool = False, workers: int | None = None) -> list[Step]:
    """Run every warm-up step (each compiles what is not cached yet); their wall times.

    ``workers`` processes (default: one per core, at most the steps) take the steps in
    turn. They compile into one folder at once, which numba's own cache saves do not
    survive: two processes adding an entry to one kernel's index together could leave one
    model's entry naming the other's code (seen in a clean-clone CI run, 2026-11-25, when
    the models compiled in parallel without a lock); ``kernels.numba_cache`` therefore
    saves under a lock. Without POSIX locks, or with ``workers = 1``, one step after
    another in this process: 414 s on 2 cores (2026-11-26), against about half that in
    two processes.
    """
    steps = _steps()
    workers = min(workers or os.cpu_count() or 1, len(steps))
    if workers <= 1 or not SAVES_LOCKED:
        return _run_steps(None, verbose)

    context = multiprocessing.get_context("spawn")  # fresh processes: nothing compiled yet
    with ProcessPoolExecutor(workers, mp_context=context) as pool:
        return [_report(step, verbose) for step in pool.map(_run_step, range(len(steps)))]


MODELS_OPTION = "--models="  # one group of kernels: --models=duffing,bilinear or chain


def _models(args: list[str]) -> list[str] | None:
    """The models of ``--models=a,b`` (None: every model), or a SystemExit naming the
    allowed ones."""
    given = [a[len(MODELS_OPTION):] for a in args if a.startswith(MODELS_OPTION)]
    if not given:
        return None
    allowed = sorted({name for name, _ in REGISTRY} | {"chain"})
    models = [m for text in given for m in text.split(",") if m]
    unknown = [m for m in models if m not in allowed]
    if unknown or not models:
        raise SystemExit(f"--models: unknown model {', '.join(unknown) or '(none)'}; "
                         f"models: {', '.join(allowed)}")
    return models


def main(argv: list[str] | None = None) -> int:
    """``python -m softimpact_cli.analysis.warmup [-q] [--serial] [--models=a,b]``: compile
    every kernel into the disk cache (``--models``: only those models' kernels, one step
    after another; the benchmarks time the presets' and the chain family's apart)."""
    args = argv if argv is not None else sys.argv[1:]
    quiet = "-q" in args
    workers = 1 if "--serial" in args else None
    models = _models(args)
    folder = cache_folder()
    if not quiet:
        print(f"softimpact: compiling numerical kernels into {folder} (a few minutes, once "
              "per installed version)", file=sys.stderr, flush=True)
    start = time.perf_counter()
    if models is None:
        compile_all(verbose=not quiet, workers=workers)
    else:
        for model in models:
            _run_steps(model, verbose=not quiet)
    print(f"softimpact: kernels compiled and cached in {time.perf_counter() - start:.0f} s "
          f"({folder})", file=sys.stderr)
    return 0


if __name__ == "__main__":
    # run the imported module's main (as when it ran worker processes)
    from softimpact_cli.analysis.warmup import main as _main

    sys.exit(_main())
