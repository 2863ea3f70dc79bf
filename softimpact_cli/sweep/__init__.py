"""Sweeps: every initial condition at every grid point, in chunks, resumably.

``run_sweep`` plans the work, builds the catalogue that names the outcomes, runs the
chunks on an executor (local pool or Dask) and writes them through the store as they
finish; at the end it assembles the labelled dataset.
"""

from .runner import prepare_catalogues, run_sweep

__all__ = ["prepare_catalogues", "run_sweep"]
