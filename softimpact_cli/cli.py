"""Command line: thin wrappers over library functions (``commands.py``): each command
parses its options, calls one function and exits with the status it returns.

Every error a user can cause ends with one line on stderr and exit status 2
(``cli_terminal``); options that are more than a flag are in ``cli_options``.
"""

from __future__ import annotations

import functools
import json
import sys

import click

from .cli_options import KindsHelp, cells, dpi_option, plot_option, run_options
from .cli_terminal import console, exit_with, interruptible, library, quick_exit, user_errors
from .config import ConfigError
from .config.examples import MODEL_EXAMPLES
from .kinds import KINDS, example_scene
from .kinds.check import check_scene, check_text, over_limit
from .kinds.scene import load_scene
from .report.streams import reader_safe_streams


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="softimpact")
def main():
    """softimpact: multistability of oscillators coupled through soft impacts."""
    quick_exit()
    # a reader that goes away (`| head`) drops the output, never the result
    click.get_current_context().with_resource(reader_safe_streams())


@main.command(cls=KindsHelp)
@click.argument("scene")
@run_options(
    quiet="No plan, no progress bar.",
    quick="Low resolution for previews and CI: planes <= 24 x 24, <= 100 samples, <= 6 "
          "values per swept grid axis, <= 64 dcrit phases, <= 50 d steps.",
    strict="Refuse to start when a fixed RK4 step is unstable, and exit with status 3 "
           "(after writing the result) when over 5% of trajectories are unresolved or "
           "diverged, the catalogue is empty, or the label error stays over the "
           "[verification] threshold (instead of warning).")
@click.option("--resume", is_flag=True, help="Finish an interrupted sweep of the same scene.")
@click.option("--chunk-size", type=click.IntRange(min=1), default=None,
              help="Trajectories per chunk (default: about 16 chunks per worker).")
@click.option("--resolution", type=click.IntRange(min=1), default=None,
              help="Cap a plane's resolution per axis at N (previews, galleries).")
@click.option("--check", "check_n", type=click.IntRange(min=1), default=None, metavar="N",
              help="Verify a sweep on N random trajectories (default: [verification] "
                   "share of them, min_sample..max_sample).")
@click.option("--no-verify", is_flag=True,
              help="Do not verify a sweep (recorded in the result as not verified).")
@click.option("--no-cache", is_flag=True,
              help="Search the attractor catalogue afresh instead of reading it from the "
                   "catalogue cache (as SOFTIMPACT_NO_CACHE=1 does; see `softimpact cache`).")
@interruptible
@user_errors
def sweep(scene, **options):
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
    lib = library()
    exit_with(lib.sweep_scene(scene, lib.SweepOptions(**options), console(lib)))


@main.command()
@click.argument("scene")
@click.option("--target", default=None, help="Solution to keep, e.g. 'L1^1 R1-0^1' "
              "(overrides [analysis] target).")
@run_options(
    quiet="No stages, no progress bar.",
    quick="At most 100 samples (previews and CI).",
    strict="Exit with status 3 (after writing) when too many trajectories stay unresolved "
           "or diverge, or no solution is found.")
@interruptible
@user_errors
def design(scene, target, **options):
    """Choose (d, phi, k_c, c_c) so that only the target solution survives (design SCENE).

    SCENE must have [analysis] kind = "design" (the other kinds, listed in
    `softimpact sweep --help`, run with sweep). Example scenes: configs/design_duffing.toml,
    configs/design_bilinear.toml; `softimpact example design` prints a minimal one.

    \b
    Example:
      softimpact design configs/design_duffing.toml --quick -o results/design_quick.h5
    """
    lib = library()
    exit_with(lib.design_scene(scene, target, lib.RunOptions(**options), console(lib)))


@main.command()
@click.argument("scene")
@click.option("--sample", type=click.IntRange(min=1), default=200, show_default=True,
              help="Trajectories (sweeps) or phases (dcrit) rerun.")
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@click.option("--fail-over", type=click.FloatRange(min=0), default=None, metavar="F",
              help="Exit 1 when the label change share (sweeps) or the largest d change "
                   "(dcrit, bifurcation) exceeds F.")
