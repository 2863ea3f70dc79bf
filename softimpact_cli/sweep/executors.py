"""Executors: run a sweep's chunks somewhere and yield their results as they finish.

One interface, ``executor.run(context, chunks) -> iterator of (index, result)``, so the
sweep writes the same file whether chunks ran in this process, on a local process pool,
or on a Dask distributed cluster.
"""

from __future__ import annotations

import multiprocessing as mp
from collections.abc import Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

from .chunks import SweepContext, run_chunk

_CONTEXT: SweepContext | None = None  # a pool worker's copy, set once by its initializer


def _init_worker(context: SweepContext) -> None:
    global _CONTEXT
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
        with ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=_init_worker,
                                 initargs=(context,)) as pool:
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


class DaskExecutor:
    """A Dask distributed cluster: ``tcp://host:port``, or ``local:N`` for a LocalCluster."""

    def __init__(self, scheduler: str):
        self.scheduler = scheduler

    def describe(self) -> str:
        return f"dask scheduler {self.scheduler}"

    def run(self, context: SweepContext, chunks: Iterable[tuple[int, int, int]]
            ) -> Iterator[tuple[int, dict]]:
        from dask.distributed import Client, LocalCluster, as_completed

        cluster = None
        if self.scheduler.startswith("local:"):
            n = int(self.scheduler.split(":", 1)[1])
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        else:
            client = Client(self.scheduler)
        try:
            shared = client.scatter(context, broadcast=True)
            futures = [client.submit(run_chunk, shared, start, stop, key=f"chunk-{index}-"
                                     f"{id(context)}", pure=False)
                       for index, start, stop in chunks]
            index_of = {f.key: int(f.key.split("-")[1]) for f in futures}
            for future, result in as_completed(futures, with_results=True):
                yield index_of[future.key], result
        finally:
            client.close()
            if cluster is not None:
                cluster.close()


def make_executor(workers: int | None, scheduler: str | None):
    """The executor for ``--workers`` / ``--scheduler`` (scheduler wins)."""
    if scheduler:
        return DaskExecutor(scheduler)
    import os

    return LocalExecutor(workers if workers else (os.cpu_count() or 1))
