"""A sweep's result on disk, written chunk by chunk so that a killed run loses nothing.

Layout while running:

- ``RESULT.h5``: written first (atomically), a valid netCDF file holding the plan, the
  scene, the catalogue and ``complete = 0``. ``xarray.open_dataset`` reads it; ``info``
  shows its progress. It is never mistaken for a result: ``complete`` is 0.
- ``RESULT.h5.parts/chunk-NNNNNNN.npz``: one file per finished chunk, each written to a
  temporary name and renamed. Plain arrays only (no pickle), plus a ``meta`` record: the
  scene's hash, the chunk's index and flat range [start, stop), the plan's chunk size and
  total, the session that wrote it, and a SHA-256 over all of that and every array. A
  part is used only when all of it matches (``read_chunk``/``verify``).

At the end the chunks are assembled into the final dataset, which atomically replaces
``RESULT.h5`` (``complete = 1``), and the parts folder is removed.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import time
import zipfile
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from ..config import ConfigError
from .checksum import payload_digest as _digest
from .h5netcdf_ import ENGINE, write_result

PART = "chunk-{:07d}.npz"
PART_FORMAT = 2
ORBIT_ARRAYS = ("orbit_point", "orbit_code", "orbit_flat", "orbit_length", "orbit_points")


class DamagedPart(Exception):
    """A chunk file that is unreadable, damaged or belongs to another run; str: why."""


class DamagedHeader(Exception):
    """A result header that exists but cannot be read; str: why."""


# what every complete sweep result holds: one value per trajectory of each
RESULT_VARIABLES = ("label", "status", "period")


def result_problem(ds: xr.Dataset, n_total: int) -> str | None:
    """What keeps ``ds``, read from a file whose ``complete`` attribute is 1, from being
    the complete result of a sweep of ``n_total`` trajectories (None: nothing). A header
    can say complete without being a result: a hand-made or hand-edited file, or one
    whose variables were removed by another tool."""
    for name in RESULT_VARIABLES:
        if name not in ds:
            return f"holds no {name!r} variable"
        if ds[name].size != n_total:
            return f"its {name!r} has {ds[name].size} values, not the run's {n_total}"
    return None


@dataclass(frozen=True)
class RunIdentity:
    """What every chunk file of one sweep shares: the scene and the plan's cut."""

    scene_sha256: str
    chunk_size: int
    n_total: int

    def chunk(self, index: int) -> tuple[int, int]:
        start = index * self.chunk_size
        return start, min(start + self.chunk_size, self.n_total)

    @property
    def n_chunks(self) -> int:
        return -(-self.n_total // self.chunk_size)


def _orbit_arrays(orbits: dict, dim: int) -> dict[str, np.ndarray]:
    """{(grid point, code): (flat index, points (q, dim))} as five plain arrays."""
    keys = sorted(orbits)
    pts = [np.asarray(orbits[k][1], dtype=np.float64).reshape(-1, dim) for k in keys]
    return {
        "orbit_point": np.array([k[0] for k in keys], dtype=np.int64),
        "orbit_code": np.array([k[1] for k in keys], dtype=np.int64),
        "orbit_flat": np.array([orbits[k][0] for k in keys], dtype=np.int64),
        "orbit_length": np.array([p.shape[0] for p in pts], dtype=np.int64),
        "orbit_points": np.concatenate(pts) if pts else np.zeros((0, dim)),
    }


def _orbits_of(arrays: dict[str, np.ndarray]) -> dict:
    out = {}
    ends = np.cumsum(arrays["orbit_length"])
    for i, end in enumerate(ends):
        start = end - arrays["orbit_length"][i]
        key = (int(arrays["orbit_point"][i]), int(arrays["orbit_code"][i]))
        out[key] = (int(arrays["orbit_flat"][i]), arrays["orbit_points"][start:end])
    return out


class SweepStore:
    def __init__(self, path: str | os.PathLike):
        self.path = Path(path)
        self.parts = self.path.with_name(self.path.name + ".parts")

    # ------------------------------------------------------------ state
    def exists(self) -> bool:
        return self.path.exists() or self.parts.exists()

    def header(self) -> xr.Dataset | None:
        """The file's attributes and catalogue (complete or not); None when there is no
        file; DamagedHeader when it cannot be read (truncated, not HDF5, ...)."""
        if not self.path.exists():
            return None
        try:
            with xr.open_dataset(self.path, engine=ENGINE) as ds:
                return ds.load()
        except Exception as exc:  # any reader failure means the file is damaged
            raise DamagedHeader(f"{exc.__class__.__name__}") from None

    def done(self) -> set[int]:
        """Indices of the chunk files on disk (not verified; see ``verify``)."""
        if not self.parts.is_dir():
            return set()
        return {int(p.name[6:13]) for p in self.parts.glob("chunk-*.npz")
                if len(p.name) == len(PART.format(0)) and p.name[6:13].isdigit()}

    # ------------------------------------------------------------ writing
    def start(self, header: xr.Dataset) -> None:
        """Write the header file and create an empty parts folder (a fresh run)."""
        if self.parts.exists():
            shutil.rmtree(self.parts)
        write_result(header, self.path)
        self.ensure_parts()

    def write_header(self, header: xr.Dataset) -> None:
        """Rewrite the header (a resume: its history; or a damaged one), atomically."""
        write_result(header, self.path)

    def ensure_parts(self) -> bool:
        """Create the parts folder if it is missing; True if it had to be created."""
        if self.parts.is_dir():
            return False
        try:
            self.parts.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ConfigError(f"{self.parts}: cannot create the chunk folder "
                              f"({exc.strerror or exc.__class__.__name__})") from None
        return True

    def write_chunk(self, index: int, result: dict, identity: RunIdentity,
                    session_started: float) -> None:
        """Store one chunk's arrays and representative orbits with their identity and
        checksum, atomically. ``result``: RESULT_FIELDS arrays and ``orbits``."""
        start, stop = identity.chunk(index)
        arrays = {k: np.asarray(v) for k, v in result.items() if k != "orbits"}
        dim = max((np.asarray(p).shape[-1] for _, p in result.get("orbits", {}).values()),
                  default=1)
        arrays.update(_orbit_arrays(result.get("orbits", {}), dim))
        body = {"format": PART_FORMAT, **asdict(identity), "chunk": index, "start": start,
                "stop": stop, "session_started": session_started, "written": time.time()}
        meta = {**body, "checksum": _digest(body, arrays)}
        arrays["meta"] = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
        self.ensure_parts()
        final = self.parts / PART.format(index)
        tmp = final.with_name(final.name + ".tmp")
        try:
            with open(tmp, "wb") as fh:
                np.savez(fh, **arrays)
                fh.flush()
                os.fsync(fh.fileno())
            os.replace(tmp, final)
        except OSError as exc:
            with contextlib.suppress(OSError):
                tmp.unlink()
            raise ConfigError(f"{final}: cannot write chunk {index} "
                              f"({exc.strerror or exc.__class__.__name__}); the chunks "
                              "written so far are kept: fix this, then run again with "
                              "--resume") from None

    # ------------------------------------------------------------ reading
    def read_chunk(self, index: int, identity: RunIdentity) -> tuple[dict, dict]:
        """(arrays with ``orbits``, meta) of chunk ``index``; DamagedPart if the file is
        unreadable, fails its checksum, or is not this run's chunk ``index``."""
        path = self.parts / PART.format(index)
        try:
            if path.stat().st_size == 0:
                raise DamagedPart("empty file")
            with np.load(path, allow_pickle=False) as data:
                arrays = {k: data[k] for k in data.files}
            meta = json.loads(arrays.pop("meta").tobytes().decode())
            if not isinstance(meta, dict):
                raise ValueError("meta is not a record")
        except DamagedPart:
            raise
        except FileNotFoundError:
            raise DamagedPart("missing") from None
        except zipfile.BadZipFile as exc:
            if "CRC" in str(exc):  # the zip member's own checksum caught the flip
                raise DamagedPart("checksum") from None
            raise DamagedPart("unreadable (truncated or damaged)") from None
        except Exception:  # truncated zip, bad JSON, ...: the file is damaged
            raise DamagedPart("unreadable (truncated or damaged)") from None
        body = {k: v for k, v in meta.items() if k != "checksum"}
        if meta.get("checksum") != _digest(body, arrays):
            raise DamagedPart("checksum")
        if meta.get("format") != PART_FORMAT:
            raise DamagedPart("written by another version")
        if meta.get("scene_sha256") != identity.scene_sha256:
            raise DamagedPart("from another scene")
        start, stop = identity.chunk(index)
        if (meta.get("chunk_size"), meta.get("n_total")) != (identity.chunk_size,
                                                            identity.n_total):
            raise DamagedPart("from a run with another chunk size")
        if (meta.get("chunk"), meta.get("start"), meta.get("stop")) != (index, start, stop):
            raise DamagedPart(f"holds chunk {meta.get('chunk')}'s data")
        if any(k not in arrays for k in ORBIT_ARRAYS) or \
                any(arrays[k].shape != (stop - start,) for k in ("label", "status", "period")):
            raise DamagedPart("incomplete arrays")
        orbits = _orbits_of({k: arrays.pop(k) for k in ORBIT_ARRAYS})
        arrays["orbits"] = orbits
        return arrays, meta

    def drop_chunk(self, index: int) -> None:
        with contextlib.suppress(OSError):
            (self.parts / PART.format(index)).unlink()

    def stored_chunk_size(self, scene_sha256: str) -> int | None:
        """The chunk size recorded by the first readable part of this scene (None if
        none): how to resume when the header is lost."""
        for index in sorted(self.done()):
            try:
                with np.load(self.parts / PART.format(index), allow_pickle=False) as data:
                    meta = json.loads(data["meta"].tobytes().decode())
                size = meta.get("chunk_size")
                if meta.get("scene_sha256") == scene_sha256 and isinstance(size, int) \
                        and size > 0:
                    return size
            except Exception:  # damaged parts are sorted out by verify
                continue
        return None

    def verify(self, identity: RunIdentity) -> tuple[dict[int, dict], dict[int, str]]:
        """Check every chunk file: ({index: meta} of the good ones, {index: reason} of
        the bad ones, which are deleted). Files beyond the plan count as bad."""
        good, bad = {}, {}
        for index in sorted(self.done()):
            try:
                if index >= identity.n_chunks:
                    raise DamagedPart("beyond this run's chunks")
                _, meta = self.read_chunk(index, identity)
                good[index] = meta
            except DamagedPart as why:
                bad[index] = str(why)
                self.drop_chunk(index)
        if self.parts.is_dir():
            for tmp in self.parts.glob("*.tmp"):  # a write cut short by a kill
                with contextlib.suppress(OSError):
                    tmp.unlink()
        return good, bad

    # ------------------------------------------------------------ the end
    def finish(self, result: xr.Dataset) -> Path:
        """Atomically replace the header with the complete result; drop the parts."""
        write_result(result, self.path)
        self.remove_parts()
        return self.path

    def remove_parts(self) -> None:
        shutil.rmtree(self.parts, ignore_errors=True)

    def remove(self) -> None:
        if self.path.exists():
            self.path.unlink()
        self.remove_parts()
