"""The results store: datasets to HDF5 files that ``xarray.open_dataset`` reads back.

Only this package imports h5py / h5netcdf.
"""

from .h5netcdf_ import add_attributes, open_result, update_attributes, write_result
from .provenance import provenance

__all__ = ["add_attributes", "open_result", "provenance", "update_attributes", "write_result"]
