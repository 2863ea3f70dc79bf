"""numba's disk cache for this package: a folder keyed by the sources, and stable
identities for jitted functions.

**The folder.** numba invalidates a cached function only when its *own* file changes; a
kernel that calls into another module (``dopri5.advance`` calling
``switching.first_exit``) would otherwise keep running stale code after that module is
edited. ``source_keyed_cache()`` points numba at a folder named by a hash of every kernel
and system source file while ``kernels`` and ``systems`` import their modules (numba
binds a function's cache folder when it is decorated), so any edit starts a fresh cache.
The folder is ``$NUMBA_CACHE_DIR`` (or ``$XDG_CACHE_HOME``, or ``~/.cache``)
``/softimpact/<hash>``. A jitted module must therefore be imported by its package's
``__init__`` inside that context (``tests/kernels/test_numba_cache.py`` checks every
dispatcher's folder).

**The identities.** Our kernels take other jitted functions as arguments (the system's
right-hand side, the integrator's ``advance``). numba's cache index keys then contain
dispatcher types, which numba pickles by the dispatcher's UUID, a random string drawn
once per process. In another process such a key is rebuilt around a fresh dispatcher
object: it never equals the live one (so cached code is missed) and, being unreferenced,
it is collected, so adding a new entry to the index fails with "ReferenceError:
underlying object has vanished" (seen on Dask workers; numba issues #2956 and #6251 are
the same family). Giving every module-level dispatcher of this package a UUID derived
from its qualified name, before anything pickles it, makes the rebuilt key resolve to
the live dispatcher in every process. This relies on numba's ``_MemoMixin._set_uuid``
(present since numba 0.49); ``tests/kernels/test_numba_cache.py`` checks the behaviour
across processes.

**Saving from several processes.** numba's save of a new entry is not safe against
another process saving into the same index at once; ``lock_cache_saves`` (applied on
import) serialises saves with a POSIX lock per index, so the warm-up and test workers can
compile into one folder together (see ``_locked_save``).
"""

from __future__ import annotations

import contextlib
import hashlib
import os
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import numba
from numba.core.caching import IndexDataCacheFile
from numba.core.dispatcher import Dispatcher

try:
    import fcntl
except ImportError:  # no POSIX locks (Windows): saves stay numba's own
    fcntl = None

PACKAGE = Path(__file__).resolve().parents[1]  # softimpact_cli/
SOURCES = ("kernels", "systems")  # the folders whose files key the cache


def source_hash(root: Path = PACKAGE, folders: tuple[str, ...] = SOURCES) -> str:
    """16 hex digits of a hash over every ``*.py`` of ``root``'s ``folders`` (default: the
    SOURCES folders that key numba's cache)."""
    digest = hashlib.sha256()
    for folder in folders:
        for path in sorted((root / folder).glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def cache_dir(root: Path = PACKAGE) -> str | None:
    """The source-keyed cache folder (created), or None when it cannot be written."""
    base = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "softimpact")
    path = os.path.join(base, source_hash(root))
    try:
        os.makedirs(path, exist_ok=True)
    except OSError:
        return None  # numba then caches next to the sources, as it would by default
    return path if os.access(path, os.W_OK) else None


@contextlib.contextmanager
def source_keyed_cache() -> Iterator[None]:
    """Functions decorated inside cache in :func:`cache_dir`; numba's setting is restored
    afterwards, so other numba code of the user's process is not affected."""
    previous = numba.config.CACHE_DIR
    folder = cache_dir()
    if folder is not None:
        numba.config.CACHE_DIR = folder
    try:
        yield
    finally:
        numba.config.CACHE_DIR = previous


def stabilise(module: ModuleType) -> None:
    """Give each jitted function of ``module`` a UUID made of its qualified name."""
    for name, obj in vars(module).items():
        if not isinstance(obj, Dispatcher) or obj.py_func.__module__ != module.__name__:
            continue
        if getattr(obj, "_MemoMixin__uuid", None) is None:
            obj._set_uuid(f"softimpact:{module.__name__}.{name}")


# ---------------------------------------------------------------------------------------
# saving under a lock: several processes may compile into one folder at once


# numba's own save (kept across a reload of this module, which must not wrap it twice)
_numba_save = getattr(IndexDataCacheFile, "_softimpact_numba_save", IndexDataCacheFile.save)


def _locked_save(self, key, data):
    """numba's ``IndexDataCacheFile.save`` holding an exclusive lock on the index, and
    writing the code before the index entry that names it.

    numba reads the index, takes the first free file number, and writes the index and the
    code file, with nothing held between: two processes saving new entries of one kernel
    at once (two models' ``orbit.classify_near``) both take the same number, and one
    model's index entry can end up naming the other's code (a later run then fails to
    type the call). Under the lock the two saves follow one another. Readers need no
    lock: every file is replaced whole (``os.replace``), and an index entry is written
    only after its code.
    """
    try:
        lock = open(self._index_path + ".lock", "a")  # noqa: SIM115 (closed below)
    except OSError:  # a folder we may not write in: numba's save says why, if it fails
        return _numba_save(self, key, data)
    with lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            overloads = self._load_index()
            data_name = overloads.get(key)
            if data_name is None:
                existing = set(overloads.values())
                number = 1
                while self._data_name(number) in existing:
                    number += 1
                data_name = self._data_name(number)
                self._save_data(data_name, data)
                overloads[key] = data_name
                self._save_index(overloads)
            else:
                self._save_data(data_name, data)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


# what ``_locked_save`` uses of numba's class (as in numba 0.68; checked, so that
# another layout leaves numba's save in place instead of failing at the first save)
_NUMBA_PARTS = ("_index_path", "_load_index", "_save_index", "_save_data", "_data_name")


def lock_cache_saves() -> bool:
    """Make numba's cache saves safe across processes (``_locked_save``); False where
    there are no POSIX locks or numba's cache file is not as expected (then compile in one
    process at a time)."""
    if fcntl is None:
        return False
    try:  # (its constructor only sets attributes)
        probe = IndexDataCacheFile("", "probe", None)
    except TypeError:
        return False
    if not all(hasattr(probe, part) for part in _NUMBA_PARTS):
        return False
    IndexDataCacheFile._softimpact_numba_save = _numba_save
    IndexDataCacheFile.save = _locked_save
    return True


SAVES_LOCKED = lock_cache_saves()
