"""Executors: run a sweep's chunks somewhere and yield their results as they finish.

One interface, ``executor.run(context, chunks) -> iterator of (index, result)``, so the
sweep writes the same file whether chunks ran in this process, on a local process pool,
or on a Dask distributed cluster.

Workers end with the sweep: a pool's workers ignore SIGINT (the parent decides), take
SIGTERM as the end, and ask the kernel to send them SIGTERM when the parent dies (Linux
``PR_SET_PDEATHSIG``; elsewhere a thread polls the parent's pid). A sweep that stops
early (Ctrl-C, SIGTERM, an error) cancels what is queued and terminates its workers
instead of waiting for the running chunks; a Dask run closes its client and cluster.
A Dask cluster that stops running the chunks (closed, or without workers or scheduler)
ends the run with ClusterLost, one line; the chunks written so far are kept.
"""

from __future__ import annotations

import contextlib
import logging
import multiprocessing as mp
import os
import signal
import sys
import threading
import time
from collections.abc import Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

from ..config import ConfigError
from . import interrupt
from .chunks import SweepContext, run_chunk

_CONTEXT: SweepContext | None = None  # a pool worker's copy, set once by its initializer


PR_SET_PDEATHSIG = 1  # from <linux/prctl.h>
WATCH_PARENT_S = 1.0  # how often a worker without PR_SET_PDEATHSIG checks its parent


def end_with_parent(parent: int) -> None:
    """Make this (worker) process receive SIGTERM when process ``parent`` ends."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            if libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0) == 0:
                if os.getppid() != parent:  # it died before prctl took effect
                    os.kill(os.getpid(), signal.SIGTERM)
                return
        except (OSError, AttributeError):
            pass

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(WATCH_PARENT_S)
        os.kill(os.getpid(), signal.SIGTERM)

    threading.Thread(target=watch, name="softimpact-parent-watch", daemon=True).start()


def _init_worker(context: SweepContext, parent: int) -> None:
    global _CONTEXT
    # a fork inherits the parent's handlers: Ctrl-C reaches the whole process group, and
    # only the parent acts on it; SIGTERM (from the parent, or its death) ends a worker
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    end_with_parent(parent)
    _CONTEXT = context


def _run_in_worker(index: int, start: int, stop: int):
    return index, run_chunk(_CONTEXT, start, stop)


class LocalExecutor:
    """A local process pool (``workers`` processes; 1 runs in this process)."""

    def __init__(self, workers: int):
        self.workers = max(1, int(workers))

    def describe(self) -> str:
        return f"local pool, {self.workers} worker{'s' if self.workers > 1 else ''}"

    def run(self, context: SweepContext, chunks: Iterable[tuple[int, int, int]]
            ) -> Iterator[tuple[int, dict]]:
        chunks = list(chunks)
        if self.workers == 1 or len(chunks) <= 1:
            for index, start, stop in chunks:
                yield index, run_chunk(context, start, stop)
            return
        # fork: workers inherit the parent's compiled kernels and the context for free
        ctx = mp.get_context("fork")
        pool = ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=_init_worker,
                                   initargs=(context, os.getpid()))
        finished = False
        try:
            pending = set()
            queue = iter(chunks)
            # keep a bounded number of chunks in flight so that results stream back
            for _ in range(2 * self.workers):
                item = next(queue, None)
                if item is None:
                    break
                pending.add(pool.submit(_run_in_worker, *item))
            while pending:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    yield future.result()
                    item = next(queue, None)
                    if item is not None:
                        pending.add(pool.submit(_run_in_worker, *item))
            finished = True
        finally:
            if finished:
                pool.shutdown(wait=True)
            else:
                stop_pool(pool)


def stop_pool(pool: ProcessPoolExecutor, grace_s: float = 5.0) -> None:
    """Cancel the queued chunks and end the workers now, without waiting for the
    running ones (``shutdown`` alone would)."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in processes:
        if p.is_alive():
            p.terminate()
    deadline = time.monotonic() + grace_s
    for p in processes:
        p.join(max(0.0, deadline - time.monotonic()))
        if p.is_alive():
            p.kill()
            p.join(1.0)


def _ignore_sigint_plugin():
    """A Dask worker plugin: a local cluster's workers share the terminal's process group,
    so a Ctrl-C reaches them too; the sweep decides (it closes the cluster), they would
    only print tracebacks."""
    from dask.distributed import WorkerPlugin

    class IgnoreSigint(WorkerPlugin):
        def setup(self, worker) -> None:
            if threading.current_thread() is threading.main_thread():
                signal.signal(signal.SIGINT, signal.SIG_IGN)

    return IgnoreSigint()


class ClusterLost(ConfigError):
    """The Dask cluster stopped running the sweep's chunks: it was closed, or lost its
    workers or its scheduler. The chunks written so far are kept (``resumable``: the
    command line adds the resume command)."""

    resumable = True


