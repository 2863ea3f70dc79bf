"""The library functions the command line calls, one per command that does more than read
its options: ``cli.py`` parses, calls one of these and exits with the status it returns.
They import the analyses, xarray and the store, which ``softimpact --help`` and the
command line's start do without: ``cli.py`` imports this module inside the commands.

Each writes through a :class:`Console` (stdout and stderr lines, a progress-bar factory,
what an interruption keeps), so that tests call them directly; an error a user can cause
raises ``ConfigError`` (one line, exit status 2) before anything is computed.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from typing import Any

from .analysis.engine import Problem
from .analysis.step_stability import rk4_step_warning
from .analysis.warmup import announce_compilation
from .api import measure as measure_result
from .api import open_result, read_result, shrink_scene
from .api import sweep as run_to_file
from .config import ConfigError, check_writable, result_path
from .kinds import get as kind_of
from .kinds import sweep_kinds
from .kinds.design_settings import with_target
from .kinds.results import (
    compare_results,
    describe,
    format_comparison,
    format_summary,
    outcome_warnings,
)
from .kinds.run import plan_text
from .kinds.scene import load_scene
from .plot import save
from .report.compare import limits_exceeded
from .report.fractality import fractality_lines
from .report.info import compare_shares, incomplete_summary
from .report.outcomes import STRICT_STATUS, outcome_notes
from .report.verification import verification_line
from .reproduce.report import reproduce as run_reproduce
from .reproduce.runs import CACHE
from .reproduce.table import summary
from .store.catalogue_cache import cache_folder, clear, switched_off
from .store.catalogue_cache import info as cache_state
from .store.sweep_store import SweepStore
from .sweep.interrupt import modified, sweep_kept
from .sweep.verification import OVER, VERIFIED

__all__ = [
    "Console", "RunOptions", "SweepOptions", "announce_compilation", "cache_folder",
    "cache_state", "clear", "compare_files", "design_scene", "draw_result", "info_text",
    "measure_to_file", "open_result", "read_result", "reproduce_to_file", "sweep_scene",
]


def _to_stderr(text: str) -> None:
    print(text, file=sys.stderr)


def _nowhere(kept: Callable[[], str]) -> None:
    """A console that is not interrupted: what a run would keep is not asked for."""


@dataclass(frozen=True)
class Console:
    """Where a command writes. ``out``: a line of its output (stdout); ``err``: a line of
    notes, warnings and stages (stderr); ``progress(total, initial=0, unit=...)``: a
    progress bar, the callable fed with counts or a chunk's label codes (None: none);
    ``keep(kept)``: told, once a run may leave a partial result, the callable that says
    what an interruption keeps and the command that resumes."""

    out: Callable[[str], None] = print
    err: Callable[[str], None] = _to_stderr
    progress: Callable[..., Any] | None = None
    keep: Callable[[Callable[[], str]], None] = _nowhere

    def note(self, text: str) -> None:
        self.err(f"softimpact: note: {text}")

    def warn(self, text: str) -> None:
        self.err(f"softimpact: warning: {text}")


@dataclass(frozen=True)
class RunOptions:
    """The options ``softimpact sweep`` and ``softimpact design`` share: the result file
    (``output``, None: the scene's [output] path; ``overwrite``), where the run goes
    (``workers``, ``scheduler``), ``quiet`` (no stages, no progress), ``quick``
    (previews), ``dry_run`` (the plan only) and ``strict`` (warnings become exit status
    3, after the result is written)."""

    output: str | None = None
    overwrite: bool = False
    workers: int | None = None
    scheduler: str | None = None
    quiet: bool = False
    quick: bool = False
    dry_run: bool = False
    strict: bool = False


@dataclass(frozen=True)
class SweepOptions(RunOptions):
    """``softimpact sweep``'s own options besides :class:`RunOptions`: ``resume``,
    ``chunk_size`` (trajectories), ``resolution`` (a plane's cells per axis at most),
    ``check_n`` (trajectories the verification reruns), ``no_verify``, ``no_cache``
    (search the catalogue afresh)."""

    resume: bool = False
    chunk_size: int | None = None
    resolution: int | None = None
    check_n: int | None = None
    no_verify: bool = False
    no_cache: bool = False


def sweep_scene(scene: str, options: SweepOptions, console: Console) -> int:
    """``softimpact sweep SCENE``: run the scene into its result file, report what it
    holds, its verification and its outcome warnings; returns the exit status (0, or
    ``STRICT_STATUS`` with ``strict`` when a warning applies)."""
    o = options
    if o.check_n and o.no_verify:
        raise ConfigError(f"--check {o.check_n} and --no-verify: choose one (--check N sets "
                          "how many trajectories the verification reruns)")
    # --no-cache: the switch of SOFTIMPACT_NO_CACHE=1, for this command only
    with switched_off() if o.no_cache else nullcontext():
        sc = shrink_scene(load_scene(scene), o.quick, o.resolution)
        out = _writable_result(sc, scene, o.output)
        if o.dry_run:
            console.out(plan_text(replace(sc, output=out), o.workers, o.chunk_size))
            return 0
        _check_rk4_step(sc, o.strict, console)
        announce_compilation(sc)
        if kind_of(sc.analysis.kind).sweep:
            return _run_sweep(sc, scene, out, o, console)
        if o.resume:
            raise ConfigError(f"{scene}: --resume is for sweeps (kinds "
                              f"{', '.join(sweep_kinds())}); a {sc.analysis.kind} reruns whole")
        return _run_whole(sc, out, o, console)


def design_scene(scene: str, target: str | None, options: RunOptions,
                 console: Console) -> int:
    """``softimpact design SCENE``: a design scene (``target`` replacing its [analysis]
    target) run into its result file; returns the exit status as :func:`sweep_scene`."""
    sc = load_scene(scene)
    if sc.analysis.kind != "design":
        raise ConfigError(f"{scene}: [analysis] kind: must be \"design\" for this command, "
                          f"got {sc.analysis.kind!r}")
    sc = with_target(sc, target) if target is not None else sc
    sc = shrink_scene(sc, options.quick)
    out = _writable_result(sc, scene, options.output)
    if options.dry_run:
        console.out(plan_text(replace(sc, output=out)))
        return 0
    announce_compilation(sc)
    return _run_whole(sc, out, options, console)


def _writable_result(sc, scene: str, output: str | None) -> Path:
    """The result path (``output``, else the scene's [output] path), checked writable."""
    out = result_path(sc, output)
    check_writable(out, scene if not output else "command line",
                   "-o/--output" if output else "[output] path")
    return out


def _stages(options: RunOptions, console: Console) -> Callable[[str], None]:
    return (lambda s: None) if options.quiet else console.err


def _run_sweep(sc, scene: str, out: Path, o: SweepOptions, console: Console) -> int:
    """Run a sweep kind chunk by chunk (resumable), verify it and report."""
    flags = ("--quick",) * o.quick + (("--resolution", str(o.resolution))
                                      if o.resolution else ())
    console.keep(partial(sweep_kept, out, scene, flags, modified(out)))
    ds = run_to_file(sc, out, workers=o.workers, scheduler=o.scheduler, resume=o.resume,
                     overwrite=o.overwrite, chunk_size=o.chunk_size,
                     echo=_stages(o, console),
                     progress=None if o.quiet else console.progress, verify=not o.no_verify,
                     verify_sample=o.check_n)
    console.out(f"{sc.analysis.kind}: {ds.attrs['n']} trajectories "
                f"({ds.attrs['wall_s']:.1f} s) -> {out}")
    over = _report_verification(ds, console)
    status = _warn_outcomes(ds, sc, o.strict, console)
    return status or (STRICT_STATUS if over and o.strict else 0)


def _run_whole(sc, out: Path, o: RunOptions, console: Console) -> int:
    """Run a scene that is not a sweep (every kind but basins, stability, map), write its
    result, print what its kind reports, the outcome line and the outcome warnings."""
    kind = kind_of(sc.analysis.kind)
    progress = None if o.quiet or console.progress is None else partial(
        console.progress, unit=kind.progress_unit)
    ds = run_to_file(sc, out, overwrite=o.overwrite, workers=o.workers,
                     scheduler=o.scheduler, progress=progress, echo=_stages(o, console))
    if kind.report is not None:
        console.out(kind.report(ds))
    console.out(f"{sc.analysis.kind}: {ds.attrs.get('outcome', 'done')}"
                + (f", period {ds.attrs['period']}" if ds.attrs.get("period") else "")
                + f" ({ds.attrs['wall_s']:.2f} s) -> {out}")
    return _warn_outcomes(ds, sc, o.strict, console)


def _warn_outcomes(ds, scene, strict: bool, console: Console) -> int:
    """Warn about a result mostly unresolved or diverged, or an empty catalogue; returns
    ``STRICT_STATUS`` (3) when a warning applies with ``strict`` (the result is written),
    else 0."""
    for note in outcome_notes(ds):
        console.note(note)
    # every kind with outcome shares (sweeps, tipping, design) runs the second stage
    messages = outcome_warnings(ds, scene.integrator.max_periods,
                                section_periods=scene.integrator.section_periods)
    for message in messages:
        console.warn(message)
    return STRICT_STATUS if messages and strict else 0


def _check_rk4_step(scene, strict: bool, console: Console) -> None:
    """Warn (or, with ``strict``, refuse) when the scene's fixed RK4 step is unstable at
    any of its grid points (the first 10 000)."""
    points = [dict(scene.values)]
    if scene.grid is not None and scene.system.bodies == 2:
        points = [{**scene.values, **{k: v for k, v in scene.grid.point(i).items()
                                      if k != "t0"}} for i in range(min(scene.grid.size, 10_000))]
    for values in points:
        message = rk4_step_warning(Problem(scene.system, values, scene.integrator))
        if message:
            if strict:
                raise ConfigError(f"{scene.source}: {message}")
            console.warn(f"{scene.source}: {message}")
            return


def _report_verification(ds, console: Console) -> bool:
    """Print the label-error line; a note when some rerun label disagreed although the
    error is within the threshold, a warning when it is over. A clean run (none disagreed,
    whatever the bound) gets no note. Returns whether it is over the threshold."""
    console.out(verification_line(ds.attrs))
    status = ds.attrs["verify_status"]
    if status == VERIFIED and int(ds.attrs.get("verify_disagreements", 0)) > 0:
        console.note(f"{ds.attrs['verify_disagreements']} of {ds.attrs['verify_sample']} "
                     f"rerun labels disagreed ({ds.attrs['verify_changes']}); "
                     f"{ds.attrs['verify_message']}")
    if status == OVER:
        console.warn(f"label error over the threshold: {ds.attrs['verify_message']}")
    return status == OVER


def info_text(result: str, as_json: bool = False, compare: str | None = None) -> str:
    """``softimpact info RESULT``: what it holds (text, or JSON with ``as_json``); with
    ``compare`` (a stability result), RESULT's plane basin shares (a basins result)
    against the 4-D basin stability at their common parameter points."""
    ds = read_result(result)
    if compare:
        return _shares_against_stability(ds, result, compare, as_json)
    if int(ds.attrs.get("complete", 1)) == 0:
        info = incomplete_summary(ds, len(SweepStore(result).done()))
    else:
        info = describe(ds)
    return json.dumps(info, indent=2) if as_json else format_summary(info, ds)


def _shares_against_stability(ds, result: str, compare: str, as_json: bool) -> str:
    other = read_result(compare)
    if ds.attrs.get("analysis") != "basins" or other.attrs.get("analysis") != "stability":
        raise ConfigError(f"--compare: RESULT must be a basins result and {compare} a "
                          "stability result")
    rows = compare_shares(ds, other)
    if not rows:
        raise ConfigError(f"--compare: {result} and {compare} share no parameter point")
    if as_json:
        return json.dumps({"comparison": rows}, indent=2)
    lines = []
    for row in rows:
        lines.append(f"d={row['d']:.6g}, phi={row['phi']:.6g}, k_c={row['k_c']:.6g}, "
                     f"c_c={row['c_c']:.6g} (t0 plane {row['t0_plane']}, "
                     f"stability {row['t0_stability']})")
        lines.append(f"  {'solution':16s} {'plane':>7s} {'4-D':>7s}  95% interval")
        for name, v in row["shares"].items():
            ci = v["ci95"] or [float("nan")] * 2
            lines.append(f"  {name:16s} {v['plane']:7.3f} {v['stability']:7.3f}  "
                         f"[{ci[0]:.3f}, {ci[1]:.3f}]")
    return "\n".join(lines)


def compare_files(result_a: str, result_b: str, as_json: bool = False,
                  **limits: float | None) -> tuple[str, list[str]]:
    """``softimpact compare``: the differences of ``result_b`` from ``result_a`` as text
    (JSON with ``as_json``), and the ``limits`` they exceed (``max_label_change``,
    ``max_share_change``, ``max_d_change``; None: no limit), each said in a few words."""
    report = compare_results(read_result(result_a), read_result(result_b), result_a,
                             result_b)
    why = limits_exceeded(report, limits.get("max_label_change"),
                          limits.get("max_share_change"), limits.get("max_d_change"))
    text = (json.dumps({**report, "failed": why}, indent=2) if as_json
            else format_comparison(report))
    return text, why


def measure_to_file(result: str, output: str, **options) -> str:
    """``softimpact measure``: the fractality of a basins result (``options`` of
    ``api.measure``: box_sizes, radii, wada_radius, wada_tol, overwrite) written to
    ``output``; returns what it found, a line per plane and the file written."""
    check_writable(output, "command line", "-o/--output")
    ds = measure_result(result, output, **options)
    return "\n".join([*fractality_lines(ds), f"fractality -> {output}"])


def draw_result(result: str, output: str, dpi: int, kind: str, draw,
                complete: bool = False, accept=None, expected: str | None = None) -> Path:
    """Open RESULT, check that it holds a ``kind`` analysis (or passes ``accept``, a
    predicate on its attributes, described by ``expected``), draw it with ``draw(ds)``
    (a ``plot`` function, returning the Figure) and save it to OUTPUT; returns the path
    written."""
    ds = read_result(result)
    ok = accept(ds.attrs) if accept else ds.attrs.get("analysis") == kind
    if not ok or (complete and int(ds.attrs.get("complete", 0)) != 1):
        what = expected or (f"a complete {kind} result" if complete else f"a {kind} result")
        raise ConfigError(f"{result}: holds a {ds.attrs.get('analysis')!r} result, not {what}")
    check_writable(output, "command line", "-o/--output")
    try:
        return save(draw(ds), output, dpi)
    except ValueError as exc:
        raise ConfigError(f"{result}: {exc}") from None


def reproduce_to_file(output: str, cache: str | None, echo: Callable[[str], None],
                      **options) -> str:
    """``softimpact reproduce``: check the study's statements (``options`` of
    ``reproduce.report.reproduce``: quick, only, workers, cached_only) with the runs
    cached in ``cache`` (None: results/reproduce/ of the repository), write the table
    (markdown) to ``output`` and return the line that sums it up."""
    try:
        rows, text = run_reproduce(cache=Path(cache) if cache else CACHE, echo=echo,
                                   **options)
    except ValueError as exc:
        raise ConfigError(str(exc)) from None
    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    counts = ", ".join(f"{v} {n}" for v, n in summary(rows).items() if n)
    return f"reproduce: {len(rows)} statements ({counts}) -> {out}"
