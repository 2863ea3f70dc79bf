"""A sweep's result on disk, written chunk by chunk so that a killed run loses nothing.

Layout while running:

- ``RESULT.h5``: written first (atomically), a valid netCDF file holding the plan, the
  scene, the catalogue and ``complete = 0``. ``xarray.open_dataset`` reads it; ``info``
  shows its progress. It is never mistaken for a result: ``complete`` is 0.
- ``RESULT.h5.parts/chunk-NNNNNNN.npz``: one file per finished chunk, each written to a
  temporary name and renamed, so a file that exists is whole.

At the end the chunks are assembled into the final dataset, which atomically replaces
``RESULT.h5`` (``complete = 1``), and the parts folder is removed.
"""

from __future__ import annotations

import os
import pickle
import shutil
from pathlib import Path

import numpy as np
import xarray as xr

from .h5netcdf_ import ENGINE, write_result

PART = "chunk-{:07d}.npz"


class SweepStore:
    def __init__(self, path: str | os.PathLike):
        self.path = Path(path)
        self.parts = self.path.with_name(self.path.name + ".parts")

    # ------------------------------------------------------------ state
    def exists(self) -> bool:
        return self.path.exists() or self.parts.exists()

    def header(self) -> xr.Dataset | None:
        """The file's attributes and catalogue (complete or not), or None."""
        if not self.path.exists():
            return None
        with xr.open_dataset(self.path, engine=ENGINE) as ds:
            return ds.load()

    def done(self) -> set[int]:
        """Indices of the chunks already on disk."""
        if not self.parts.is_dir():
            return set()
        return {int(p.name[6:13]) for p in self.parts.glob("chunk-*.npz")
                if len(p.name) == len(PART.format(0))}

    # ------------------------------------------------------------ writing
    def start(self, header: xr.Dataset) -> None:
        """Write the header file and create the parts folder (a fresh run)."""
        if self.parts.exists():
            shutil.rmtree(self.parts)
        write_result(header, self.path)
        self.parts.mkdir(parents=True)

    def write_chunk(self, index: int, result: dict) -> None:
        """Store one chunk's arrays and representative orbits, atomically."""
        final = self.parts / PART.format(index)
        tmp = final.with_name(final.name + ".tmp")
        arrays = {k: v for k, v in result.items() if k != "orbits"}
        arrays["orbits"] = np.frombuffer(pickle.dumps(result.get("orbits", {})), dtype=np.uint8)
        with open(tmp, "wb") as fh:
            np.savez(fh, **arrays)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, final)

    def read_chunk(self, index: int) -> dict:
        with np.load(self.parts / PART.format(index)) as data:
            out = {k: data[k] for k in data.files if k != "orbits"}
            # our own file, written by write_chunk above: pickle is safe here
            out["orbits"] = pickle.loads(data["orbits"].tobytes())
        return out

    def finish(self, result: xr.Dataset) -> Path:
        """Atomically replace the header with the complete result; drop the parts."""
        write_result(result, self.path)
        shutil.rmtree(self.parts, ignore_errors=True)
        return self.path

    def remove(self) -> None:
        if self.path.exists():
            self.path.unlink()
        shutil.rmtree(self.parts, ignore_errors=True)
