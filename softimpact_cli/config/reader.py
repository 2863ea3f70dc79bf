"""Reading TOML tables with messages that name the file, the section and the key."""

from __future__ import annotations

import contextlib
import difflib
import math
import os
import tempfile
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from .expressions import parse_multiple

MAX_PROBLEM_CHARS = 300  # longest problem text of one message


class ConfigError(ValueError):
    """A user error in a scene or on the command line; the message is one line."""


# ---------------------------------------------------------------- small checkers


# What the reader reads, recorded while ``recording()`` is active: the scene-key reference
# (softimpact_cli.kinds.key_reference) is generated from it, so the documentation is the
# reader's own schema. {(section, key): {"type", "default", "allowed"}}; off (None) in use.
_RECORDED: dict[tuple[str, str], dict[str, Any]] | None = None


@contextlib.contextmanager
def recording():
    """Record every key a Section reads (its type, default and allowed values) and every
    key its ``finish`` allows, in the dict this yields; nested calls share one record."""
    global _RECORDED
    outer = _RECORDED
    if outer is None:
        _RECORDED = {}
    try:
        yield _RECORDED
    finally:
        if outer is None:
            _RECORDED = None


class Section:
    """Reads keys of one TOML table, tracking which ones were used."""

    def __init__(self, source: str, name: str, table: Mapping[str, Any]):
        self.source = source
        self.name = name
        self.table = dict(table)
        self.used: set[str] = set()

    def _note(self, key: str, weak: bool = False, **traits: Any) -> None:
        """Record ``key``'s traits (type, default, allowed) while ``recording()``; weak
        traits (what ``raw`` knows) do not replace those a typed reader recorded."""
        if _RECORDED is not None:
            entry = _RECORDED.setdefault((self.name, key), {})
            for name, value in traits.items():
                if not (weak and name in entry):
                    entry[name] = value

    def fail(self, key: str | None, problem: str) -> ConfigError:
        where = f"[{self.name}]" + (f" {key}" if key else "")
        if len(problem) > MAX_PROBLEM_CHARS:  # a huge value quoted back stays readable
            problem = problem[:MAX_PROBLEM_CHARS] + "..."
        return ConfigError(f"{self.source}: {where}: {problem}")

    def has(self, key: str) -> bool:
        return key in self.table

    def raw(self, key: str, default: Any = None) -> Any:
        self._note(key, weak=True, type="value", default=default)
        self.used.add(key)
        return self.table.get(key, default)

    def number(self, key: str, default: float | None, check: Callable[[float], str | None]
               | None = None) -> float:
        self._note(key, type="number", default=default,
                   allowed=check_text(check))
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
        self._note(key, type="integer", default=default,
                   allowed=f">= {minimum}" if maximum is None else f"{minimum} .. {maximum}")
        value = self.raw(key, default)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(key, f"must be a whole number, got {value!r}")
        if value < minimum or (maximum is not None and value > maximum):
            allowed = f">= {minimum}" if maximum is None else f"in {minimum}..{maximum}"
            raise self.fail(key, f"must be {allowed}, got {value!r}")
        return value

    def choice(self, key: str, default: str, allowed: tuple[str, ...]) -> str:
        self._note(key, type="choice", default=default,
                   allowed=" | ".join(map(repr, allowed)))
        value = self.raw(key, default)
        if value not in allowed:
            hint = did_you_mean(str(value), allowed)
            raise self.fail(key, f"must be one of {', '.join(map(repr, allowed))}, got "
                                 f"{value!r}{hint}")
        return value

    def boolean(self, key: str, default: bool) -> bool:
        self._note(key, type="boolean", default=default, allowed="true | false")
        value = self.raw(key, default)
        if not isinstance(value, bool):
            raise self.fail(key, f"must be true or false, got {value!r}")
        return value

    def multiple(self, key: str, default: float, symbol: str, unit: float) -> float:
        self._note(key, type=f'number or "a*{symbol}/b"', default=default)
        value = self.raw(key, default)
        try:
            return parse_multiple(value, symbol, unit)
        except ValueError as exc:
            raise self.fail(key, str(exc)) from None

    def finish(self, allowed: tuple[str, ...] | None = None) -> None:
        for key in allowed or ():
            self._note(key)
        unknown = sorted(set(self.table) - self.used)
        if unknown:
            key = unknown[0]
            pool = allowed if allowed is not None else tuple(sorted(self.used))
            hint = did_you_mean(key, pool)
            raise self.fail(key, f"unknown key{hint}; allowed: {', '.join(sorted(pool))}")


