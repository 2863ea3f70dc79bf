"""Reading TOML tables with messages that name the file, the section and the key."""

from __future__ import annotations

import difflib
import math
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from ..expressions import parse_multiple


class ConfigError(ValueError):
    """A user error in a scene or on the command line; the message is one line."""


# ---------------------------------------------------------------- small checkers


class Section:
    """Reads keys of one TOML table, tracking which ones were used."""

    def __init__(self, source: str, name: str, table: Mapping[str, Any]):
        self.source = source
        self.name = name
        self.table = dict(table)
        self.used: set[str] = set()

    def fail(self, key: str | None, problem: str) -> ConfigError:
        where = f"[{self.name}]" + (f" {key}" if key else "")
        return ConfigError(f"{self.source}: {where}: {problem}")

    def has(self, key: str) -> bool:
        return key in self.table

    def raw(self, key: str, default: Any = None) -> Any:
        self.used.add(key)
        return self.table.get(key, default)

    def number(self, key: str, default: float | None, check: Callable[[float], str | None]
               | None = None) -> float:
        value = self.raw(key, default)
        if value is None:
            raise self.fail(key, "is required (a number)")
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(key, f"must be a number, got {value!r}")
        value = float(value)
        if not math.isfinite(value):
            raise self.fail(key, f"must be a finite number, got {value!r}")
        if check is not None:
            problem = check(value)
            if problem:
                raise self.fail(key, f"{problem}, got {value!r}")
        return value

    def integer(self, key: str, default: int, minimum: int, maximum: int | None = None) -> int:
        value = self.raw(key, default)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(key, f"must be a whole number, got {value!r}")
        if value < minimum or (maximum is not None and value > maximum):
            allowed = f">= {minimum}" if maximum is None else f"in {minimum}..{maximum}"
            raise self.fail(key, f"must be {allowed}, got {value!r}")
        return value

    def choice(self, key: str, default: str, allowed: tuple[str, ...]) -> str:
        value = self.raw(key, default)
        if value not in allowed:
            hint = did_you_mean(str(value), allowed)
            raise self.fail(key, f"must be one of {', '.join(map(repr, allowed))}, got "
                                 f"{value!r}{hint}")
        return value

    def boolean(self, key: str, default: bool) -> bool:
        value = self.raw(key, default)
        if not isinstance(value, bool):
            raise self.fail(key, f"must be true or false, got {value!r}")
        return value

    def multiple(self, key: str, default: float, symbol: str, unit: float) -> float:
        value = self.raw(key, default)
        try:
            return parse_multiple(value, symbol, unit)
        except ValueError as exc:
            raise self.fail(key, str(exc)) from None

    def finish(self, allowed: tuple[str, ...] | None = None) -> None:
        unknown = sorted(set(self.table) - self.used)
        if unknown:
            key = unknown[0]
            pool = allowed if allowed is not None else tuple(sorted(self.used))
            hint = did_you_mean(key, pool)
            raise self.fail(key, f"unknown key{hint}; allowed: {', '.join(sorted(pool))}")


def did_you_mean(word: str, options) -> str:
    close = difflib.get_close_matches(word, list(options), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def positive(value: float) -> str | None:
    return None if value > 0 else "must be > 0"



def check_writable(path: Path, source: str, key: str = "[output] path") -> None:
    """Refuse an output path that cannot be written, before any work is done."""
    if path.is_dir():
        raise ConfigError(f"{source}: {key}: {str(path)!r} is a directory, not a file")
    parent = path.parent if str(path.parent) else Path(".")
    probe = parent
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir() or not os.access(probe, os.W_OK | os.X_OK):
        raise ConfigError(f"{source}: {key}: cannot write {str(path)!r} "
                          f"({str(probe)!r} is not a writable directory)")
    if path.exists() and not os.access(path, os.W_OK):
        raise ConfigError(f"{source}: {key}: cannot write {str(path)!r} (not writable)")
