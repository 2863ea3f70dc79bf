"""pytest plugin: CPU seconds of each test (the process's and its waited children's,
``getrusage``), written as JSON to ``$CPUPLUG_OUT.<worker>.json`` at the end: a test's
cost that a shared machine's load barely moves.

Use: ``PYTHONPATH=benchmarks python -m pytest -p pytest_cpu_per_test``; compare two runs
with ``benchmarks/compare_test_cpu.py`` (results/issue30_measures.md).
"""

import json
import os
import resource

import pytest

_times: dict[str, float] = {}


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    start = _cpu()
    yield
    _times[item.nodeid] = _cpu() - start


def pytest_sessionfinish(session):
    out = os.environ.get("CPUPLUG_OUT")
    if out:
        worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
        with open(f"{out}.{worker}.json", "w") as f:
            json.dump(_times, f)