def check_text(check: Callable | None) -> str | None:
    """What a number check allows, as its own message says ("must be > 0" -> "> 0"): the
    "must be ..." texts among the check function's constants (None when it has none)."""
    code = getattr(check, "__code__", None)
    texts = [c for c in (code.co_consts if code else ()) if isinstance(c, str)
             and c.startswith("must be ") and c.count("[") + c.count("(")
             == c.count("]") + c.count(")")]  # whole texts, not an f-string's pieces
    return "; ".join(c.removeprefix("must be ") for c in texts) or None


def did_you_mean(word: str, options) -> str:
    close = difflib.get_close_matches(word, list(options), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def positive(value: float) -> str | None:
    return None if value > 0 else "must be > 0"



# A result's sidecar files add suffixes to its name (RESULT.h5.parts, temporary and lock
# files); 255 bytes is the usual file-system limit of one name.
MAX_NAME_BYTES = 224


def output_path(value: str, stem: str) -> Path:
    """The result file named by ``value`` (an [output] path or ``-o``).

    A value ending in "/" names a directory: the result is ``<value>/<stem>.h5`` there
    (``stem``: the scene file's stem). A NUL character or an empty value is refused.
    """
    if not value:
        raise ValueError("is empty; give a file path such as results/x.h5")
    if "\0" in value:
        raise ValueError(f"{value!r} contains a NUL character")
    if value.endswith(("/", os.sep)):
        return Path(value) / f"{stem}.h5"
    return Path(value)


def _reason(exc: OSError) -> str:
    return exc.strerror or exc.__class__.__name__


def check_writable(path: str | os.PathLike, source: str, key: str = "[output] path") -> None:
    """Refuse an output path that cannot be written, before any work is done.

    A real probe, not ``os.access`` (which says yes to root everywhere, /proc included):
    the missing parent directories are created and the file itself (or, when it exists, a
    temporary file beside it) is created and removed again; everything the probe created
    is removed. The message is one line naming the path and the system's reason.
    """
    text = os.fspath(path)
    where = f"{source}: {key}"
    try:
        output_path(text, "x")
    except ValueError as exc:
        raise ConfigError(f"{where}: {exc}") from None
    if text.endswith(("/", os.sep)):
        raise ConfigError(f"{where}: {text!r} ends with '/' (a directory); give a file name")
    target = Path(text)
    try:
        for part in target.parts:
            if len(os.fsencode(part)) > MAX_NAME_BYTES:
                raise ConfigError(f"{where}: the name {part[:40]!r}... is "
                                  f"{len(os.fsencode(part))} bytes; at most {MAX_NAME_BYTES} "
                                  "(room for the suffixes of the files written beside it)")
    except UnicodeEncodeError:
        raise ConfigError(f"{where}: {text!r} cannot be encoded as a file name") from None
    try:
        if target.is_dir():
            raise ConfigError(f"{where}: {text} is a directory, not a file")
        if target.exists() and not target.is_file():
            raise ConfigError(f"{where}: {text} exists and is not a regular file")
        _probe(target, where)
    except OSError as exc:  # stat of an unreachable path (ELOOP, EACCES, ...)
        raise ConfigError(f"{where}: cannot write {text}: {_reason(exc)}") from None


def _probe(target: Path, where: str) -> None:
    """Create what writing ``target`` would create, then remove it again."""
    parent = target.parent
    missing = []
    while not parent.exists() and parent != parent.parent:
        missing.append(parent)
        parent = parent.parent
    if not parent.is_dir():
        raise ConfigError(f"{where}: cannot write {target}: {parent} is not a directory")
    created: list[Path] = []
    try:
        for folder in reversed(missing):
            try:
                os.mkdir(folder)
            except OSError as exc:
                raise ConfigError(f"{where}: cannot create directory {folder}: "
                                  f"{_reason(exc)}") from None
            created.append(folder)
        if target.exists():
            try:
                with open(target, "r+b"):
                    pass
            except OSError as exc:
                raise ConfigError(f"{where}: cannot write {target}: {_reason(exc)}") from None
            probe = None
            try:
                fd, probe = tempfile.mkstemp(prefix=".softimpact-probe-", dir=target.parent)
                os.close(fd)
            except OSError as exc:
                raise ConfigError(f"{where}: cannot write in {target.parent} (to replace "
                                  f"{target.name}): {_reason(exc)}") from None
            finally:
                if probe is not None:
                    os.unlink(probe)
        else:
            try:
                os.close(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644))
            except OSError as exc:
                raise ConfigError(f"{where}: cannot create {target}: {_reason(exc)}") from None
            os.unlink(target)
    finally:
        for folder in reversed(created):
            try:
                os.rmdir(folder)
            except OSError:
                pass
