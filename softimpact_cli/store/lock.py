"""One writer per result file: an advisory lock held for the whole run.

The lock is ``fcntl.flock`` on a sibling file ``RESULT.h5.lock`` that holds the holder's
pid and command (for the refusal message). The kernel drops a flock when its process
dies, so a lock file left behind by a killed run never blocks the next one.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
from collections.abc import Iterator
from pathlib import Path

from ..config import ConfigError

_held: dict[Path, int] = {}  # resolved result path -> lock file descriptor (this process)


def lock_path(path: str | os.PathLike) -> Path:
    """The lock file guarding the result at ``path``."""
    path = Path(path)
    return path.with_name(path.name + ".lock")


def _key(path: str | os.PathLike) -> Path:
    return Path(os.path.abspath(path))


def held(path: str | os.PathLike) -> bool:
    """Whether this process holds the lock on ``path``."""
    return _key(path) in _held


def _holder(lock: Path) -> str:
    try:
        text = lock.read_text(errors="replace").strip()
    except OSError:
        return "another process"
    pid, _, command = text.partition(" ")
    if not pid.isdigit():
        return "another process"
    return f"process {pid}" + (f" ({command})" if command else "")


def acquire(path: str | os.PathLike, command: str) -> None:
    """Take the lock on ``path`` for this process, or raise ConfigError naming the holder."""
    key = _key(path)
    if key in _held:
        return
    lock = lock_path(key)
    while True:
        try:
            lock.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise ConfigError(f"{path}: cannot create the lock file {lock} "
                              f"({exc.strerror or exc.__class__.__name__})") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise ConfigError(f"{path}: in use by {_holder(lock)}; wait for it to end "
                              "(or stop it) and run again") from None
        # the holder before us may have removed the file after we opened it: then our
        # lock is on an orphan inode and a third process could lock a new file; retry
        try:
            same = os.stat(lock).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    try:
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()} {command}\n".encode(errors="replace"))
    except OSError:
        pass  # the lock holds without its note (e.g. a full disk)
    _held[key] = fd


def release(path: str | os.PathLike) -> None:
    """Drop this process's lock on ``path`` (and its lock file); no-op if not held."""
    key = _key(path)
    fd = _held.pop(key, None)
    if fd is None:
        return
    with contextlib.suppress(OSError):
        os.unlink(lock_path(key))  # while still locked: nobody else holds this inode
    os.close(fd)


@contextlib.contextmanager
def output_lock(path: str | os.PathLike, command: str) -> Iterator[None]:
    """Hold the lock on ``path`` for the ``with`` block (re-entrant within a process)."""
    if held(path):
        yield
        return
    acquire(path, command)
    try:
        yield
    finally:
        release(path)
