"""Command line: thin wrappers over library functions.

Every error a user can cause ends with one line on stderr and exit status 2.
"""

from __future__ import annotations

import functools
import json
import sys
from pathlib import Path

import click

from .config import ConfigError, check_writable, load_scene


def _user_errors(func):
    """Turn ConfigError (and unreadable result files) into one line and exit status 2."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except ConfigError as exc:
            click.echo(f"softimpact: error: {exc}", err=True)
            sys.exit(2)

    return wrapper


def _open(path: str):
    from .store import open_result

    p = Path(path)
    if not p.is_file():
        raise ConfigError(f"{path}: no such result file")
    try:
        return open_result(p)
    except Exception as exc:  # any reader failure is the file's fault, said in one line
        raise ConfigError(f"{path}: not a softimpact result file ({exc.__class__.__name__})"
                          ) from None


def _progress_bar(total: int):
    """A tqdm bar on stderr when it is a terminal; returns its update function."""
    from tqdm import tqdm

    bar = tqdm(total=total, unit="ic", disable=not sys.stderr.isatty(), leave=False)
    return bar.update


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="softimpact")
def main():
    """softimpact: multistability of oscillators coupled through soft impacts."""


@main.command()
@click.argument("scene", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Result file (overrides [output] path).")
@click.option("--overwrite", is_flag=True, help="Replace an existing result file.")
@_user_errors
def sweep(scene, output, overwrite):
    """Run SCENE (a TOML file) and write its result to HDF5."""
    from .run import run_scene
    from .store import write_result

    sc = load_scene(scene)
    out = Path(output) if output else sc.output
    key = "-o/--output" if output else "[output] path"
    check_writable(out, scene if not output else "command line", key)
    if out.exists() and not overwrite:
        raise ConfigError(f"{out}: result exists; pass --overwrite to replace it")
    ds = run_scene(sc, progress=_progress_bar)
    write_result(ds, out)
    if ds.attrs.get("analysis") == "catalogue":
        from .info import format_catalogue

        click.echo(format_catalogue(ds))
    click.echo(f"{sc.analysis.kind}: {ds.attrs.get('outcome', 'done')}"
               + (f", period {ds.attrs['period']}" if ds.attrs.get("period") else "")
               + f" ({ds.attrs['wall_s']:.2f} s) -> {out}")


@main.group()
def plot():
    """Draw figures from result files."""


@plot.command("trajectory")
@click.argument("result", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Figure file (.png, .pdf, .svg).")
@click.option("--last-periods", type=click.IntRange(min=1), default=None,
              help="Periods drawn strongly as the steady state (default: a quarter, <= 20).")
@_user_errors
def plot_trajectory_cmd(result, output, last_periods):
    """Time series, phase portraits and Poincare points of a trajectory RESULT."""
    from .plot.trajectory import plot_trajectory

    ds = _open(result)
    if ds.attrs.get("analysis") != "trajectory":
        raise ConfigError(f"{result}: holds a {ds.attrs.get('analysis')!r} result, not a "
                          "trajectory")
    check_writable(Path(output), "command line", "-o/--output")
    click.echo(f"figure -> {plot_trajectory(ds, output, last_periods)}")


@plot.command("catalogue")
@click.argument("result", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Figure file (.png, .pdf, .svg).")
@_user_errors
def plot_catalogue_cmd(result, output):
    """Attractors on the phase plane and one panel per combination of a catalogue RESULT."""
    from .plot.catalogue import plot_catalogue

    ds = _open(result)
    if ds.attrs.get("analysis") != "catalogue":
        raise ConfigError(f"{result}: holds a {ds.attrs.get('analysis')!r} result, not a "
                          "catalogue")
    check_writable(Path(output), "command line", "-o/--output")
    click.echo(f"figure -> {plot_catalogue(ds, output)}")


@main.command()
@click.argument("result", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@_user_errors
def info(result, as_json):
    """What RESULT holds: scene, status, period, contacts, wall time."""
    from .info import describe

    summary = describe(_open(result))
    if as_json:
        click.echo(json.dumps(summary, indent=2))
        return
    scene = summary.pop("scene", "")
    for key, value in summary.items():
        click.echo(f"{key:28s} {value}")
    click.echo("scene:")
    for line in scene.splitlines():
        click.echo(f"  {line}")


if __name__ == "__main__":
    main()
