"""xarray's dask probes, answered without importing dask while nothing has imported it.

xarray asks "is this a dask array?" (when it builds any variable), "is this a dask
collection?" and, when it writes a file, "which dask scheduler is running?". With dask
installed it answers each by importing dask: ``dask.array`` (with ``scipy.fft`` and
``scipy.sparse``) on the first variable, ``distributed`` on the first write. That was
0.3 s of a 3 s `softimpact sweep` of 100 trajectories that never touches a dask array
(the Dask executor sends chunks of plain arrays, and results are read without
``chunks``).

No dask object can exist before its module is imported, so while ``dask.array``
(``dask``, ``distributed``) is absent from ``sys.modules`` the answer is "no" without
importing anything; once something imports it, every probe asks xarray's own code
again. :func:`install` wraps the probes accordingly, once per process; with an xarray
whose internals have moved it does nothing (xarray then imports dask as before).
"""

from __future__ import annotations

import sys

_INSTALLED: list = []


class _LazyDaskArrayModule:
    """Stands in for xarray's cached ``DuckArrayModule("dask")``: no array type until
    ``dask.array`` is imported, then the real entry (built on first use)."""

    def __init__(self, real_class):
        self._real_class = real_class
        self._real = None

    def _entry(self):
        if self._real is None:
            self._real = self._real_class("dask")
        return self._real

    @property
    def type(self):
        if "dask.array" not in sys.modules:
            return ()
        return self._entry().type

    def __getattr__(self, name):  # module, version, available: ask the real entry
        return getattr(self._entry(), name)


def install() -> None:
    """Make xarray's dask probes lazy in this process (idempotent)."""
    if _INSTALLED:
        return
    _INSTALLED.append(True)
    try:
        from xarray.backends import locks, writers
        from xarray.namedarray import pycompat
        from xarray.namedarray import utils as named_utils
    except ImportError:
        return
    cache = getattr(pycompat, "_cached_duck_array_modules", None)
    if isinstance(cache, dict) and "dask" not in cache and \
            hasattr(pycompat, "DuckArrayModule"):
        cache["dask"] = _LazyDaskArrayModule(pycompat.DuckArrayModule)

    is_collection = getattr(named_utils, "is_dask_collection", None)
    if callable(is_collection):
        def is_dask_collection(x):
            return "dask" in sys.modules and is_collection(x)

        named_utils.is_dask_collection = is_dask_collection

    get_scheduler = getattr(locks, "get_dask_scheduler", None)
    if callable(get_scheduler) and getattr(writers, "get_dask_scheduler", None) is \
            get_scheduler:
        # "threaded": xarray's answer when dask is installed and no scheduler is set,
        # whose write lock is a thread lock; a file without dask variables is written
        # the same under any answer (the scheduler only decides for chunked ones)
        def get_dask_scheduler(get=None, collection=None):
            if "dask" not in sys.modules and get is None and collection is None:
                return "threaded"
            return get_scheduler(get, collection)

        locks.get_dask_scheduler = get_dask_scheduler
        writers.get_dask_scheduler = get_dask_scheduler
