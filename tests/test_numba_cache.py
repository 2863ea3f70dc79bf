"""numba's disk cache must work across processes for kernels taking jitted functions."""

import os
import subprocess
import sys

SCRIPT = """
import sys
from softimpact_cli.engine import Problem, classify_state
from softimpact_cli.kernels import orbit
from softimpact_cli.systems import get_system
which = sys.argv[1]
if which == "pair":
    pr = Problem(get_system("duffing", 2), dict(c=0.05, k1=1, k2=0.01, F=1, w=1.3, d=6.0,
                                               phi=0.0, k_c=8, c_c=10, law="paper"))
    classify_state(pr, [1.0, 0.0, -1.0, 0.0])
else:
    pr = Problem(get_system("duffing", 1), dict(c=0.05, k1=1, k2=0.01, F=1, w=1.3))
    classify_state(pr, [1.0, 0.0])
stats = orbit.classify_near.stats  # what classify_state calls
print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))
"""


def run(which, cache_dir):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache_dir)}
    proc = subprocess.run([sys.executable, "-c", SCRIPT, which], capture_output=True,
                          text=True, env=env)
    assert proc.returncode == 0, proc.stderr
    hits, misses = map(int, proc.stdout.split())
    return hits, misses


def test_second_process_adds_and_third_reuses(tmp_path):
    assert run("pair", tmp_path) == (0, 1)  # compiled and saved
    assert run("body", tmp_path) == (0, 1)  # another specialization added to the index
    assert run("pair", tmp_path) == (1, 0)  # both load from disk in a fresh process
    assert run("body", tmp_path) == (1, 0)


def test_cache_folder_changes_when_any_kernel_source_changes(tmp_path):
    """numba only watches a function's own file; the folder key covers all of them."""
    import shutil

    from softimpact_cli._numba_cache_dir import PACKAGE, SOURCES, source_hash

    for folder in SOURCES:
        shutil.copytree(PACKAGE / folder, tmp_path / folder,
                        ignore=shutil.ignore_patterns("__pycache__"))
    before = source_hash(tmp_path)
    assert before == source_hash(PACKAGE)
    target = tmp_path / "kernels" / "switching.py"
    target.write_text(target.read_text() + "\n# edited\n")
    assert source_hash(tmp_path) != before
