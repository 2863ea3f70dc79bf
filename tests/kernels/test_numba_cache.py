"""numba's disk cache must work across processes for kernels taking jitted functions."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from softimpact_cli.kernels.numba_cache import cache_dir

# rk4, the method that compiles fastest, through orbit.flow, the smallest kernel taking
# the method and the system as arguments (the cache's behaviour is the same for every
# method and kernel; classify_near on the default "auto" compiled about 40 s of CPU per
# process, on rk4 about 18 s)
SCRIPT = """
import sys
from softimpact_cli.analysis.engine import Problem, flow
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kernels import orbit
from softimpact_cli.systems import get_system
which = sys.argv[1]
rk4 = IntegratorSettings(method="rk4")
if which == "pair":
    pr = Problem(get_system("duffing", 2), dict(c=0.05, k1=1, k2=0.01, F=1, w=1.3, d=6.0,
                                               phi=0.0, k_c=8, c_c=10, law="paper"), rk4)
    flow(pr, [1.0, 0.0, -1.0, 0.0], 0.0, pr.period)
else:
    pr = Problem(get_system("duffing", 1), dict(c=0.05, k1=1, k2=0.01, F=1, w=1.3), rk4)
    flow(pr, [1.0, 0.0], 0.0, pr.period)
stats = orbit.flow.stats  # what engine.flow calls
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

    from softimpact_cli.kernels.numba_cache import PACKAGE, SOURCES, source_hash

    for folder in SOURCES:
        shutil.copytree(PACKAGE / folder, tmp_path / folder,
                        ignore=shutil.ignore_patterns("__pycache__"))
    before = source_hash(tmp_path)
    assert before == source_hash(PACKAGE)
    target = tmp_path / "kernels" / "switching.py"
    target.write_text(target.read_text() + "\n# edited\n")
    assert source_hash(tmp_path) != before


CATALOGUE = """
import json
from numba.core import event
from softimpact_cli.analysis import warmup
from softimpact_cli.analysis.catalogue import body_catalogue, sample_states
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.analysis.engine import Problem
from softimpact_cli.systems import get_system
missing = warmup.missing_kernels("duffing", 1, "dopri5")
body = get_system("duffing", 1)
problem = Problem(body, body.defaults(), IntegratorSettings(method="dopri5"))
states = sample_states({"x": (-12.0, 12.0), "v": (-12.0, 12.0)}, 2, 0, 0)
with event.install_recorder("numba:compile") as rec:
    attractors, _ = body_catalogue(problem, states)
compiled = sorted({e.data["dispatcher"].py_func.__qualname__ for _, e in rec.buffer})
print(json.dumps({"missing": missing, "compiled": compiled,
                  "multipliers": [repr(complex(m)) for a in attractors for m in a.multipliers]}))
"""


def cache_files(folder):
    return {str(p.relative_to(folder)): p.stat().st_size for p in folder.rglob("*")
            if p.is_file()}


@pytest.mark.slow
def test_catalogue_in_four_processes_stops_growing_the_cache(tmp_path):
    """Issue 20, items 8 and 16: the catalogue's Newton refinement (variational equations)
    compiled in every process and added one `orbit.flow` entry to the disk cache per run,
    until numba failed with "underlying object has vanished". After a first process (on a
    copy of this checkout's cache: warm after `make install`, compiled here otherwise),
    nothing compiles and the cache folder stays byte for byte the same size. Ten
    processes from a cold cache took minutes of the suite; three warm ones show the growth.
    A cold cache's notice: tests/analysis/test_warmup.py."""
    warm = Path(cache_dir())
    shutil.copytree(warm, tmp_path / warm.name)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    runs, sizes = [], []
    for _ in range(4):
        proc = subprocess.run([sys.executable, "-c", CATALOGUE], capture_output=True,
                              text=True, env=env)
        assert proc.returncode == 0, proc.stderr
        runs.append(json.loads(proc.stdout))
        sizes.append(cache_files(tmp_path))
    first, warm_runs = runs[0], runs[1:]
    assert first["multipliers"]  # the catalogue refined at least one orbit
    for run in warm_runs:
        assert run["compiled"] == [] and run["missing"] == []
        assert run["multipliers"] == first["multipliers"]
    assert all(s == sizes[0] for s in sizes[1:])


def test_every_jitted_function_caches_in_the_source_keyed_folder():
    """A jitted module not imported inside ``source_keyed_cache`` would cache next to its
    source and keep stale code after a callee's file changes."""
    import importlib
    import pkgutil

    from numba.core.dispatcher import Dispatcher

    from softimpact_cli import kernels, systems
    from softimpact_cli.kernels.numba_cache import cache_dir

    folder = cache_dir()
    found, elsewhere = 0, []
    for package in (kernels, systems):
        for info in pkgutil.iter_modules(package.__path__):
            module = importlib.import_module(f"{package.__name__}.{info.name}")
            for name, obj in vars(module).items():
                if isinstance(obj, Dispatcher) and obj.py_func.__module__ == module.__name__:
                    found += 1
                    if not obj._cache._cache_path.startswith(folder):
                        elsewhere.append(f"{module.__name__}.{name}")
    assert found > 40 and elsewhere == []


SAVER = """
import sys
import softimpact_cli.kernels  # applies the locked save (unless argv[3] says not to)
from numba.core.caching import IndexDataCacheFile
if sys.argv[3] == "numba":
    IndexDataCacheFile.save = IndexDataCacheFile._softimpact_numba_save
cache = IndexDataCacheFile(sys.argv[1], "kernel", ("stamp", 1))
for k in range(40):
    key = f"{sys.argv[2]}-{k}"
    cache.save(key, key)  # the code of a key is its own name
"""


def save_together(folder, how: str) -> tuple[int, int]:
    """Four processes save 40 new entries each into one index at once; (entries in the
    index, entries whose code is another's)."""
    from numba.core.caching import IndexDataCacheFile

    env = {**os.environ, "NUMBA_CACHE_DIR": str(folder / "numba")}
    procs = [subprocess.Popen([sys.executable, "-c", SAVER, str(folder), f"p{i}", how],
                              env=env) for i in range(4)]
    assert all(p.wait() == 0 for p in procs)
    cache = IndexDataCacheFile(str(folder), "kernel", ("stamp", 1))
    keys = [f"p{i}-{k}" for i in range(4) for k in range(40)]
    loaded = {key: cache.load(key) for key in keys}
    return (sum(v is not None for v in loaded.values()),
            sum(v is not None and v != key for key, v in loaded.items()))


def test_processes_saving_into_one_index_keep_every_entry_with_its_own_code(tmp_path):
    # numba alone loses entries and can point one process's entry at another's code (the
    # cache corruption of parallel compiling); the locked save keeps all 160, each right
    from softimpact_cli.kernels.numba_cache import SAVES_LOCKED

    assert SAVES_LOCKED
    assert save_together(tmp_path, "locked") == (160, 0)
