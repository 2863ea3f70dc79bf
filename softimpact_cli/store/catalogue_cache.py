"""A cache on disk of catalogue searches, so that a repeated sweep of the same system does
not search its attractors again.

An entry is one ``.npz`` file per key under :func:`cache_folder`: plain arrays (no pickle)
plus a ``meta`` record holding the full key material and a SHA-256 over it and every
array. The key is a SHA-256 of the key material, a JSON-able record of everything the
cached result depends on (the caller builds it: parameters, settings, initial states,
a hash of the sources that compute it). On loading, the file's key material must equal
the caller's and its checksum must match; anything else (a damaged, truncated, foreign or
tampered file, a hash collision) counts as a miss, and the recomputed entry replaces it.
Entries are written to a temporary file and renamed, so no reader ever sees half an entry.
The cache is best effort: a folder that cannot be written only means no entry is kept.

Where: ``$SOFTIMPACT_CACHE_DIR``, else ``$XDG_CACHE_HOME/softimpact`` or
``~/.cache/softimpact``, subfolder ``catalogues/``. Off when ``$SOFTIMPACT_NO_CACHE`` is
set to anything but ``""`` or ``"0"`` (``softimpact sweep --no-cache`` sets it).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import tempfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .checksum import payload_digest

FORMAT = 1  # of an entry's layout; a change makes every older entry a miss
DIR_VARIABLE = "SOFTIMPACT_CACHE_DIR"
OFF_VARIABLE = "SOFTIMPACT_NO_CACHE"
SUFFIX = ".npz"
KEY_SHOWN = 12  # hex digits of the key named in "cache <key>"


def cache_folder() -> Path:
    """The folder of the catalogue entries (not created here)."""
    base = os.environ.get(DIR_VARIABLE) or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "softimpact")
    return Path(base) / "catalogues"


def enabled() -> bool:
    """Whether the cache is used (``$SOFTIMPACT_NO_CACHE`` unset, empty or "0")."""
    return os.environ.get(OFF_VARIABLE, "") in ("", "0")


@contextlib.contextmanager
def switched_off() -> Iterator[None]:
    """The cache off (``$SOFTIMPACT_NO_CACHE=1``, seen by worker processes too) inside;
    the variable's previous state restored afterwards."""
    previous = os.environ.get(OFF_VARIABLE)
    os.environ[OFF_VARIABLE] = "1"
    try:
        yield
    finally:
        if previous is None:
            os.environ.pop(OFF_VARIABLE, None)
        else:
            os.environ[OFF_VARIABLE] = previous


def entry_key(material: dict) -> str:
    """64 hex digits of SHA-256 over the key material (JSON, sorted keys)."""
    return hashlib.sha256(json.dumps(material, sort_keys=True).encode()).hexdigest()


def entry_path(key: str) -> Path:
    return cache_folder() / f"{key}{SUFFIX}"


def load(material: dict) -> dict[str, np.ndarray] | None:
    """The arrays stored under ``material``, or None (no entry, or one that does not
    verify: unreadable, another key material, or a checksum that does not match)."""
    try:
        with np.load(entry_path(entry_key(material)), allow_pickle=False) as data:
            arrays = {k: data[k] for k in data.files}
        meta = json.loads(arrays.pop("meta").tobytes().decode())
    except Exception:  # missing, truncated, not a zip, bad JSON...: a miss
        return None
    body = {"format": FORMAT, "material": material}
    as_stored = json.loads(json.dumps(body))  # tuples become lists, as in the file
    if not isinstance(meta, dict) or {k: meta.get(k) for k in body} != as_stored:
        return None
    return arrays if meta.get("checksum") == payload_digest(body, arrays) else None


def save(material: dict, arrays: dict[str, np.ndarray]) -> Path | None:
    """Store ``arrays`` under ``material`` atomically; the entry's path, or None when the
    folder cannot be written (the cache is then skipped, never an error)."""
    arrays = {k: np.asarray(v) for k, v in arrays.items()}
    body = {"format": FORMAT, "material": material}
    meta = {**body, "checksum": payload_digest(body, arrays)}
    arrays["meta"] = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    final = entry_path(entry_key(material))
    try:
        final.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{final.stem[:16]}-", suffix=".tmp",
                                   dir=final.parent)
    except OSError:
        return None
    try:
        with os.fdopen(fd, "wb") as fh:
            np.savez(fh, **arrays)
        os.replace(tmp, final)
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        return None
    return final


def cached(material: dict, compute: Callable[[], dict[str, np.ndarray]]
           ) -> tuple[dict[str, np.ndarray], str]:
    """(arrays, source): the entry of ``material`` when one verifies (source ``"cache
    <key prefix>"``), else ``compute()``, stored for next time (source ``"computed"``).
    With the cache off, always computed and nothing read or written."""
    if not enabled():
        return compute(), "computed (cache off)"
    arrays = load(material)
    if arrays is not None:
        return arrays, f"cache {entry_key(material)[:KEY_SHOWN]}"
    arrays = compute()
    save(material, arrays)
    return arrays, "computed"


@dataclass(frozen=True)
class CacheInfo:
    """What the cache holds: its folder, entries and their total size (bytes)."""

    location: Path
    entries: int
    size: int
    enabled: bool

    def describe(self) -> str:
        state = "" if self.enabled else f" (off: ${OFF_VARIABLE} is set)"
        return (f"catalogue cache: {self.location}{state}\n"
                f"entries: {self.entries}\nsize: {self.size / 1024:.1f} KiB")


def _entries() -> list[Path]:
    folder = cache_folder()
    return sorted(folder.glob(f"*{SUFFIX}")) if folder.is_dir() else []


def info() -> CacheInfo:
    """The cache's folder, number of entries and size."""
    entries = _entries()
    size = sum(p.stat().st_size for p in entries if p.exists())
    return CacheInfo(cache_folder(), len(entries), size, enabled())


def clear() -> int:
    """Remove every entry (and temporary files left by killed writers); the number of
    entries removed."""
    folder = cache_folder()
    removed = 0
    for path in _entries():
        with contextlib.suppress(FileNotFoundError):
            path.unlink()
            removed += 1
    for tmp in folder.glob(".*.tmp") if folder.is_dir() else ():
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
    return removed
