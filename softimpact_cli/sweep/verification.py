"""Every sweep knows its label error: rerun a random sample at tight settings, bound the
disagreement, and tighten the whole sweep when the bound is too high.

After a sweep (basins, stability, map), ``n = [verification] sample_size(total)`` random
trajectories are rerun at ``sweep.check.tightened`` settings (rtol and atol / 100,
convergence_tol / 10, twice the periods, 4x the RK4 steps, capture off, each in its own
chunk so recurrence cells are off) and compared with the labels the sweep stored. The
share that disagrees gets a 95% Wilson interval ``[low, high]``; with ``threshold`` from
[verification]:

- ``high <= threshold``: "verified";
- no disagreement, but ``high > threshold``: "bounded" (the result is reported as what it
  is, a bound: "label error <= 3.70% (95%), measured on 100 reruns"; nothing is redone,
  there is nothing to fix, and nothing is noted: a clean run reads clean. The sample
  that would bound the error at the threshold is :func:`sample_for_threshold`);
- disagreements and ``high > threshold``: with ``tighten``, the whole sweep is redone on
  the next rung of :func:`ladder` and verified again, at most MAX_RUNGS times. Which rung
  comes first, the sample says: it is also rerun alone at the sweep's own settings without
  capture and cells; when those labels already disagree with the tight ones beyond the
  threshold, the tolerance is to blame (rtol and atol / 100 and 4x RK4 steps first, capture
  and cells kept), else capture and cells are (off first, then the tolerance). A redo that
  does not halve the disagreements ends the ladder (:func:`stalled`). The final result is
  kept, every attempt recorded (``verify_history``); status "tightened" when the final
  attempt is not over the threshold, else "over threshold" (as without ``tighten``).

The attributes (``verify_*``) go into the result. A result file gets ``verify_status =
PENDING`` before the reruns start, so a run killed while verifying leaves the complete
sweep, marked unverified; ``--resume`` then verifies it. Redone sweeps are written beside
the result (``RESULT.h5.tighter1`` ...; resumable like any sweep) and replace it when done.
"""

from __future__ import annotations

import json
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
import xarray as xr

from ..analysis.stability import Z95, wilson_interval
from ..config import IntegratorSettings, Scene, VerificationSettings
from ..store import add_attributes, open_result, update_attributes, write_result
from ..store.lock import output_lock
from ..store.provenance import command_line
from ..store.sweep_store import DamagedHeader, SweepStore, result_problem
from .check import check_sweep, tightened
from .executors import make_executor
from .pilot import choose_tolerance, scene_as_run
from .runner import refuse_existing, run_sweep

VERIFIED, BOUNDED, TIGHTENED, OVER = "verified", "bounded", "tightened", "over threshold"
INCONCLUSIVE = "inconclusive"  # what BOUNDED was called in results written before it
PENDING = ("not verified (interrupted while verifying; `softimpact sweep SCENE -o RESULT "
           "--resume` verifies it)")
MAX_RUNGS = 2
REDO_SUFFIX = ".tighter"


def disabled_status(by: str) -> str:
    """The status of a result whose verification was switched off ``by`` a flag or key."""
    return f"not verified (disabled by {by})"


def not_applicable(kind) -> str:
    """The status of a result of a kind that is not a sweep (an ``AnalysisKind``)."""
    if kind.check is not None:
        return (f"not applicable (a {kind.name} result has no sample of labels; "
                "`softimpact check SCENE` measures its error)")
    if kind.name == "design":
        return ("not applicable (a design screens many small sweeps whose shares carry "
                "Wilson intervals; verify the pick with a basins or stability scene)")
    return f"not applicable (a {kind.name} result has no sample of labels to rerun)"


def settings_text(s: IntegratorSettings) -> str:
    """The integrator settings that decide labels, as one line."""
    parts = [s.resolved_method]
    if not s.traits.closed_form:  # (the exact flow has no tolerance)
        parts += [f"rtol {s.rtol:.3g}", f"atol {s.atol:.3g}"]
    if s.traits.fixed_step:
        parts.append(f"{s.steps_per_period} steps per period")
    parts += [f"convergence_tol {s.convergence_tol:.3g}", f"{s.max_periods} periods",
              f"capture {s.capture_tol:g}" if s.capture_tol > 0 else "capture off",
              f"cells {s.cell_size:g} x {s.cell_hits}" if s.cell_size > 0 else "cells off"]
    return ", ".join(parts)


