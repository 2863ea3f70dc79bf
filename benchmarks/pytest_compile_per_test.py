"""pytest plugin: seconds of numba compilation in each test (wall time of the outermost
compilations in the test's own process), and what was compiled, written as JSON to
``$COMPILEPLUG_OUT.<worker>.json`` at the end: which tests compile kernels the warm-up
(``python -m softimpact_cli.analysis.warmup``) left out, i.e. what a CI run compiles after
the install.

Use beside ``pytest_cpu_per_test``, on a cache just warmed (a copy of it per run, so that
one run's compiles do not hide the next's; ``$NUMBA_CACHE_DIR`` holds the hash folder):

    cp -a ~/.cache/softimpact /tmp/warm-copy
    NUMBA_CACHE_DIR=/tmp/warm-copy COMPILEPLUG_OUT=/tmp/compile CPUPLUG_OUT=/tmp/cpu \\
        PYTHONPATH=benchmarks python -m pytest -p pytest_cpu_per_test \\
        -p pytest_compile_per_test -p no:cacheprovider tests/...

JSON: {"seconds": {nodeid: s}, "compiled": {nodeid: [function names]}}, tests that
compiled under 0.05 s left out.
"""

import json
import os
import time

import pytest
from numba.core import event

_seconds: dict[str, float] = {}
_compiled: dict[str, list[str]] = {}


class _CompileTimer(event.Listener):
    """Sums the outermost compilations' wall time (a compilation nests its callees')."""

    def __init__(self):
        self.depth, self.started, self.total, self.names = 0, 0.0, 0.0, set()

    def on_start(self, ev):
        if self.depth == 0:
            self.started = time.perf_counter()
            func = getattr(ev.data.get("dispatcher"), "py_func", None)
            self.names.add(getattr(func, "__qualname__", "?"))
        self.depth += 1

    def on_end(self, ev):
        self.depth -= 1
        if self.depth == 0:
            self.total += time.perf_counter() - self.started


_timer = _CompileTimer()
event.register("numba:compile", _timer)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    before = _timer.total
    _timer.names = set()
    yield
    spent = _timer.total - before
    if spent > 0.05:
        _seconds[item.nodeid] = spent
        _compiled[item.nodeid] = sorted(_timer.names)


def pytest_sessionfinish(session):
    out = os.environ.get("COMPILEPLUG_OUT")
    if out:
        worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
        with open(f"{out}.{worker}.json", "w") as f:
            json.dump({"seconds": _seconds, "compiled": _compiled}, f)
