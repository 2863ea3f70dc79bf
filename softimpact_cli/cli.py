"""Command line: thin wrappers over library functions.

Every error a user can cause ends with one line on stderr and exit status 2.
"""

from __future__ import annotations

import atexit
import functools
import gc
import json
import sys
from pathlib import Path

import click

from .config import ConfigError, check_writable, result_path
from .config.examples import MODEL_EXAMPLES
from .kinds import KINDS, example_scene, help_lines, sweep_kinds
from .kinds import get as kind_of
from .kinds.check import check_scene, over_limit
from .kinds.design_settings import with_target
from .kinds.scene import load_scene
from .report.progress import ProgressLines
from .report.streams import reader_safe_streams
from .sweep import interrupt
from .sweep.interrupt import modified, sweep_kept


def _user_errors(func):
    """Turn ConfigError (and unreadable result files) into one line and exit status 2;
    an error after which the run can be resumed (``resumable``, e.g. a Dask cluster
    lost) says what was kept and the command that resumes (``ctx.meta["softimpact.kept"]``)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except ConfigError as exc:
            kept = click.get_current_context().meta.get("softimpact.kept")
            more = f"; {kept()}" if getattr(exc, "resumable", False) and kept else ""
            click.echo(f"softimpact: error: {exc}{more}", err=True)
            sys.exit(2)

    return wrapper


def _open(path: str):
    # the analyses, xarray and the store: imported when the command runs
    from .commands import read_result

    return read_result(path)


# progress lines started by the running command: its end stops their timers, whatever
# ended it (an error, or a run whose units never reached the total), so that no line is
# printed after the command, e.g. under CliRunner in the tests' process or a notebook
_STARTED_LINES: list = []


def _progress_bar(total: int, initial: int = 0, unit: str = "trajectories"):
    """A tqdm bar on stderr (points/s, ETA) when it is a terminal, else a line every
    $SOFTIMPACT_PROGRESS_INTERVAL s (default 30, see report/progress.py); returns the callable
    fed with counts or with a chunk's label codes."""
    if not sys.stderr.isatty():
        lines = ProgressLines(total, initial, unit)
        _STARTED_LINES.append(lines)
        return lines
    from tqdm import tqdm

    bar = tqdm(total=total, initial=initial, unit="ic", leave=False, smoothing=0.1)
    return lambda work: bar.update(len(work) if hasattr(work, "__len__") else work)


def _interruptible(func):
    """Ctrl-C or SIGTERM end the command with one line saying what was kept (a callable
    the command may put in ``ctx.meta["softimpact.kept"]``; else "nothing written") and
    exit status 128 + the signal: 130 (SIGINT), 143 (SIGTERM). See sweep/interrupt.py."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        with interrupt.raising_on_signals():
            try:
                return func(*args, **kwargs)
            except BaseException as exc:
                stop = interrupt.interruption(exc)
                if stop is None:
                    raise
                kept = click.get_current_context().meta.get("softimpact.kept")
                interrupt.exit_interrupted(stop, kept() if kept else "nothing written")
            finally:
                while _STARTED_LINES:
                    _STARTED_LINES.pop().close()

    return wrapper


def _warn_outcomes(ds, scene, strict: bool) -> None:
    """Warn about a result mostly unresolved or diverged, or an empty catalogue; with
    --strict, exit with report.outcomes.STRICT_STATUS (3) afterwards (the result is written)."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import STRICT_STATUS, outcome_notes, outcome_warnings

    for note in outcome_notes(ds):
        click.echo(f"softimpact: note: {note}", err=True)
    # every kind with outcome shares (sweeps, tipping, design) runs the second stage
    messages = outcome_warnings(ds, scene.integrator.max_periods,
                                section_periods=scene.integrator.section_periods)
    for message in messages:
        click.echo(f"softimpact: warning: {message}", err=True)
    if messages and strict:
        sys.exit(STRICT_STATUS)