@interruptible
@user_errors
def check(scene, sample, seed, as_json, fail_over):
    """Rerun part of SCENE at tightened settings: label changes and wall-time ratio."""
    sc = load_scene(scene)
    library().announce_compilation(sc)
    try:
        report = check_scene(sc, sample, seed)
    except ValueError as exc:
        raise ConfigError(f"{scene}: {exc}") from None
    click.echo(json.dumps(report, indent=2) if as_json else check_text(report))
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
@user_errors
def compare(result_a, result_b, as_json, **limits):
    """Differences of RESULT_B from RESULT_A (same scene layout): labels, shares, d."""
    text, why = library().compare_files(result_a, result_b, as_json, **limits)
    click.echo(text)
    if why:
        click.echo(f"softimpact: compare: {'; '.join(why)}", err=True)
        sys.exit(1)


@main.command()
@click.argument("result")
@click.option("-o", "--output", required=True, help="Fractality result file (HDF5).")
@click.option("--overwrite", is_flag=True, help="Replace an existing result file.")
@click.option("--box-sizes", callback=cells, default=None, metavar="N,N,...",
              help="Basin-entropy box sizes in cells (default 2 .. min(20, side/4)).")
@click.option("--radii", callback=cells, default=None, metavar="R,R,...",
              help="Uncertainty radii in cells (default about 12 over 1 .. side/10).")
@click.option("--wada-radius", type=click.IntRange(1, 100), default=5, show_default=True,
              help="Largest fattening of the merged boundaries in the Wada test (cells).")
@click.option("--wada-tol", type=click.FloatRange(0, 1, max_open=True), default=0.05,
              show_default=True, help="Largest mismatch share still called Wada.")
@user_errors
def measure(result, output, **options):
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
    click.echo(library().measure_to_file(result, output, **options))


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


def _plot_command(kind) -> click.Command:
    """``softimpact plot <kind>``, built from the kind's PlotSpec."""
    spec = kind.plot

    def command(result, output, dpi, **options):
        draw = kind.figure_function()
        path = library().draw_result(result, output, dpi, kind.name,
                                      lambda ds: draw(ds, **options), complete=spec.complete,
                                      accept=spec.accept, expected=spec.expected)
        click.echo(f"figure -> {path}")

    params = [click.Argument(["result"]),
              click.Option(["-o", "--output"], required=True,
                           help="Figure file (.png, .pdf, .svg).")]
    params += [dpi_option(), *(plot_option(option) for option in spec.options)]
    return click.Command(kind.name, callback=user_errors(command), params=params,
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
@user_errors
def info(result, as_json, compare):
    """What RESULT holds: scene, status, period, contacts, wall time."""
    click.echo(library().info_text(result, as_json, compare))


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
    state = library().cache_state()
    if as_json:
        click.echo(json.dumps({"location": str(state.location), "entries": state.entries,
                               "size_bytes": state.size, "enabled": state.enabled}))
        return
    click.echo(state.describe())


@cache.command("clear")
def cache_clear():
    """Remove every entry of the catalogue cache."""
    lib = library()
    removed = lib.clear()
    click.echo(f"removed {removed} catalogue cache entr{'y' if removed == 1 else 'ies'} "
               f"from {lib.cache_folder()}")


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
@interruptible
@user_errors
def reproduce(output, cache, quiet, **options):
    """Check the study's statements one by one and write a table (results/reproduce.md):
    the study's value, softimpact's with its interval, the runs, and a verdict.

    Runs are cached in results/reproduce/ under a hash of their scene text: a finished
    run is reused and an interrupted sweep resumes.
    """
    echo = (lambda s: None) if quiet else functools.partial(click.echo, err=True)
    click.echo(library().reproduce_to_file(output, cache, echo, **options))


if __name__ == "__main__":
    main()
