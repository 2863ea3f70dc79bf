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
"""

from __future__ import annotations

import contextlib
import hashlib
import os
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import numba
from numba.core.dispatcher import Dispatcher

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