@dataclass(frozen=True)
class Attempt:
    """One verification of one result: ``disagreements`` of ``sample`` rerun trajectories
    (out of ``total``) with their 95% Wilson interval [ci_low, ci_high] (shares, 0..1).

    settings : the result's integrator settings (text); reference : the rerun's
    changes : {"A -> B": count}; check_wall_s : wall time of the reruns (s)
    run_wall_s : wall time of the sweep that made the result (s)
    """

    settings: str
    reference: str
    sample: int
    total: int
    disagreements: int
    ci_low: float
    ci_high: float
    changes: dict
    check_wall_s: float
    run_wall_s: float
    alone_disagreements: int | None = None  # the same settings without capture or cells

    def blame(self, threshold: float) -> str:
        """What the ladder should tighten first: "tolerance" when the run's settings
        without capture and cells already disagree beyond the threshold, else "shortcuts"
        (capture and recurrence cells)."""
        if not self.alone_disagreements:
            return "shortcuts"
        (_,), (high,) = wilson_interval(np.array([self.alone_disagreements]), self.sample)
        return "tolerance" if high > threshold else "shortcuts"

    @property
    def share(self) -> float:
        return self.disagreements / self.sample if self.sample else 0.0

    def outcome(self, threshold: float) -> str:
        """VERIFIED, BOUNDED or OVER (see the module docstring)."""
        if self.ci_high <= threshold:
            return VERIFIED
        return BOUNDED if self.disagreements == 0 else OVER


def sample_for_threshold(threshold: float) -> int:
    """The fewest reruns whose zero disagreements put the upper end of the 95% Wilson
    interval at or below ``threshold`` (a share): z^2 / (n + z^2) <= threshold, i.e.
    n >= z^2 (1 - threshold) / threshold (765 for 0.5%)."""
    n = math.ceil(Z95 * Z95 * (1.0 - threshold) / threshold)
    return n if Z95 * Z95 / (n + Z95 * Z95) <= threshold else n + 1  # rounding


def check_result(scene: Scene, ds: xr.Dataset, sample: int, seed: int, executor=None
                 ) -> Attempt:
    """Rerun ``sample`` random trajectories of the sweep result ``ds`` (of ``scene``) at
    tightened settings and compare with its stored labels."""
    report = check_sweep(scene, sample, seed, result=ds, executor=executor)
    (low,), (high,) = wilson_interval(np.array([report["changed"]]), max(report["sample"], 1))
    return Attempt(settings=settings_text(scene.integrator),
                   reference=settings_text(tightened(scene.integrator)),
                   sample=report["sample"], total=int(ds.attrs["n"]),
                   disagreements=report["changed"], ci_low=float(low), ci_high=float(high),
                   changes=report["changes"], check_wall_s=report["tight_wall_s"],
                   run_wall_s=float(ds.attrs["wall_s"]),
                   alone_disagreements=report.get("changed_alone"))


def ladder(s: IntegratorSettings, blame: str = "shortcuts"
           ) -> list[tuple[str, IntegratorSettings]]:
    """The rungs a sweep over the threshold is redone on, each tighter than the one
    before: (what changed, settings). A rung that would change nothing is left out.
    ``blame`` (:meth:`Attempt.blame`) "tolerance": the tolerance first, capture and cells
    kept (they cost nothing in labels there), then both. The exact flow has no tolerance
    to tighten: its one rung is capture and cells off."""
    if s.traits.closed_form:
        blame = "shortcuts"
    if blame == "tolerance":
        tighter = replace(s, rtol=max(s.rtol / 100, 1e-14), atol=s.atol / 100,
                          steps_per_period=4 * s.steps_per_period)
        rungs = [("rtol and atol / 100, 4x RK4 steps", tighter)]
        if s.cell_size > 0 or s.capture_tol > 0:
            rungs.append(("rtol and atol / 100, 4x RK4 steps, cells and capture off",
                          replace(tighter, cell_size=0.0, capture_tol=0.0)))
        return rungs[:MAX_RUNGS]
    rungs = []
    if s.cell_size > 0 or s.capture_tol > 0:
        s = replace(s, cell_size=0.0, capture_tol=0.0)
        rungs.append(("recurrence cells and capture off", s))
    if s.traits.closed_form:
        return rungs
    s = replace(s, rtol=max(s.rtol / 100, 1e-14), atol=s.atol / 100,
                steps_per_period=4 * s.steps_per_period)
    rungs.append(("rtol and atol / 100, 4x RK4 steps"
                  + (" (cells and capture off)" if rungs else ""), s))
    return rungs[:MAX_RUNGS]


