"""The pytest plugin that names the tests compiling numba kernels
(benchmarks/pytest_compile_per_test.py) sees a compilation and only where it happens."""

import json
import os
import subprocess
import sys
from pathlib import Path

BENCHMARKS = Path(__file__).parents[1] / "benchmarks"

TESTS = '''
from numba import njit


def test_compiles():
    @njit
    def twice(x):
        return 2 * x
    assert twice(3) == 6


def test_compiles_nothing():
    assert sum(range(4)) == 6
'''


def test_a_test_that_compiles_is_named_with_what_it_compiled(tmp_path):
    (tmp_path / "test_toy.py").write_text(TESTS)
    out = tmp_path / "compile"
    env = {**os.environ, "COMPILEPLUG_OUT": str(out), "PYTHONPATH": str(BENCHMARKS)}
    env.pop("PYTEST_XDIST_WORKER", None)
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                          "-p", "pytest_compile_per_test", "-p", "no:xdist", "test_toy.py"],
                         cwd=tmp_path, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    found = json.loads((tmp_path / "compile.main.json").read_text())
    assert list(found["seconds"]) == ["test_toy.py::test_compiles"]
    assert found["seconds"]["test_toy.py::test_compiles"] > 0
    assert found["compiled"]["test_toy.py::test_compiles"] == ["test_compiles.<locals>.twice"]