def _check_rk4_step(scene, strict: bool) -> None:
    """Warn (or, with --strict, refuse) when the scene's fixed RK4 step is unstable at any
    of its grid points."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import Problem, rk4_step_warning

    points = [dict(scene.values)]
    if scene.grid is not None and scene.system.bodies == 2:
        points = [{**scene.values, **{k: v for k, v in scene.grid.point(i).items()
                                      if k != "t0"}} for i in range(min(scene.grid.size, 10_000))]
    for values in points:
        message = rk4_step_warning(Problem(scene.system, values, scene.integrator))
        if message:
            if strict:
                raise ConfigError(f"{scene.source}: {message}")
            click.echo(f"softimpact: warning: {scene.source}: {message}", err=True)
            return


def _quick_exit() -> None:
    """Freeze the garbage collector when the interpreter exits (once per process).

    At exit CPython clears every module and runs full collections over what is left:
    with numba's, xarray's and pandas' objects that took 0.5 s of a 3 s `softimpact
    sweep` (a quarter of a small command). Frozen objects are skipped by those
    collections; they are still freed by reference counting, the atexit handlers
    registered before this one still run, and what is written (results, chunks, cache
    entries) is closed and fsynced before the command returns, never left to a finalizer.
    """
    if not _QUICK_EXIT:
        atexit.register(gc.freeze)
        _QUICK_EXIT.append(True)


_QUICK_EXIT: list = []


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="softimpact")
def main():
    """softimpact: multistability of oscillators coupled through soft impacts."""
    _quick_exit()
    # a reader that goes away (`| head`) drops the output, never the result
    click.get_current_context().with_resource(reader_safe_streams())


def _scheduler(ctx, param, value):
    if value is None:
        return None
    if value.startswith("local:"):
        n = value.split(":", 1)[1]
        if not n.isdigit() or int(n) < 1:
            raise click.BadParameter("use local:N with N >= 1 workers, or tcp://HOST:PORT")
    elif not value.startswith(("tcp://", "tls://", "inproc://", "ucx://")):
        raise click.BadParameter("use tcp://HOST:PORT (a Dask scheduler) or local:N")
    return value


class _KindsHelp(click.Command):
    """A command whose help lists the kinds of the registry where it says ``{kinds}``
    (read when the help is shown: the kinds' modules are imported then)."""

    def format_help_text(self, ctx, formatter) -> None:
        help_text = self.help
        # the docstring's indentation (click dedents the whole text)
        self.help = help_text.replace("{kinds}", "\n    ".join(help_lines("  ")))
        try:
            super().format_help_text(ctx, formatter)
        finally:
            self.help = help_text


@main.command(cls=_KindsHelp)
@click.argument("scene")
@click.option("-o", "--output", help="Result file (overrides [output] path).")
@click.option("--overwrite", is_flag=True, help="Replace an existing result file.")
@click.option("--resume", is_flag=True, help="Finish an interrupted sweep of the same scene.")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Local worker processes (default: all cores).")
@click.option("--scheduler", callback=_scheduler, default=None,
              help="Dask scheduler: tcp://HOST:PORT, or local:N to start a LocalCluster.")
@click.option("--chunk-size", type=click.IntRange(min=1), default=None,
              help="Trajectories per chunk (default: about 16 chunks per worker).")
@click.option("-q", "--quiet", is_flag=True, help="No plan, no progress bar.")
@click.option("--quick", is_flag=True,
              help="Low resolution for previews and CI: planes <= 24 x 24, <= 100 samples, "
                   "<= 6 values per swept grid axis, <= 64 dcrit phases, <= 50 d steps.")
@click.option("--resolution", type=click.IntRange(min=1), default=None,
              help="Cap a plane's resolution per axis at N (previews, galleries).")
@click.option("--strict", is_flag=True,
              help="Refuse to start when a fixed RK4 step is unstable, and exit with status "
                   "3 (after writing the result) when over 5% of trajectories are unresolved "
                   "or diverged, the catalogue is empty, or the label error stays over the "
                   "[verification] threshold (instead of warning).")
@click.option("--check", "check_n", type=click.IntRange(min=1), default=None, metavar="N",
              help="Verify a sweep on N random trajectories (default: [verification] "
                   "share of them, min_sample..max_sample).")
@click.option("--no-verify", is_flag=True,
              help="Do not verify a sweep (recorded in the result as not verified).")
@click.option("--dry-run", is_flag=True,
              help="Validate SCENE and print what would be computed; write nothing.")
@click.option("--no-cache", is_flag=True,
              help="Search the attractor catalogue afresh instead of reading it from the "
                   "catalogue cache (as SOFTIMPACT_NO_CACHE=1 does; see `softimpact cache`).")
@_interruptible
@_user_errors
def sweep(scene, output, overwrite, resume, workers, scheduler, chunk_size, quiet, quick,
          resolution, strict, check_n, no_verify, dry_run, no_cache):
    """Run SCENE (a TOML file) and write its result to HDF5.

    SCENE's [analysis] kind says what is computed:

    \b
    {kinds}

    Example scenes: configs/ (demo, trajectory, catalogues, designs) and
    configs/figures/ (every figure of the study); `softimpact example KIND` prints a
    minimal commented scene of each kind.

    A sweep (basins, stability, map) is verified when it completes: a random sample is
    rerun at tight settings and its label disagreement stored with a 95% interval; over
    the [verification] threshold it is redone at tighter settings (docs/validation/
    how-right.md). --strict: exit status 3 when it stays over the threshold.

    \b
    Examples:
      softimpact sweep configs/demo_basins.toml -o results/demo.h5
      softimpact sweep configs/fig04_duffing_catalogue.toml --quick
    """
    # the analyses, xarray and the store: imported when the command runs
    from .commands import (
        STRICT_STATUS,
        announce_compilation,
        plan_text,
        run_to_file,
        shrink_scene,
        switched_off,
    )

    if check_n and no_verify:
        raise ConfigError(f"--check {check_n} and --no-verify: choose one (--check N sets "
                          "how many trajectories the verification reruns)")
    if no_cache:  # the switch of SOFTIMPACT_NO_CACHE=1, for this command only

        click.get_current_context().with_resource(switched_off())
    sc = shrink_scene(load_scene(scene), quick, resolution)
    out = result_path(sc, output)
    key = "-o/--output" if output else "[output] path"
    check_writable(out, scene if not output else "command line", key)
    if dry_run:
        from dataclasses import replace

        click.echo(plan_text(replace(sc, output=out), workers, chunk_size))
        return
    echo = (lambda s: None) if quiet else (lambda s: click.echo(s, err=True))
    _check_rk4_step(sc, strict)
    announce_compilation(sc)
    if kind_of(sc.analysis.kind).sweep:
        flags = ("--quick",) * quick + (("--resolution", str(resolution)) if resolution else ())
        click.get_current_context().meta["softimpact.kept"] = functools.partial(
            sweep_kept, out, scene, flags, modified(out))

        ds = run_to_file(sc, out, workers=workers, scheduler=scheduler, resume=resume,
                         overwrite=overwrite, chunk_size=chunk_size, echo=echo,
                         progress=None if quiet else _progress_bar, verify=not no_verify,
                         verify_sample=check_n)
        click.echo(f"{sc.analysis.kind}: {ds.attrs['n']} trajectories "
                   f"({ds.attrs['wall_s']:.1f} s) -> {out}")
        over = _report_verification(ds)
        _warn_outcomes(ds, sc, strict)
        if over and strict:
            sys.exit(STRICT_STATUS)
        return
    if resume:
        raise ConfigError(f"{scene}: --resume is for sweeps (kinds {', '.join(sweep_kinds())}); "
                          f"a {sc.analysis.kind} reruns whole")
    _warn_outcomes(_run_whole(sc, out, overwrite, workers, scheduler, quiet), sc, strict)


def _run_whole(sc, out: Path, overwrite: bool, workers, scheduler, quiet: bool):
    """Run a scene that is not a sweep (every kind but basins, stability, map), write its
    result, print what its kind reports and the outcome line; return the dataset."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import run_to_file

    kind = kind_of(sc.analysis.kind)
    ds = run_to_file(sc, out, overwrite=overwrite, workers=workers, scheduler=scheduler,
                     progress=None if quiet else functools.partial(
                         _progress_bar, unit=kind.progress_unit),
                     echo=(lambda s: None) if quiet else (lambda s: click.echo(s, err=True)))
    if kind.report is not None:
        click.echo(kind.report(ds))
    click.echo(f"{sc.analysis.kind}: {ds.attrs.get('outcome', 'done')}"
               + (f", period {ds.attrs['period']}" if ds.attrs.get("period") else "")
               + f" ({ds.attrs['wall_s']:.2f} s) -> {out}")
    return ds


@main.command()
@click.argument("scene")
@click.option("--target", default=None, help="Solution to keep, e.g. 'L1^1 R1-0^1' "
              "(overrides [analysis] target).")
@click.option("-o", "--output", help="Result file (overrides [output] path).")
@click.option("--overwrite", is_flag=True, help="Replace an existing result file.")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Local worker processes (default: all cores).")
@click.option("--scheduler", callback=_scheduler, default=None,
              help="Dask scheduler: tcp://HOST:PORT, or local:N to start a LocalCluster.")
@click.option("-q", "--quiet", is_flag=True, help="No stages, no progress bar.")
@click.option("--quick", is_flag=True, help="At most 100 samples (previews and CI).")
@click.option("--dry-run", is_flag=True,
              help="Validate SCENE and print what would be computed; write nothing.")
@click.option("--strict", is_flag=True,
              help="Exit with status 3 (after writing) when too many trajectories stay "
                   "unresolved or diverge, or no solution is found.")
@_interruptible
@_user_errors
def design(scene, target, output, overwrite, workers, scheduler, quiet, quick, dry_run,
           strict):
    """Choose (d, phi, k_c, c_c) so that only the target solution survives (design SCENE).

    SCENE must have [analysis] kind = "design" (the other kinds, listed in
    `softimpact sweep --help`, run with sweep). Example scenes: configs/design_duffing.toml,
    configs/design_bilinear.toml; `softimpact example design` prints a minimal one.

    \b
    Example:
      softimpact design configs/design_duffing.toml --quick -o results/design_quick.h5
    """
    # the analyses, xarray and the store: imported when the command runs
    from .commands import announce_compilation, plan_text, shrink_scene

    sc = load_scene(scene)
    if sc.analysis.kind != "design":
        raise ConfigError(f"{scene}: [analysis] kind: must be \"design\" for this command, "
                          f"got {sc.analysis.kind!r}")
    sc = with_target(sc, target) if target is not None else sc
    sc = shrink_scene(sc, quick)
    out = result_path(sc, output)
    check_writable(out, scene if not output else "command line",
                   "-o/--output" if output else "[output] path")
    if dry_run:
        from dataclasses import replace

        click.echo(plan_text(replace(sc, output=out)))
        return
    announce_compilation(sc)
    _warn_outcomes(_run_whole(sc, out, overwrite, workers, scheduler, quiet), sc, strict)


def _report_verification(ds) -> bool:
    """Print the label-error line; a note when some rerun label disagreed although the
    error is within the threshold, a warning when it is over. A clean run (none disagreed,
    whatever the bound) gets no note. Returns whether it is over the threshold."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import OVER, VERIFIED, verification_line

    click.echo(verification_line(ds.attrs))
    status = ds.attrs["verify_status"]
    if status == VERIFIED and int(ds.attrs.get("verify_disagreements", 0)) > 0:
        click.echo(f"softimpact: note: {ds.attrs['verify_disagreements']} of "
                   f"{ds.attrs['verify_sample']} rerun labels disagreed "
                   f"({ds.attrs['verify_changes']}); {ds.attrs['verify_message']}", err=True)
    if status == OVER:
        click.echo(f"softimpact: warning: label error over the threshold: "
                   f"{ds.attrs['verify_message']}", err=True)
    return status == OVER


def _format_check(report: dict) -> str:
    head = (f"check ({report['kind']}, {report['sample']} sampled, tightened settings: "
            f"rtol and atol / 100, convergence_tol / 10, 2x periods, 4x RK4 steps): ")
    if report["kind"] == "labels":
        body = (f"{report['changed']} labels changed ({100 * report['changed_share']:.2f}%)"
                + (f" [{', '.join(f'{k}: {v}' for k, v in report['changes'].items())}]"
                   if report["changes"] else ""))
    else:
        body = f"largest change {report['max_change']:.3g}"
    return (head + body + f"; wall {report['wall_s']:.2f} s vs {report['tight_wall_s']:.2f} s "
            f"tightened (x{report['wall_ratio']:.2f})")


@main.command()
@click.argument("scene")
@click.option("--sample", type=click.IntRange(min=1), default=200, show_default=True,
              help="Trajectories (sweeps) or phases (dcrit) rerun.")
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@click.option("--fail-over", type=click.FloatRange(min=0), default=None, metavar="F",
              help="Exit 1 when the label change share (sweeps) or the largest d change "
                   "(dcrit, bifurcation) exceeds F.")
@_interruptible
@_user_errors
def check(scene, sample, seed, as_json, fail_over):
    """Rerun part of SCENE at tightened settings: label changes and wall-time ratio."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import announce_compilation

    sc = load_scene(scene)
    announce_compilation(sc)
    try:
        report = check_scene(sc, sample, seed)
    except ValueError as exc:
        raise ConfigError(f"{scene}: {exc}") from None
    click.echo(json.dumps(report, indent=2) if as_json else _format_check(report))
    why = over_limit(report, fail_over)
    if why:
        click.echo(f"softimpact: check: {why}", err=True)
        sys.exit(1)


@main.command()
@click.argument("result_a")  # checked when opened: one line naming the file (no usage text)
@click.argument("result_b")
@click.option("--max-label-change", type=click.FloatRange(0, 1), default=None, metavar="F",
              help="Exit 1 when more than this share of the labels differ (sweeps).")
@click.option("--max-share-change", type=click.FloatRange(0, 1), default=None, metavar="F",
              help="Exit 1 when a solution's share at a grid point moves by more (sweeps).")
@click.option("--max-d-change", type=click.FloatRange(min=0), default=None, metavar="F",
              help="Exit 1 when a d_crit or destruction point moves by more (dcrit, "
                   "bifurcation).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@_user_errors
def compare(result_a, result_b, max_label_change, max_share_change, max_d_change, as_json):
    """Differences of RESULT_B from RESULT_A (same scene layout): labels, shares, d."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import compare_results, format_comparison, limits_exceeded

    report = compare_results(_open(result_a), _open(result_b), result_a, result_b)
    why = limits_exceeded(report, max_label_change, max_share_change, max_d_change)
    click.echo(json.dumps({**report, "failed": why}, indent=2) if as_json
               else format_comparison(report))
    if why:
        click.echo(f"softimpact: compare: {'; '.join(why)}", err=True)
        sys.exit(1)


def _cells_option(ctx, param, value):
    """"2,5,10" -> (2, 5, 10); None stays None (the analysis' default)."""
    if value is None:
        return None
    try:
        cells = tuple(int(v) for v in value.split(","))
    except ValueError:
        raise click.BadParameter(f"a comma-separated list of whole numbers of cells, got "
                                 f"{value!r}") from None
    if not cells or min(cells) < 1:
        raise click.BadParameter(f"whole numbers of cells >= 1, got {value!r}")
    return cells


@main.command()
@click.argument("result")
@click.option("-o", "--output", required=True, help="Fractality result file (HDF5).")
@click.option("--overwrite", is_flag=True, help="Replace an existing result file.")
@click.option("--box-sizes", callback=_cells_option, default=None, metavar="N,N,...",
              help="Basin-entropy box sizes in cells (default 2 .. min(20, side/4)).")
@click.option("--radii", callback=_cells_option, default=None, metavar="R,R,...",
              help="Uncertainty radii in cells (default about 12 over 1 .. side/10).")
@click.option("--wada-radius", type=click.IntRange(1, 100), default=5, show_default=True,
              help="Largest fattening of the merged boundaries in the Wada test (cells).")
@click.option("--wada-tol", type=click.FloatRange(0, 1, max_open=True), default=0.05,
              show_default=True, help="Largest mismatch share still called Wada.")
@_user_errors
def measure(result, output, overwrite, box_sizes, radii, wada_radius, wada_tol):
    """How fractal the basins of RESULT (a basins result over a plane) are, per plane:
    basin entropy S_b, S_bb against the box size with the ln 2 criterion, the uncertainty
    exponent alpha and boundary dimension D = 2 - alpha with 95% fit intervals, and the
    Wada merging test. Writes a fractality result (softimpact info / plot fractality);
    docs/validation/fractality.md.

    \b
    Example:
      softimpact sweep configs/figures/fig09_bilinear_single_basins.toml -o fig09.h5
      softimpact measure fig09.h5 -o fig09_fractality.h5
    """
    # the analyses, xarray and the store: imported when the command runs
    from .commands import fractality_lines, measure_result

    check_writable(output, "command line", "-o/--output")
    ds = measure_result(result, output, box_sizes=box_sizes, radii=radii,
                        wada_radius=wada_radius, wada_tol=wada_tol, overwrite=overwrite)
    click.echo("\n".join(fractality_lines(ds)))
    click.echo(f"fractality -> {output}")


@main.command()
@click.argument("kind", required=False)
def example(kind):
    """Print a minimal commented scene of analysis KIND, or of model "chain" (no KIND: list
    the kinds).

    \b
    Example:
      softimpact example basins > my_basins.toml && softimpact sweep my_basins.toml
    """

    if kind is None:
        click.echo("kinds: " + ", ".join(KINDS) + " (softimpact example KIND); models: "
                   + ", ".join(MODEL_EXAMPLES) + " (softimpact example MODEL)")
        return
    if kind in MODEL_EXAMPLES:
        click.echo(MODEL_EXAMPLES[kind], nl=False)
        return
    if kind not in KINDS:
        click.echo(f"softimpact: error: example: unknown kind {kind!r}; kinds: "
                   f"{', '.join(KINDS)}", err=True)
        sys.exit(2)
    click.echo(example_scene(kind), nl=False)


def _dpi_option() -> click.Option:
    return click.Option(["--dpi"], type=click.IntRange(min=10, max=2400), default=150,
                        show_default=True, help="Resolution of raster figures (PNG).")


def _draw(result: str, output: str, dpi: int, kind: str, draw, complete: bool = False,
          accept=None, expected: str | None = None) -> None:
    """Open RESULT, check that it holds a ``kind`` analysis (or passes ``accept``, a
    predicate on its attributes, described by ``expected``), draw it with ``draw(ds)``
    (a ``plot`` function, returning the Figure) and save it to OUTPUT."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import save

    ds = _open(result)
    ok = accept(ds.attrs) if accept else ds.attrs.get("analysis") == kind
    if not ok or (complete and int(ds.attrs.get("complete", 0)) != 1):
        what = expected or (f"a complete {kind} result" if complete else f"a {kind} result")
        raise ConfigError(f"{result}: holds a {ds.attrs.get('analysis')!r} result, not {what}")
    check_writable(output, "command line", "-o/--output")

    try:
        path = save(draw(ds), output, dpi)
    except ValueError as exc:
        raise ConfigError(f"{result}: {exc}") from None
    click.echo(f"figure -> {path}")


def _plot_option(option) -> click.Option:
    """A click option from a kind's PlotOption (``kinds.PlotOption``)."""
    if option.kind == "flag":
        return click.Option([option.flag, option.keyword], is_flag=True, help=option.help)
    types = {"int>=1": click.IntRange(min=1), "choice": click.Choice(list(option.choices)),
             "text": None}
    return click.Option([option.flag, option.keyword], type=types[option.kind],
                        default=option.default, help=option.help,
                        show_default=option.default is not None)


def _plot_command(kind) -> click.Command:
    """``softimpact plot <kind>``, built from the kind's PlotSpec."""
    spec = kind.plot

    def command(result, output, dpi, **options):
        draw = kind.figure_function()
        _draw(result, output, dpi, kind.name, lambda ds: draw(ds, **options),
              complete=spec.complete, accept=spec.accept, expected=spec.expected)

    params = [click.Argument(["result"]),
              click.Option(["-o", "--output"], required=True,
                           help="Figure file (.png, .pdf, .svg).")]
    params += [_dpi_option(), *(_plot_option(option) for option in spec.options)]
    return click.Command(kind.name, callback=_user_errors(command), params=params,
                         help=spec.help)


class _KindPlots(click.Group):
    """One ``plot`` command per registered kind that declares a figure, read from the
    registry when the command line is parsed."""

    def list_commands(self, ctx):
        return sorted(name for name, kind in KINDS.items() if kind.plot is not None)

    def get_command(self, ctx, name):
        kind = KINDS.get(name)
        return _plot_command(kind) if kind is not None and kind.plot is not None else None


@main.group(cls=_KindPlots)
def plot():
    """Draw figures from result files."""


@main.command()
@click.argument("result")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@click.option("--compare", default=None,
              help="A stability result: compare RESULT's plane basin shares with its 4-D "
                   "basin stability at common parameter points.")
@_user_errors
def info(result, as_json, compare):
    """What RESULT holds: scene, status, period, contacts, wall time."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import (
        SweepStore,
        compare_shares,
        describe,
        format_summary,
        incomplete_summary,
    )

    ds = _open(result)
    if compare:
        other = _open(compare)
        if ds.attrs.get("analysis") != "basins" or other.attrs.get("analysis") != "stability":
            raise ConfigError(f"--compare: RESULT must be a basins result and {compare} a "
                              "stability result")
        rows = compare_shares(ds, other)
        if not rows:
            raise ConfigError(f"--compare: {result} and {compare} share no parameter point")
        if as_json:
            click.echo(json.dumps({"comparison": rows}, indent=2))
            return
        for row in rows:
            click.echo(f"d={row['d']:.6g}, phi={row['phi']:.6g}, k_c={row['k_c']:.6g}, "
                       f"c_c={row['c_c']:.6g} (t0 plane {row['t0_plane']}, "
                       f"stability {row['t0_stability']})")
            click.echo(f"  {'solution':16s} {'plane':>7s} {'4-D':>7s}  95% interval")
            for name, v in row["shares"].items():
                ci = v["ci95"] or [float("nan")] * 2
                click.echo(f"  {name:16s} {v['plane']:7.3f} {v['stability']:7.3f}  "
                           f"[{ci[0]:.3f}, {ci[1]:.3f}]")
        return
    if int(ds.attrs.get("complete", 1)) == 0:
        summary = incomplete_summary(ds, len(SweepStore(result).done()))
    else:
        summary = describe(ds)
    if as_json:
        click.echo(json.dumps(summary, indent=2))
        return

    click.echo(format_summary(summary, ds))


@main.group()
def cache():
    """The catalogue cache: one-body attractor searches kept on disk, so that a repeated
    sweep, check, design or map of the same system does not search again. Entries are
    keyed by everything a search depends on (parameters, [catalogue] and [integrator]
    settings, initial states, the package's sources) and verified when read.
    Location: $SOFTIMPACT_CACHE_DIR, else $XDG_CACHE_HOME/softimpact or
    ~/.cache/softimpact, subfolder catalogues/. Off with SOFTIMPACT_NO_CACHE=1 or
    `softimpact sweep --no-cache`."""


@cache.command("info")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
def cache_info(as_json):
    """Where the catalogue cache is, its entries and size."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import cache_state

    state = cache_state()
    if as_json:
        click.echo(json.dumps({"location": str(state.location), "entries": state.entries,
                               "size_bytes": state.size, "enabled": state.enabled}))
        return
    click.echo(state.describe())


@cache.command("clear")
def cache_clear():
    """Remove every entry of the catalogue cache."""
    # the analyses, xarray and the store: imported when the command runs
    from .commands import cache_folder, clear

    removed = clear()
    click.echo(f"removed {removed} catalogue cache entr{'y' if removed == 1 else 'ies'} "
               f"from {cache_folder()}")


@main.command("reproduce")
@click.option("--quick", is_flag=True,
              help="Reduced sizes (planes 24 x 24, 100 samples, fewer phases and d steps; "
                   "the table says so): minutes instead of hours.")
@click.option("--only", default=None, metavar="IDS",
              help="Only these statements: S9, S9-S11 or S9,S12 (default: all 89).")
@click.option("-o", "--output", default="results/reproduce.md", show_default=True,
              type=click.Path(dir_okay=False), help="Where to write the table (markdown).")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Worker processes for the sweeps (default: all cores).")
@click.option("--cached-only", is_flag=True,
              help="Compute nothing: use the runs cached in results/reproduce/ and mark the "
                   "statements whose runs are missing as not checked yet.")
@click.option("--cache", type=click.Path(file_okay=False), default=None,
              help="Folder of the cached runs (default: results/reproduce/ of the "
                   "repository).")
@click.option("-q", "--quiet", is_flag=True, help="No progress lines.")
@_interruptible
@_user_errors
def reproduce(quick, only, output, workers, cached_only, cache, quiet):
    """Check the study's statements one by one and write a table (results/reproduce.md):
    the study's value, softimpact's with its interval, the runs, and a verdict.

    Runs are cached in results/reproduce/ under a hash of their scene text: a finished
    run is reused and an interrupted sweep resumes.
    """
    # the analyses, xarray and the store: imported when the command runs
    from .commands import CACHE, run_reproduce, summary

    echo = (lambda s: None) if quiet else (lambda s: click.echo(s, err=True))
    try:
        rows, text = run_reproduce(quick=quick, only=only, workers=workers,
                                   cached_only=cached_only,
                                   cache=Path(cache) if cache else CACHE, echo=echo)
    except ValueError as exc:
        raise ConfigError(str(exc)) from None
    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    counts = ", ".join(f"{v} {n}" for v, n in summary(rows).items() if n)
    click.echo(f"reproduce: {len(rows)} statements ({counts}) -> {out}")


if __name__ == "__main__":
    main()
