"""Progress for logs: when stderr is not a terminal (CI, ``2> log``), one line at a steady
interval instead of a progress bar, e.g.

    progress: 1200/40000 trajectories (3.0%), 85 /s, ETA 7m40s, unresolved 3 (0.25%)

The interval is ``SOFTIMPACT_PROGRESS_INTERVAL`` seconds (default 30); a last line is
printed when the work is done. Fed with counts, or with a chunk's label codes (then the
unresolved and diverged outcomes are counted too, and the trajectories the second stage
found on a recurrent set, coded ``PENDING`` until the parent names them).
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable

import numpy as np

from ..kernels.codes import DIVERGED_LABEL, PENDING, UNRESOLVED_LABEL
from ..sweep.interrupt import received

INTERVAL_ENV = "SOFTIMPACT_PROGRESS_INTERVAL"
DEFAULT_INTERVAL_S = 30.0


def interval_s() -> float:
    """Seconds between progress lines (``SOFTIMPACT_PROGRESS_INTERVAL``, default 30)."""
    try:
        value = float(os.environ.get(INTERVAL_ENV, DEFAULT_INTERVAL_S))
    except ValueError:
        return DEFAULT_INTERVAL_S
    return value if value > 0 else DEFAULT_INTERVAL_S


def duration(seconds: float) -> str:
    """``12s``, ``7m40s``, ``2h05m``."""
    s = int(round(seconds))
    if s < 60:
        return f"{s}s"
    if s < 3600:
        return f"{s // 60}m{s % 60:02d}s"
    return f"{s // 3600}h{s % 3600 // 60:02d}m"


class ProgressLines:
    """Counts work done and prints a progress line every ``interval`` seconds.

    ``total``: units of work; ``initial``: units already done (a resumed sweep), which do
    not count in the rate. Call the object with a count or with an array of label codes;
    ``close()`` stops the timer (it stops by itself when the total is reached).
    """

    def __init__(self, total: int, initial: int = 0, unit: str = "trajectories",
                 interval: float | None = None,
                 write: Callable[[str], None] | None = None):
        self.total, self.initial, self.unit = int(total), int(initial), unit
        self.done = int(initial)
        self.unresolved = self.diverged = self.labelled = self.recurrent = 0
        self.interval = interval_s() if interval is None else float(interval)
        self._write = write or (lambda line: print(line, file=sys.stderr, flush=True))
        self._started = time.monotonic()
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="softimpact-progress",
                                        daemon=True)
        self._thread.start()

    def __call__(self, work) -> None:
        """Add ``work``: a number of units, or the label codes of that many trajectories."""
        if np.ndim(work) == 0:
            n = int(work)
        else:
            codes = np.asarray(work)
            n = codes.size
            with self._lock:
                self.unresolved += int(np.count_nonzero(codes == UNRESOLVED_LABEL))
                self.diverged += int(np.count_nonzero(codes == DIVERGED_LABEL))
                self.recurrent += int(np.count_nonzero(codes == PENDING))
                self.labelled += n
        with self._lock:
            self.done += n
            finished = self.done >= self.total
        if finished and not self._stop.is_set():
            self.close()
            self._write(self.line())

    def line(self) -> str:
        with self._lock:
            done, unresolved, diverged, labelled, recurrent = (
                self.done, self.unresolved, self.diverged, self.labelled, self.recurrent)
        elapsed = time.monotonic() - self._started
        rate = (done - self.initial) / elapsed if elapsed > 0 else 0.0
        share = 100.0 * done / self.total if self.total else 100.0
        parts = [f"progress: {done}/{self.total} {self.unit} ({share:.1f}%)",
                 f"{rate:.3g} /s"]
        if done < self.total:
            parts.append(f"ETA {duration((self.total - done) / rate)}" if rate > 0
                         else "ETA unknown")
        else:
            parts.append(f"took {duration(elapsed)}")
        if labelled:
            parts.append(f"unresolved {unresolved} ({100.0 * unresolved / labelled:.2f}%)")
            if diverged:
                parts.append(f"diverged {diverged} ({100.0 * diverged / labelled:.2f}%)")
            if recurrent:  # the second stage's, named (chaotic A1...) after the last chunk
                parts.append(f"on a recurrent set {recurrent} "
                             f"({100.0 * recurrent / labelled:.2f}%, named at the end)")
        return ", ".join(parts)

    def _run(self) -> None:
        # an interrupted run is being cleaned up: its last line would only repeat itself
        while not self._stop.wait(self.interval) and received() is None:
            self._write(self.line())

    def close(self) -> None:
        """Stop the timer and wait for its thread, so no line follows the caller's last."""
        self._stop.set()
        if self._thread is not threading.current_thread():
            self._thread.join(timeout=5.0)
