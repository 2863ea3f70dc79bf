"""Where numba caches this package's compiled kernels: a folder named by a hash of every
kernel and system source file.

numba invalidates a cached function only when its *own* file changes; a kernel that calls
into another module (``dopri5.advance`` calling ``switching.first_exit``) would otherwise
keep running stale code after that module is edited. Keying the folder by all sources
makes any edit start a fresh cache. The folder is ``$NUMBA_CACHE_DIR`` (or
``$XDG_CACHE_HOME``, or ``~/.cache``) ``/softimpact/<hash>``.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

PACKAGE = Path(__file__).parent
SOURCES = ("kernels", "systems")


def source_hash(root: Path = PACKAGE) -> str:
    digest = hashlib.sha256()
    for folder in SOURCES:
        for path in sorted((root / folder).glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def cache_dir(root: Path = PACKAGE) -> str | None:
    base = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "softimpact")
    path = os.path.join(base, source_hash(root))
    try:
        os.makedirs(path, exist_ok=True)
    except OSError:
        return None  # numba then caches next to the sources, as it would by default
    return path if os.access(path, os.W_OK) else None