@contextlib.contextmanager
def sigint_blocked_in_new_processes() -> Iterator[None]:
    """Within: SIGINT is blocked in this thread, so that the threads it starts, and the
    processes they spawn (a LocalCluster's workers, which share the terminal's process
    group), are born with it blocked: a Ctrl-C while they import would print a
    KeyboardInterrupt traceback from each. A signal mask is inherited across fork and
    exec; multiprocessing's resource tracker unblocks SIGINT in the thread that starts
    it, so it is started first. Here a Ctrl-C waits until the block ends (run it within
    ``interrupt.deferred()``)."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


class DaskExecutor:
    """A Dask distributed cluster: ``tcp://host:port``, or ``local:N`` for a LocalCluster."""

    def __init__(self, scheduler: str):
        self.scheduler = scheduler

    def describe(self) -> str:
        return f"dask scheduler {self.scheduler}"

    def _lost(self, index: int | None, why: BaseException | str) -> ClusterLost:
        """The one line of a chunk the cluster gave up (``why``: its reason, the first
        line of its text or else its class)."""
        text = str(why).strip().splitlines()[0][:160] if str(why).strip() else \
            why.__class__.__name__
        which = f"chunk {index}" if index is not None else "a chunk"
        return ClusterLost(f"the Dask cluster {self.scheduler} stopped running {which} "
                           f"({text}): it was closed, or lost its workers or scheduler")

    def run(self, context: SweepContext, chunks: Iterable[tuple[int, int, int]]
            ) -> Iterator[tuple[int, dict]]:
        from dask.distributed import Client, LocalCluster, as_completed
        from distributed.scheduler import KilledWorker

        cluster = client = None
        finished = False
        quiet = _QuietDaskLogs()
        try:  # from the start: an interrupted LocalCluster start is closed too
            if self.scheduler.startswith("local:"):
                n = int(self.scheduler.split(":", 1)[1])
                # a Ctrl-C waits for the start to end (then closes the cluster): cut in
                # half, the start would leave workers behind
                with interrupt.deferred(), sigint_blocked_in_new_processes():
                    # CRITICAL: a Ctrl-C or a close cancels running chunks and cuts the
                    # workers' heartbeats, which they would log as warnings and errors with
                    # tracebacks (a chunk's own error reaches the sweep as its exception)
                    cluster = LocalCluster(n_workers=n, threads_per_worker=1,
                                           processes=True, dashboard_address=None,
                                           silence_logs=logging.CRITICAL)
                    client = Client(cluster)
                    client.register_plugin(_ignore_sigint_plugin(),
                                           name="softimpact-ignore-sigint")
            else:
                client = Client(self.scheduler)
            shared = client.scatter(context, broadcast=True)
            futures = [client.submit(run_chunk, shared, start, stop, key=f"chunk-{index}-"
                                     f"{id(context)}", pure=False)
                       for index, start, stop in chunks]
            index_of = {f.key: int(f.key.split("-")[1]) for f in futures}
            done = as_completed(futures, with_results=True)
            while True:
                try:
                    future, result = next(done)
                except StopIteration:
                    break
                except KilledWorker as exc:  # workers died running it, again and again
                    raise self._lost(index_of.get(getattr(exc, "task", None)),
                                     "the workers running it died") from None
                if isinstance(result, BaseException):  # cancelled: the result is why
                    raise self._lost(index_of[future.key], result) from None
                yield index_of[future.key], result
            finished = True
        finally:  # on a remote scheduler, closing the client cancels what it still wants
            # Interrupted or the cluster lost: as_completed's gathers still in flight fail
            # when the client closes, and tornado logs each with a traceback on the loop's
            # thread; they are expected then, so the loggers stay quiet (the process is
            # ending, and ClusterLost or the interruption says what happened)
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()
            if finished:
                quiet.restore()


class _QuietDaskLogs:
    """Dask's loggers (and tornado's and asyncio's, which log the errors of its callbacks
    and tasks, e.g. a scatter cut by the cluster's close: "Task exception was never
    retrieved") at CRITICAL while a sweep runs on a cluster: a cluster closed,
    interrupted or left without workers logs warnings and tracebacks from its client,
    scheduler and workers before the sweep can say in one line what happened
    (ClusterLost, Interrupted); a worker's own error reaches the sweep as the chunk's
    exception. ``restore()`` puts the levels back."""

    def __init__(self):
        names = ["tornado.application", "asyncio", "distributed",
                 *(n for n in list(logging.root.manager.loggerDict)
                   if n.startswith("distributed."))]
        self.levels = {name: logging.getLogger(name).level for name in names}
        for name in names:
            logging.getLogger(name).setLevel(logging.CRITICAL)

    def restore(self) -> None:
        for name, level in self.levels.items():
            logging.getLogger(name).setLevel(level)


def make_executor(workers: int | None, scheduler: str | None):
    """The executor for ``--workers`` / ``--scheduler`` (scheduler wins)."""
    if scheduler:
        return DaskExecutor(scheduler)
    return LocalExecutor(workers if workers else (os.cpu_count() or 1))
