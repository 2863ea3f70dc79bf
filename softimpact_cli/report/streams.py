"""Standard output and error whose reader may go away: a closed pipe never costs a result.

``softimpact sweep S -o R.h5 2>&1 | head -n 2`` closes the pipe after two lines; every
later write (a progress line, the plan, the last "-> R.h5" line) then fails with
BrokenPipeError (Python ignores SIGPIPE). Raised out of a progress callback, that error
ended the sweep after its last chunk and before its result was written.

Within :func:`reader_safe_streams`, ``sys.stdout`` and ``sys.stderr`` are
:class:`ReaderSafeStream` wrappers: the first write or flush that fails with an OSError
(EPIPE, EIO from a closed terminal, a full disk under ``2> log``) or on a closed file
marks the stream as gone, points its file descriptor at /dev/null (so that what is still
buffered, and the interpreter's flush at exit, go nowhere instead of failing: Python
would otherwise exit with status 120), and every later write is dropped. The command
goes on, writes its result and exits with its usual status.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterator
from typing import TextIO

# what a write to a stream whose reader is gone raises: BrokenPipeError (EPIPE) and the
# other OSErrors of a vanished reader or a full disk; ValueError: the file was closed
GONE = (OSError, ValueError)


class ReaderSafeStream:
    """A text stream that drops its output, silently, once its reader is gone.

    Everything but ``write``, ``writelines`` and ``flush`` is the wrapped stream's
    (``isatty``, ``encoding``, ``fileno``, ``buffer``, ...). ``gone``: whether a write
    failed (then nothing more is written).
    """

    def __init__(self, stream: TextIO):
        self.stream = stream
        self.gone = False

    def write(self, text: str) -> int:
        if not isinstance(text, str):  # as a text stream does (click probes with b"")
            raise TypeError(f"write() argument must be str, not {type(text).__name__}")
        if not self.gone:
            try:
                return self.stream.write(text)
            except GONE:
                self._reader_gone()
        return len(text)

    def writelines(self, lines) -> None:
        for line in lines:
            self.write(line)

    def flush(self) -> None:
        if not self.gone:
            try:
                self.stream.flush()
            except GONE:
                self._reader_gone()

    def _reader_gone(self) -> None:
        """Drop what is buffered and every later write; the descriptor writes to
        /dev/null from now on (the interpreter's flush at exit, C-level writers)."""
        self.gone = True
        with contextlib.suppress(OSError, ValueError, AttributeError):
            null = os.open(os.devnull, os.O_WRONLY)
            try:
                os.dup2(null, self.stream.fileno())
            finally:
                os.close(null)
        with contextlib.suppress(*GONE):
            self.stream.flush()  # the bytes still buffered go to /dev/null

    def __getattr__(self, name: str):
        return getattr(self.stream, name)


@contextlib.contextmanager
def reader_safe_streams() -> Iterator[None]:
    """Within: ``sys.stdout`` and ``sys.stderr`` are ReaderSafeStreams; the previous
    streams after (flushed, or pointed at /dev/null if their reader is gone)."""
    previous = sys.stdout, sys.stderr
    wrapped = [s if s is None or isinstance(s, ReaderSafeStream) else ReaderSafeStream(s)
               for s in previous]
    sys.stdout, sys.stderr = wrapped
    try:
        yield
    finally:
        for stream in wrapped:
            if stream is not None:
                stream.flush()
        sys.stdout, sys.stderr = previous
