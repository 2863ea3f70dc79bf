"""Will a result fit? Its estimated size against free memory and disk space, checked
before anything is computed (a sweep's plan, a trajectory), so that a full disk is said
in one line at the start instead of after the computation.

Estimates are upper bounds (results are stored compressed); :func:`free_bytes` is the one
place that asks the file system (tests replace it to simulate a full disk).
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from .reader import ConfigError

OVERHEAD_BYTES = 1 << 20  # catalogue, label tables, scene text, attributes, HDF5 headers
MEMORY_COPIES = 3  # a result in memory: the dataset, its file image, a transposed copy


def free_bytes(folder: Path) -> int:
    """Free bytes on the file system of ``folder`` (OSError when it cannot be told)."""
    return shutil.disk_usage(folder).free


def physical_memory() -> int:
    """This machine's physical memory in bytes."""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


def size_text(n: float) -> str:
    """``1.0 MiB``, ``15.3 GiB``."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if n < 1024:
            return f"{n:.1f} {unit}"
        n /= 1024
    return f"{n:.1f} PiB"


def check_memory(need: int, where: str, advice: str) -> None:
    """ConfigError when a result of ``need`` bytes would not fit in memory while it is
    assembled (MEMORY_COPIES of it). ``where``: the file and keys that set its size (the
    message starts with it); ``advice``: what to reduce."""
    memory = physical_memory()
    if MEMORY_COPIES * need > memory:
        raise ConfigError(f"{where}: the result needs at most "
                          f"{size_text(MEMORY_COPIES * need)} of memory while assembled, and "
                          f"this machine has {size_text(memory)}; {advice}")


def check_disk(out: Path, need: int, copies: int = 1, while_written: str = "") -> None:
    """ConfigError when ``copies`` x ``need`` bytes do not fit on the file system that
    will hold ``out`` (its nearest existing folder). ``while_written`` says what the
    copies are (e.g. "chunk files and the final file")."""
    out = Path(out)
    folder = out.parent if str(out.parent) else Path(".")
    while not folder.exists():
        folder = folder.parent
    try:
        free = free_bytes(folder)
    except OSError as exc:
        raise ConfigError(f"{out}: cannot tell the free disk space in {folder}: "
                          f"{exc.strerror or exc.__class__.__name__}") from None
    if copies * need > free:
        what = f" while written ({while_written})" if while_written else ""
        raise ConfigError(f"{out}: not enough disk space: the result needs at most "
                          f"{size_text(copies * need)}{what}, and the file system of "
                          f"{folder} has {size_text(free)} free")
