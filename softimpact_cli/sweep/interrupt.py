"""Ctrl-C and SIGTERM: end a run at once, cleanly, and say what was kept.

Within ``raising_on_signals()`` the first SIGINT or SIGTERM raises ``Interrupted`` in the
main thread (Python runs signal handlers between bytecodes, so a numba kernel finishes
its call first). The exception unwinds the run: the executors terminate their workers,
the store's files are written atomically so nothing half-written is left.

Two unsafe places: a handler that raises inside a ctypes callback (llvmlite, while numba
compiles) is printed as "Exception ignored" and the run goes on; there the exception is
deferred, rechecked every RECHECK_S by a SIGALRM timer, and raised once the main thread
is back in ordinary code. A signal that arrives while compiled code calls into the C API
can surface as a ``SystemError`` (or a bare ``KeyboardInterrupt``); ``interruption(exc)``
maps every such exception back to the signal received. A second signal exits at once.

The exit status is 128 + the signal number, as a shell reports it: 130 for SIGINT,
143 for SIGTERM.
"""

from __future__ import annotations

import contextlib
import os
import shlex
import signal
import sys
import threading
from collections.abc import Iterator
from pathlib import Path

SIGNALS = (signal.SIGINT, signal.SIGTERM)
RECHECK_S = 0.05  # how soon a deferred interruption is tried again
UNSAFE_MODULES = ("llvmlite",)  # frames whose callers ignore an exception raised in them

_received: int | None = None  # the first signal caught in the current block, if any
_deferring = 0  # depth of ``deferred()`` blocks: within them the interruption waits


class Interrupted(BaseException):
    """A run stopped by a signal; ``status`` is the exit status to end with. A
    BaseException, as KeyboardInterrupt is, so that no ``except Exception`` swallows it."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = int(signum)
        self.status = 128 + int(signum)


def _unsafe(frame) -> bool:
    """Whether an exception raised in ``frame`` could be swallowed (see the module doc)."""
    while frame is not None:
        if str(frame.f_globals.get("__name__", "")).startswith(UNSAFE_MODULES):
            return True
        frame = frame.f_back
    return False


def _handler(signum, frame) -> None:
    global _received
    if _received is not None:  # asked again (while deferred or cleaning up): stop now
        os.write(2, b"softimpact: interrupted again: exiting now\n")
        os._exit(128 + signum)
    _received = signum
    _raise_when_safe(frame)


def _raise_when_safe(frame, *_) -> None:
    """Raise the interruption received, or try again in RECHECK_S if ``frame`` is unsafe."""
    if _received is None or _deferring:
        return
    if _unsafe(frame) and hasattr(signal, "setitimer"):
        signal.setitimer(signal.ITIMER_REAL, RECHECK_S)
        return
    raise Interrupted(_received)


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Within: a signal is noted, not raised; it is raised when the block ends (an
    ``Interrupted`` then, unless the block raised already). For a start that must not
    be cut in half, such as a Dask cluster's, whose parts a half-done start would leave
    running: once started, it is closed as any other."""
    global _deferring
    _deferring += 1
    try:
        yield
    finally:
        _deferring -= 1
    if _received is not None and not _deferring:
        raise Interrupted(_received)


def received() -> int | None:
    """The signal caught by the current ``raising_on_signals`` block, or None."""
    return _received


@contextlib.contextmanager
def raising_on_signals() -> Iterator[None]:
    """Within: SIGINT and SIGTERM raise ``Interrupted``; the previous handlers after.

    A no-op outside the main thread (only it may set handlers). A signal the process
    was started with ignored (``nohup``, a background job's SIGINT) stays ignored.
    """
    global _received
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {s: signal.getsignal(s) for s in (*SIGNALS, signal.SIGALRM)}
    _received = None
    for s in SIGNALS:
        if previous[s] is not signal.SIG_IGN:
            signal.signal(s, _handler)
    signal.signal(signal.SIGALRM, lambda signum, frame: _raise_when_safe(frame))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        for s, h in previous.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)
        _received = None  # a later block (or code outside one) starts uninterrupted


def interruption(exc: BaseException) -> Interrupted | None:
    """The interruption behind ``exc``, or None when it is an ordinary error.

    ``Interrupted`` itself; ``KeyboardInterrupt``; or any exception raised after a signal
    was caught (a numba ``SystemError`` that wraps the handler's exception, a worker pool
    broken by the same Ctrl-C, ...).
    """
    if isinstance(exc, Interrupted):
        return exc
    if isinstance(exc, SystemExit | GeneratorExit):
        return None
    if _received is not None:
        return Interrupted(_received)
    seen = exc
    while seen is not None:
        if isinstance(seen, Interrupted):
            return seen
        if isinstance(seen, KeyboardInterrupt):
            return Interrupted(signal.SIGINT)
        seen = seen.__cause__ or seen.__context__
    return None


def modified(path: Path) -> int | None:
    """``path``'s modification time (ns), None if it does not exist: taken before a run,
    it tells whether an interrupted run wrote the file."""
    try:
        return os.stat(path).st_mtime_ns
    except OSError:
        return None


def sweep_kept(out: Path, scene: str, flags: tuple[str, ...] = (),
               before: int | None = None) -> str:
    """What an interrupted sweep left in ``out``, with the command that finishes it.

    ``flags``: the options that change the scene (``--quick``, ``--resolution N``), which
    the resume must repeat; ``before``: ``modified(out)`` when the run started.
    """
    # deferred: every command's signal handling imports this module, and the store
    # imports xarray (0.8 s); only an interrupted sweep needs it
    from ..store.sweep_store import SweepStore

    store = SweepStore(out)
    try:
        header = store.header()
        done = len(store.done())
    except Exception:  # an unreadable header: a later --resume says what is wrong
        header, done = None, 0
    if header is None or "n_chunks" not in header.attrs:
        return f"nothing written to {out}"
    command = shlex.join(["softimpact", "sweep", scene, "-o", str(out), *flags, "--resume"])
    if int(header.attrs.get("complete", 0)) == 1:
        if before is not None and modified(out) == before:
            return f"nothing written ({out} holds an earlier result, unchanged)"
        if str(header.attrs.get("verify_status", "")).startswith("not verified (interrupted"):
            return f"{out} is complete but not verified; verify with: {command}"
        return f"{out} is complete"
    total = int(header.attrs["n_chunks"])
    return f"{done} of {total} chunks kept in {store.parts}; resume with: {command}"


def exit_interrupted(exc: Interrupted, kept: str) -> None:
    """One line on stderr, then exit with the signal's status."""
    sys.stderr.write(f"softimpact: interrupted ({signal.Signals(exc.signum).name}): {kept}\n")
    sys.stderr.flush()
    sys.exit(exc.status)
