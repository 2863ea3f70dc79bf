"""The command line's options that are more than a flag: their checks (``scheduler``,
``cells``), the options ``sweep`` and ``design`` share (``run_options``), a kind's plot
options, and the help of ``sweep`` that lists the kinds (``KindsHelp``)."""

from __future__ import annotations

import click

from .kinds import help_lines


def scheduler(ctx, param, value):
    """--scheduler: a Dask scheduler's address (tcp://, tls://, inproc://, ucx://) or
    local:N (a LocalCluster of N workers started for the run)."""
    if value is None:
        return None
    if value.startswith("local:"):
        n = value.split(":", 1)[1]
        if not n.isdigit() or int(n) < 1:
            raise click.BadParameter("use local:N with N >= 1 workers, or tcp://HOST:PORT")
    elif not value.startswith(("tcp://", "tls://", "inproc://", "ucx://")):
        raise click.BadParameter("use tcp://HOST:PORT (a Dask scheduler) or local:N")
    return value


class KindsHelp(click.Command):
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


def run_options(quiet: str, quick: str, strict: str):
    """The options ``sweep`` and ``design`` share (``commands.RunOptions``), with their
    own help for ``--quiet``, ``--quick`` and ``--strict``."""
    options = (
        click.option("-o", "--output", help="Result file (overrides [output] path)."),
        click.option("--overwrite", is_flag=True, help="Replace an existing result file."),
        click.option("--workers", type=click.IntRange(min=1), default=None,
                     help="Local worker processes (default: all cores)."),
        click.option("--scheduler", callback=scheduler, default=None,
                     help="Dask scheduler: tcp://HOST:PORT, or local:N to start a "
                          "LocalCluster."),
        click.option("-q", "--quiet", is_flag=True, help=quiet),
        click.option("--quick", is_flag=True, help=quick),
        click.option("--dry-run", is_flag=True,
                     help="Validate SCENE and print what would be computed; write nothing."),
        click.option("--strict", is_flag=True, help=strict),
    )

    def decorate(command):
        for option in reversed(options):
            command = option(command)
        return command

    return decorate


def cells(ctx, param, value):
    """"2,5,10" -> (2, 5, 10); None stays None (the analysis' default)."""
    if value is None:
        return None
    try:
        sizes = tuple(int(v) for v in value.split(","))
    except ValueError:
        raise click.BadParameter(f"a comma-separated list of whole numbers of cells, got "
                                 f"{value!r}") from None
    if not sizes or min(sizes) < 1:
        raise click.BadParameter(f"whole numbers of cells >= 1, got {value!r}")
    return sizes


def dpi_option() -> click.Option:
    return click.Option(["--dpi"], type=click.IntRange(min=10, max=2400), default=150,
                        show_default=True, help="Resolution of raster figures (PNG).")


def plot_option(option) -> click.Option:
    """A click option from a kind's PlotOption (``kinds.PlotOption``)."""
    if option.kind == "flag":
        return click.Option([option.flag, option.keyword], is_flag=True, help=option.help)
    types = {"int>=1": click.IntRange(min=1), "choice": click.Choice(list(option.choices)),
             "text": None}
    return click.Option([option.flag, option.keyword], type=types[option.kind],
                        default=option.default, help=option.help,
                        show_default=option.default is not None)
