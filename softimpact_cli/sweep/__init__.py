"""Sweeps: every initial condition at every grid point, in chunks, resumably.

``run_sweep`` plans the work, builds the catalogue that names the outcomes, runs the
chunks on an executor (local pool or Dask) and writes them through the store as they
finish; at the end it assembles the labelled dataset. ``sweep_in_memory`` runs the same
chunks and assembly without a file (the Python API's ``run``).

The names are imported on first use: ``import softimpact_cli`` imports this package
(before it binds its own ``sweep``, the API function, which would otherwise be replaced
by this package on its first import), and must not pay for xarray and the store.
"""

import importlib

# the runner imports the analyses and the kernels: only when a sweep runs, so that the
# CLI's signal handling (sweep.interrupt) costs no kernel import
_NAMES = {"prepare_catalogues": "runner", "run_sweep": "runner",
          "sweep_in_memory": "in_memory", "label_states": "in_memory"}

__all__ = sorted(_NAMES)


def __getattr__(name: str):
    if name in _NAMES:
        return getattr(importlib.import_module(f".{_NAMES[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
