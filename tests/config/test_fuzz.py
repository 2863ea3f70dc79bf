"""Fuzz the scene reader (issue 20, items 14 and 19).

Every shipped scene (configs/*.toml, configs/figures/*.toml) is mutated deterministically:
every key and section deleted, every value replaced by wrong types, zero, negatives, NaN,
infinities, huge numbers and unicode, arrays emptied or lengthened, pairs reversed, phase and
start-time strings like "1e308*pi" or "pi/0", duplicate keys, deep nesting. Each case must
end in a clean ConfigError (one line, naming the file and a key or section on the mutated
path) or in a scene whose every count and size is in bounds and whose sweep plan and size
checks run (nothing is integrated).
"""

from __future__ import annotations

import json
import math
import re
import signal
import tomllib
from contextlib import contextmanager
from pathlib import Path

import pytest

from softimpact_cli.config import ConfigError, check_writable
from softimpact_cli.config.limits import (
    MAX_GRID_VALUES,
    MAX_INITIAL_CONDITIONS,
    MAX_PARAMETER,
    MAX_TRAJECTORIES,
    MAX_TRAJECTORY_SAMPLES,
)
from softimpact_cli.kinds import SWEEP_KINDS
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.plan import Plan, default_chunk_size

ROOT = Path(__file__).parents[2]
CONFIGS = sorted(ROOT.glob("configs/*.toml")) + sorted(ROOT.glob("configs/figures/*.toml"))

WRONG_VALUES = [
    ("string", "abc"), ("bool", True), ("array", [1, 2]), ("table", {"a": 1}), ("zero", 0),
    ("negative", -1), ("negative float", -0.5), ("nan", math.nan), ("inf", math.inf),
    ("-inf", -math.inf), ("1e308", 1e308), ("-1e308", -1e308), ("2**63", 2**63),
    ("10**30", 10**30), ("10**400", 10**400), ("-2**63-1", -2**63 - 1),
    ("2**63-1", 2**63 - 1), ("empty array", []), ("unicode", "φ→∞ ü\u200b"),
    ("nested", [[[[[[[[[[1]]]]]]]]]]), ("1e9", 1_000_000_000), ("2**32", 2**32),
]
EXPRESSIONS = ["1e308*pi", "pi/0", "--pi", "nan*pi", "inf*pi", "1e400", "pi/1e-320",
               "1e-320*pi", "-0*pi", "T/0", "1e308*T", "1e20", "nan", "", " ", "pi pi",
               "2**63", "ϕ", "1e308*pi/1e-308", "-T", "1e7*T", "0.5*T/1e-300"]
SYMBOLIC_KEYS = {"phi", "t0", "start", "stop", "step"}


# ---------------------------------------------------------------- a small TOML writer


def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else
                                              "-inf" if v == -math.inf else repr(v))
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def dumps(doc: dict) -> str:
    lines = [f"{_key(k)} = {_value(v)}" for k, v in doc.items() if not isinstance(v, dict)]
    for name, table in doc.items():
        if isinstance(table, dict):
            lines.append(f"[{_key(name)}]")
            lines.extend(f"{_key(k)} = {_value(v)}" for k, v in table.items())
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- mutations


def paths(node, prefix=()):
    """Every key path (dict keys and list indices) below ``node``."""
    items = node.items() if isinstance(node, dict) else enumerate(node)
    for k, v in items:
        yield (*prefix, k)
        if isinstance(v, dict | list):
            yield from paths(v, (*prefix, k))


def _copy(doc):
    return json.loads(json.dumps(doc, allow_nan=True))


def _parent(doc, path):
    node = doc
    for k in path[:-1]:
        node = node[k]
    return node


def _get(doc, path):
    return _parent(doc, path)[path[-1]]


def _set(doc, path, value):
    doc = _copy(doc)
    _parent(doc, path)[path[-1]] = value
    return doc


def _delete(doc, path):
    doc = _copy(doc)
    parent = _parent(doc, path)
    del parent[path[-1]]
    return doc


