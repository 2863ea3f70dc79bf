"""How a command of the command line runs at the terminal: an error a user can cause
ends with one line and exit status 2 (``user_errors``), Ctrl-C and SIGTERM with what was
kept (``interruptible``), progress bars on stderr, the library's :class:`Console` on
click's streams, and a quick interpreter exit."""

from __future__ import annotations

import atexit
import functools
import gc
import sys

import click

from .config import ConfigError
from .report.progress import ProgressLines
from .sweep import interrupt


def user_errors(func):
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


def library():
    """``commands.py``, the library the commands call."""
    # the analyses, xarray and the store: imported when a command runs, not for
    # `softimpact --help` and the command line's start
    from . import commands

    return commands


def console(lib):
    """The library's Console on click's streams: stdout, stderr, the progress bars, and
    what an interruption keeps in ``ctx.meta["softimpact.kept"]``."""
    meta = click.get_current_context().meta
    return lib.Console(out=click.echo, err=functools.partial(click.echo, err=True),
                       progress=progress_bar,
                       keep=functools.partial(meta.__setitem__, "softimpact.kept"))


def exit_with(status: int) -> None:
    """End the command with ``status`` when it is not 0."""
    if status:
        sys.exit(status)


# progress lines started by the running command: its end stops their timers, whatever
# ended it (an error, or a run whose units never reached the total), so that no line is
# printed after the command, e.g. under CliRunner in the tests' process or a notebook
_STARTED_LINES: list = []


def progress_bar(total: int, initial: int = 0, unit: str = "trajectories"):
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


def interruptible(func):
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


def quick_exit() -> None:
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
