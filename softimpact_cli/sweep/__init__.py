"""Sweeps: every initial condition at every grid point, in chunks, resumably.

``run_sweep`` plans the work, builds the catalogue that names the outcomes, runs the
chunks on an executor (local pool or Dask) and writes them through the store as they
finish; at the end it assembles the labelled dataset.
"""

__all__ = ["prepare_catalogues", "run_sweep"]


def __getattr__(name: str):
    # the runner imports the analyses and the kernels: only when a sweep runs, so that
    # the CLI's signal handling (sweep.interrupt) costs no kernel import
    if name in __all__:
        from . import runner

        return getattr(runner, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
