"""Stable identities for jitted functions, so that numba's disk cache works across processes.

Our kernels take other jitted functions as arguments (the system's right-hand side, the
integrator's ``advance``). numba's cache index keys then contain dispatcher types, which
numba pickles by the dispatcher's UUID, a random string drawn once per process. In another
process such a key is rebuilt around a fresh dispatcher object: it never equals the live
one (so cached code is missed) and, being unreferenced, it is collected, so adding a new
entry to the index fails with "ReferenceError: underlying object has vanished" (seen on
Dask workers; numba issues #2956 and #6251 are the same family).

Giving every module-level dispatcher of this package a UUID derived from its qualified
name, before anything pickles it, makes the rebuilt key resolve to the live dispatcher in
every process. This relies on numba's ``_MemoMixin._set_uuid`` (present since numba 0.49);
``tests/kernels/test_numba_cache.py`` checks the behaviour across processes.
"""

from __future__ import annotations

from types import ModuleType

from numba.core.dispatcher import Dispatcher


def stabilise(module: ModuleType) -> None:
    """Give each jitted function of ``module`` a UUID made of its qualified name."""
    for name, obj in vars(module).items():
        if not isinstance(obj, Dispatcher) or obj.py_func.__module__ != module.__name__:
            continue
        if getattr(obj, "_MemoMixin__uuid", None) is None:
            obj._set_uuid(f"softimpact:{module.__name__}.{name}")