def rung_scene(scene: Scene, description: str, settings: IntegratorSettings) -> Scene:
    """The scene redone at ``settings``; its stored text says so (its hash differs)."""
    return replace(scene, integrator=settings,
                   text=scene.text + f"\n# verification: redone with {description} "
                                     f"({settings_text(settings)})\n")


def verify_sweep(scene: Scene, ds: xr.Dataset, redo: Callable[[Scene, int], xr.Dataset],
                 sample: int | None = None, executor=None,
                 echo: Callable[[str], None] = lambda s: None) -> xr.Dataset:
    """Verify the sweep result ``ds`` of ``scene`` and, when it is over the threshold,
    redo it on the tightening ladder (``redo(scene, rung number) -> dataset``).

    ``sample`` overrides the [verification] sample size (``--check N``). Returns the
    final dataset with the ``verify_*`` attributes.
    """
    settings = scene.verification or VerificationSettings()  # a Scene built by hand
    total = int(ds.attrs["n"])
    n = min(sample if sample is not None else settings.sample_size(total), total)
    started = time.perf_counter()
    echo(f"verification: rerunning {n} of {total} trajectories at "
         f"{settings_text(_reference(scene))}")
    attempts = [check_result(scene, ds, n, settings.seed, executor)]
    blame = attempts[0].blame(settings.threshold)
    for rung, (description, tighter) in enumerate(
            ladder(scene.integrator, blame) if settings.tighten else (), start=1):
        if attempts[-1].outcome(settings.threshold) != OVER or stalled(attempts):
            break
        echo(f"verification: {_numbers(attempts[-1])} > {_percent(settings.threshold)}; "
             f"redoing the whole sweep with {description}")
        scene = rung_scene(scene, description, tighter)
        kept = {k: v for k, v in ds.attrs.items() if k.startswith("pilot_")}
        ds = redo(scene, rung)
        ds.attrs.update(kept)  # how the first run's tolerance was chosen stays on record
        attempts.append(check_result(scene, ds, n, settings.seed, executor))
    ds.attrs.update(attributes(attempts, settings.threshold, settings.tighten,
                               time.perf_counter() - started, settings.seed))
    return ds


def stalled(attempts: list[Attempt]) -> bool:
    """Whether the last redo failed to halve the disagreements of the attempt before it:
    tightening is then not what the labels need (near a fractal boundary a start's label
    depends on every digit of its integration, at any tolerance), and a further rung
    would redo the whole sweep for nothing."""
    return (len(attempts) > 1
            and 2 * attempts[-1].disagreements > attempts[-2].disagreements)


def _reference(scene: Scene) -> IntegratorSettings:
    return tightened(scene.integrator)


def _percent(share: float) -> str:
    return f"{100 * share:.2f}%"


def _numbers(a: Attempt) -> str:
    return (f"{a.disagreements} / {a.sample} disagree, 95% interval "
            f"[{_percent(a.ci_low)}, {_percent(a.ci_high)}]")


def final_status(attempts: list[Attempt], threshold: float) -> str:
    """VERIFIED, BOUNDED or OVER for one attempt; TIGHTENED or OVER after redoing."""
    last = attempts[-1].outcome(threshold)
    if len(attempts) == 1:
        return last
    return OVER if last == OVER else TIGHTENED


def status_message(attempts: list[Attempt], threshold: float, tighten: bool) -> str:
    """What the status means for this result, in one sentence."""
    status, last = final_status(attempts, threshold), attempts[-1]
    limit = _percent(threshold)
    if status == VERIFIED:
        return f"the label error is below {limit} (95% upper bound)"
    if status == BOUNDED:
        needed = sample_for_threshold(threshold)
        return (f"no label changed in {last.sample} reruns: the label error is at most "
                f"{_percent(last.ci_high)} (95% upper bound); {needed} reruns without a "
                f"change would bound it at {limit} (--check {needed}, or [verification] "
                f"min_sample = {needed})")
    if status == TIGHTENED:
        return (f"the first run was over {limit}; redone {len(attempts) - 1} time(s) at "
                f"tighter settings, now {last.outcome(threshold)}")
    why = ("[verification] tighten = false" if not tighten else
           f"a redo at tighter settings did not halve the disagreements "
           f"({attempts[-2].disagreements} -> {last.disagreements} of {last.sample}): "
           "labels this sensitive (a fractal boundary) change with any tolerance, so no "
           "further rung was run" if stalled(attempts) else
           f"still over after {len(attempts) - 1} redo(s), the last rung of the ladder"
           if len(attempts) > 1 else "no tighter rung")
    return (f"the label error may exceed {limit} ({why}); the result is kept as run: "
            "tighten [integrator] by hand")