def mutations(text: str):
    """(description, path, scene text) of every mutation of one scene."""
    doc = tomllib.loads(text)
    for path in paths(doc):
        name = ".".join(map(str, path))
        yield f"delete {name}", path, dumps(_delete(doc, path))
        for what, value in WRONG_VALUES:
            yield f"{name} = {what}", path, dumps(_set(doc, path, value))
        old = _get(doc, path)
        if path[-1] in SYMBOLIC_KEYS or (len(path) > 1 and path[-2] in SYMBOLIC_KEYS):
            for expr in EXPRESSIONS:
                yield f"{name} = {expr!r}", path, dumps(_set(doc, path, expr))
        if isinstance(old, list) and old:
            yield f"{name} longer", path, dumps(_set(doc, path, old + old[-1:]))
            yield f"{name} shorter", path, dumps(_set(doc, path, old[:-1]))
            if len(old) == 2 and all(isinstance(v, int | float) for v in old):
                yield f"{name} lo > hi", path, dumps(_set(doc, path, old[::-1]))
        if isinstance(old, dict) and {"start", "stop"} <= set(old):
            swapped = {**old, "start": old["stop"], "stop": old["start"]}
            yield f"{name} start > stop", path, dumps(_set(doc, path, swapped))
    # text-level cases: duplicate keys and tables, deep nesting, unicode section names
    first = next(iter(doc["system"]))
    yield "duplicate key", ("system",), text.replace("[system]", f"[system]\n{first} = 1", 1)
    yield "duplicate table", ("system",), text + "\n[system]\nmodel = \"duffing\"\n"
    yield "unknown section", ("ßystem",), text + "\n[ßystem]\nx = 1\n"
    for depth in (20, 3000, 100_000):
        yield f"array nested {depth}", ("system",), \
            text.replace("[system]", "[system]\nx = " + "[" * depth + "]" * depth, 1)
        yield f"table nested {depth}", ("system",), \
            text.replace("[system]", "[system]\nx = " + "{a = " * depth + "1" + "}" * depth, 1)
    yield "dotted table 500", ("system",), text + "\n[" + ".".join(["t"] * 500) + "]\n"


# ---------------------------------------------------------------- checks


class Hang(Exception):
    pass


@contextmanager
def no_hang(seconds: int):
    """Turn a case that runs for ``seconds`` into a failure instead of a stuck suite."""
    def alarm(signum, frame):
        raise Hang()

    old = signal.signal(signal.SIGALRM, alarm)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def check_success(scene, tmp_path: Path) -> None:
    """A scene that parsed: every number finite and bounded, every count in bounds, and the
    checks a sweep makes before it computes run cleanly."""
    for key, v in scene.values.items():
        if key != "law":
            assert math.isfinite(v) and abs(v) <= MAX_PARAMETER, (key, v)
    a = scene.analysis
    if a.kind == "trajectory":
        assert a.periods * a.samples_per_period <= MAX_TRAJECTORY_SAMPLES
    if scene.grid is not None:
        assert scene.grid.size <= MAX_GRID_VALUES
        assert all(math.isfinite(v) for vs in scene.grid.axes.values() for v in vs)
    if scene.initial_conditions is not None:
        assert scene.initial_conditions.count <= MAX_INITIAL_CONDITIONS
    if a.kind in SWEEP_KINDS:
        n_total = scene.grid.size * scene.initial_conditions.count
        assert n_total <= MAX_TRAJECTORIES
        plan = Plan(scene, default_chunk_size(n_total, 2))
        assert plan.result_bytes > plan.n_total * 28
        plan.describe()
        try:
            plan.check_resources(tmp_path / "x.h5", scene.source)
        except ConfigError as exc:
            assert "\n" not in str(exc)
    out = scene.output if not scene.output.is_absolute() else tmp_path / "x.h5"
    try:
        check_writable(tmp_path / out, scene.source)
    except ConfigError as exc:
        assert "\n" not in str(exc)


def check_error(exc: ConfigError, source: str, path: tuple) -> None:
    msg = str(exc)
    assert "\n" not in msg and len(msg) < 700, msg
    assert msg.startswith(f"{source}: "), msg
    # names the section (and key) at fault: the mutated one, or one its change makes
    # inconsistent (deleting [system] bodies makes [initial_conditions] axes wrong); the
    # TOML reader's own errors give the line, and nesting too deep for it has no place
    rest = msg[len(source) + 2:]
    assert re.match(r"(invalid TOML: |\[[A-Za-z_ß/\[\]]+\]|tables or arrays nested too "
                    r"deeply)", rest), msg


@pytest.mark.parametrize("config", CONFIGS, ids=[p.name for p in CONFIGS])
def test_mutated_scenes_fail_cleanly_or_stay_in_bounds(config, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    source = config.name
    failures = []
    for what, path, text in mutations(config.read_text()):
        try:
            with no_hang(30):
                try:
                    scene = parse_scene(text, source)
                except ConfigError as exc:
                    check_error(exc, source, path)
                else:
                    check_success(scene, tmp_path)
        except (AssertionError, Exception) as exc:  # collect every bad case, report all
            failures.append(f"{what}: {exc.__class__.__name__}: {str(exc)[:300]}")
    assert not failures, f"{len(failures)} bad cases:\n" + "\n".join(failures[:40])


def test_corpus_is_large():
    assert sum(1 for c in CONFIGS for _ in mutations(c.read_text())) >= 300
    assert len(CONFIGS) >= 20  # every shipped scene, figures included
