"""The scene form of a chain: ``[system] model = "chain"``, ``[[kink]]`` and ``[[stop]]``.

```toml
[system]
model = "chain"
bodies = 3                  # 1..8
m = 1.0                     # per-body keys: one number (every body) or a list of one per body
c = 0.05
k1 = 1.0                    # restoring force k1 x + k2 x^3 (+ k_xp x^p: k_x2, k_x4 .. k_x9)
k2 = 0.01
F = 1.0
phi = [0.0, "5*pi/8", "5*pi/4"]
w = 1.3                     # one forcing frequency

[[kink]]                    # a one-sided spring: force k (x - x_k) while engaged
body = 1
side = "left"               # engaged while x_1 <= x (left) or x_1 >= x (right)
x = -1.26
k = 29.0

[[stop]]
between = [1, 2]            # in contact while x_1 - x_2 >= d
d = 2.0
law = "paper"               # paper | no-tension | hunt-crossley (its exponent) | rigid (r)
k_c = 8.0
c_c = 10.0

[[stop]]
body = 3                    # a wall: in contact while x_3 >= wall (right) or <= wall (left)
wall = 2.5
side = "right"
```

Every problem is one line naming the table and key, before anything runs.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..systems import STOP_KEYS, STOP_LAWS, System
from ..systems.chain import (
    BODY_KEYS,
    EXTRA_POWERS,
    MAX_BODIES,
    SIDES,
    ChainModel,
    Kink,
    Stop,
    chain_system,
    chain_values,
)
from .expressions import parse_multiple
from .limits import parameter_problem
from .reader import ConfigError, Section

CHAIN = "chain"
TABLES = ("stop", "kink")  # the arrays of tables only a chain has

POWER_KEYS = tuple(f"k_x{p}" for p in EXTRA_POWERS)
SYSTEM_KEYS = ("model", "bodies", "w") + BODY_KEYS + POWER_KEYS
# what each per-body key allows (the parameters' own checks say it again)
BODY_MINIMUM = {"m": (0.0, True), "c": (0.0, False), "F": (0.0, False)}


def read_chain(source: str, doc: Mapping[str, Any]) -> tuple[System, dict[str, Any]]:
    """The chain of a scene and its parameter values by name (``systems.chain``)."""
    sec = Section(source, "system", doc.get("system", {}))
    sec.raw("model")
    bodies_raw = sec.raw("bodies", 2)
    if isinstance(bodies_raw, bool) or not isinstance(bodies_raw, int) \
            or not 1 <= bodies_raw <= MAX_BODIES:
        raise sec.fail("bodies", f"must be a whole number in 1..{MAX_BODIES}, got "
                                 f"{bodies_raw!r}")
    n = bodies_raw
    w = sec.number("w", 1.3, lambda v: None if v > 0 else "must be > 0")
    problem = parameter_problem("w", w)
    if problem:
        raise sec.fail("w", f"{problem}, got {w!r}")
    per_body = {key: _per_body(sec, key, n) for key in BODY_KEYS + POWER_KEYS
                if sec.has(key)}
    sec.finish(SYSTEM_KEYS)
    powers = tuple(p for p in EXTRA_POWERS if f"k_x{p}" in per_body)
    kinks, kink_values = _read_kinks(source, doc, n)
    stops, stop_values = _read_stops(source, doc, n)
    model = ChainModel(n, powers, tuple(kinks), tuple(stops))
    problems = model.problems()
    if problems:
        raise ConfigError(f"{source}: {problems[0]}")
    values = chain_values(model, w, per_body, kink_values, stop_values)
    problems = model.value_problems(values)
    if problems:
        raise ConfigError(f"{source}: [[kink]]: {problems[0]}")
    return chain_system(model), values


def _per_body(sec: Section, key: str, n: int) -> list[float]:
    """One number or a list of ``n`` (numbers, or multiples of pi for ``phi``)."""
    raw = sec.raw(key)
    items = raw if isinstance(raw, list) else [raw] * n
    if isinstance(raw, list) and len(raw) != n:
        raise sec.fail(key, f"has {len(raw)} values for {n} bodies; give one number or a "
                            f"list of {n}")
    out = []
    for item in items:
        try:
            value = parse_multiple(item, "pi", math.pi) if key == "phi" else _number(item)
        except ValueError as exc:
            raise sec.fail(key, str(exc)) from None
        low, strict = BODY_MINIMUM.get(key, (-math.inf, False))
        if value < low or (strict and value == low):
            raise sec.fail(key, f"must be {'>' if strict else '>='} {low:g}, got {item!r}")
        problem = parameter_problem(key, value)
        if problem:
            raise sec.fail(key, f"{problem}, got {item!r}")
        out.append(value)
    return out


def _number(item: Any) -> float:
    if isinstance(item, bool) or not isinstance(item, int | float) \
            or not math.isfinite(float(item)):
        raise ValueError(f"must be a finite number, got {item!r}")
    return float(item)


class _Table(Section):
    """One table of an array (``[[stop]]``): its keys are recorded under the array's name
    (the key reference), its errors name the table by number (``[stop 2] d: ...``)."""

    def __init__(self, source: str, name: str, number: int, table: Mapping[str, Any]):
        super().__init__(source, name, table)
        self.index = number

    def fail(self, key: str | None, problem: str) -> ConfigError:
        where = f"[{self.name} {self.index}]" + (f" {key}" if key else "")
        return ConfigError(f"{self.source}: {where}: {problem}")


def _tables(source: str, doc: Mapping[str, Any], name: str) -> list[Section]:
    given = doc.get(name, [])
    if not isinstance(given, list) or not all(isinstance(t, dict) for t in given):
        raise ConfigError(f"{source}: [{name}]: must be an array of tables ([[{name}]])")
    return [_Table(source, name, i, t) for i, t in enumerate(given, 1)]


def _body(sec: Section, key: str, n: int) -> int:
    value = sec.raw(key)
    if isinstance(value, bool) or not isinstance(value, int):
        raise sec.fail(key, f"must name a body, a whole number in 1..{n}, got {value!r}")
    if not 1 <= value <= n:
        raise sec.fail(key, f"body {value} does not exist; bodies 1..{n}")
    return value


def _side(sec: Section) -> str:
    if not sec.has("side"):
        raise sec.fail("side", "is required: \"left\" or \"right\"")
    return sec.choice("side", None, tuple(SIDES))


def _read_kinks(source: str, doc: Mapping[str, Any], n: int):
    kinks, values = [], []
    for sec in _tables(source, doc, "kink"):
        body = _body(sec, "body", n)
        kinks.append(Kink(body, _side(sec)))
        values.append({"x": sec.number("x", None),
                       "k": sec.number("k", None, lambda v: None if v >= 0 else "must be >= 0")})
        sec.finish(("body", "side", "x", "k"))
    return kinks, values


def _read_stops(source: str, doc: Mapping[str, Any], n: int):
    stops, values = [], []
    non_negative = (lambda v: None if v >= 0 else "must be >= 0")  # noqa: E731
    for sec in _tables(source, doc, "stop"):
        law = STOP_LAWS[sec.choice("law", "paper", tuple(STOP_LAWS))]
        if sec.has("between"):
            pair = sec.raw("between")
            if not isinstance(pair, list) or len(pair) != 2:
                raise sec.fail("between", f"must be two bodies [i, j], got {pair!r}")
            for b in pair:
                if isinstance(b, bool) or not isinstance(b, int) or not 1 <= b <= n:
                    raise sec.fail("between", f"body {b!r} does not exist; bodies 1..{n}")
            if pair[0] == pair[1]:
                raise sec.fail("between", f"a stop between body {pair[0]} and itself")
            for key in ("wall", "side", "body"):
                if sec.has(key):
                    raise sec.fail(key, "only for a wall stop (body, wall, side); this stop "
                                        "is between two bodies")
            stop = Stop(pair[0], pair[1], law=law.name)
            value = {"d": sec.number("d", None)}
        elif sec.has("body") or sec.has("wall"):
            body = _body(sec, "body", n)
            if sec.has("d"):
                raise sec.fail("d", "a wall stop has no gap: its wall is the position "
                                    "where contact begins")
            wall = sec.number("wall", None)
            stop = Stop(body, 0, _side(sec), law.name)
            value = {"wall": wall}
        else:
            raise sec.fail(None, "needs between = [i, j] (two bodies) or body, wall, side "
                                 "(a wall)")
        if law.soft:
            value["k_c"] = sec.number("k_c", 8.0, non_negative)
            value["c_c"] = sec.number("c_c", 10.0, non_negative)
        else:
            for key in ("k_c", "c_c"):
                if sec.has(key):
                    raise sec.fail(key, f"not a key of law {law.name!r} (a rigid stop has no "
                                        "stiffness or damping: its restitution is r)")
        for key in STOP_KEYS.values():  # a law's own keys (exponent, r)
            if key in law.keys:
                value[key.name] = sec.number(key.name, key.default, key.check)
            elif sec.has(key.name):
                raise sec.fail(key.name, f"not a key of law {law.name!r}")
        sec.finish(("between", "body", "wall", "side", "d", "law", "k_c", "c_c")
                   + tuple(STOP_KEYS))
        stops.append(stop)
        values.append(value)
    return stops, values