def attributes(attempts: list[Attempt], threshold: float, tighten: bool, wall_s: float,
               seed: int) -> dict:
    """The ``verify_*`` attributes of a result verified by ``attempts`` (the last one
    judged the result kept)."""
    last = attempts[-1]
    return {
        "verify_status": final_status(attempts, threshold),
        "verify_message": status_message(attempts, threshold, tighten),
        "verify_sample": last.sample, "verify_total": last.total,
        "verify_disagreements": last.disagreements, "verify_share": last.share,
        "verify_ci95_low": last.ci_low, "verify_ci95_high": last.ci_high,
        "verify_threshold": threshold, "verify_tighten": int(tighten), "verify_seed": seed,
        "verify_settings": last.reference, "verify_run_settings": last.settings,
        "verify_changes": ", ".join(f"{k}: {v}" for k, v in last.changes.items()) or "none",
        "verify_check_wall_s": last.check_wall_s, "verify_wall_s": wall_s,
        "verify_rungs": len(attempts) - 1,
        "verify_blame": (attempts[0].blame(threshold)
                         if attempts[0].alone_disagreements is not None else "n/a"),
        "verify_history": json.dumps([{**asdict(a), "outcome": a.outcome(threshold)}
                                      for a in attempts]),
    }


# ---------------------------------------------------------------- result files


def redo_path(out: Path, rung: int) -> Path:
    """Where the sweep redone on ``rung`` is written before it replaces ``out``."""
    return out.with_name(f"{out.name}{REDO_SUFFIX}{rung}")


def remove_redo_files(out: Path) -> None:
    """The redone sweeps beside ``out`` and their chunk folders."""
    for rung in range(1, MAX_RUNGS + 1):
        SweepStore(redo_path(out, rung)).remove()


def pending(out: Path, n_total: int) -> bool:
    """Whether ``out`` is a complete sweep of ``n_total`` trajectories whose verification
    was interrupted (a header that only says it is complete is left to the resume)."""
    try:
        header = SweepStore(out).header()
    except DamagedHeader:
        return False
    return (header is not None and int(header.attrs.get("complete", 0)) == 1
            and str(header.attrs.get("verify_status", "")) == PENDING
            and result_problem(header, n_total) is None)


def sweep_verified(scene: Scene, out: Path, verify: bool = True, sample: int | None = None,
                   resume: bool = False, echo: Callable[[str], None] = lambda s: None,
                   **run_options) -> xr.Dataset:
    """Run (or resume) the sweep ``scene`` into ``out`` and verify it (``verify`` False, or
    [verification] enabled = false: recorded as not verified). ``run_options`` go to
    ``run_sweep`` (workers, scheduler, overwrite, chunk_size, progress)."""
    with output_lock(out, command_line()):
        enabled = verify and (scene.verification is None or scene.verification.enabled)
        executor = make_executor(run_options.get("workers"), run_options.get("scheduler"))
        if resume and pending(out, scene.grid.size * scene.initial_conditions.count):
            echo(f"resume: {out} is complete; finishing its verification")
            ds = open_result(out)
            scene = scene_as_run(scene, ds.attrs)
        else:
            if enabled:
                if not resume:  # refused before the pilot spends anything
                    refuse_existing(out, bool(run_options.get("overwrite")))
                scene, extra = choose_tolerance(scene, sample, executor, echo)
                extra["verify_status"] = PENDING  # until the verification below ends
            else:
                by = "--no-verify" if not verify else "[verification] enabled = false"
                extra = {"verify_status": disabled_status(by)}
            ds = run_sweep(scene, out, resume=resume, echo=echo, attrs=extra, **run_options)
            if any(ds.attrs.get(k) != value for k, value in extra.items()):
                add_attributes(out, extra)  # a run found complete already: not written
                ds.attrs.update(extra)
        if not enabled:
            return ds
        options = {k: v for k, v in run_options.items() if k != "overwrite"}

        def redo(tighter: Scene, rung: int) -> xr.Dataset:
            path = redo_path(out, rung)

            return run_sweep(tighter, path, resume=resume and SweepStore(path).exists(),
                             overwrite=True, echo=echo, **options)

        written, attrs = ds, dict(ds.attrs)  # what ``out`` holds now
        ds = verify_sweep(scene, ds, redo, sample, executor, echo)
        if ds is written:  # not redone: only the verify_* attributes are new
            update_attributes(out, attrs, ds.attrs)
        else:
            write_result(ds, out)
        remove_redo_files(out)
    return ds
