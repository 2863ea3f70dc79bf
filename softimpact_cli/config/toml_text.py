"""A scene given as a Python mapping, written as the TOML text it stands for.

The API's ``load_scene(dict)`` validates a mapping by writing it as TOML and reading that
text with the scene reader, so a mapping and the TOML file it mirrors give the same Scene
(the same text, hash and result attributes) and the same one-line errors. This module
only writes; every check of the values stays in the reader. What TOML cannot hold (None,
a set, an object) is a ConfigError naming the section and key.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from numbers import Integral, Real
from typing import Any

from .reader import ConfigError

BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _key(key: Any, where: str, source: str) -> str:
    if not isinstance(key, str):
        raise ConfigError(f"{source}: {where}: keys must be strings, got {key!r}")
    return key if BARE_KEY.fullmatch(key) else _string(key)


def _string(text: str) -> str:
    """A TOML basic string: quotes, backslashes and control characters escaped."""
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _value(value: Any, where: str, source: str) -> str:
    """``value`` as a TOML value (tables inline); ``where`` names it in messages."""
    if isinstance(value, bool):  # before Integral: bool is an int
        return "true" if value else "false"
    if isinstance(value, Integral):
        return str(int(value))
    if isinstance(value, Real):
        x = float(value)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, Mapping):
        items = [f"{_key(k, where, source)} = {_value(v, f'{where}.{k}', source)}"
                 for k, v in value.items()]
        return "{" + ", ".join(items) + "}"
    if isinstance(value, list | tuple) or (hasattr(value, "tolist") and
                                          hasattr(value, "ndim")):  # numpy arrays
        values = value.tolist() if hasattr(value, "tolist") else value
        if not isinstance(values, list):  # a 0-d array
            return _value(values, where, source)
        return "[" + ", ".join(_value(v, where, source) for v in values) + "]"
    raise ConfigError(f"{source}: {where}: not a TOML value (a number, string, boolean, list "
                      f"or table), got {value!r}")


def toml_text(doc: Mapping[str, Any], source: str = "<dict>") -> str:
    """The TOML text of a scene mapping: ``{"system": {"model": "duffing"}, ...}`` becomes
    ``[system]`` / ``model = "duffing"``. A top-level value that is not a table is written
    before the tables, so that the reader rejects it as it rejects it in a file."""
    if not isinstance(doc, Mapping):
        raise ConfigError(f"{source}: a scene is a mapping of sections, got "
                          f"{type(doc).__name__}")
    head, tables = [], []
    for name, section in doc.items():
        key = _key(name, "scene", source)
        if not isinstance(section, Mapping):
            head.append(f"{key} = {_value(section, f'[{name}]', source)}")
            continue
        tables.append(f"[{key}]")
        for k, v in section.items():
            tables.append(f"{_key(k, f'[{name}]', source)} = "
                          f"{_value(v, f'[{name}] {k}', source)}")
        tables.append("")
    return "\n".join(head + ([""] if head else []) + tables)
