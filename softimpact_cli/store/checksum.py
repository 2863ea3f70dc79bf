"""One SHA-256 over a record and named arrays: what the store's files carry to be
verified on reading (sweep chunk parts, catalogue cache entries)."""

from __future__ import annotations

import hashlib
import json

import numpy as np


def payload_digest(record: dict, arrays: dict[str, np.ndarray]) -> str:
    """64 hex digits over ``record`` (JSON, sorted keys) and every array's name, dtype,
    shape and bytes (in name order)."""
    h = hashlib.sha256(json.dumps(record, sort_keys=True).encode())
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    return h.hexdigest()
