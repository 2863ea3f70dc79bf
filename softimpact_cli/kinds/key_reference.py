"""The scene-key reference, generated from the scene reader itself.

Every scene of ``softimpact example KIND`` (and a few variants reaching the reader's other
branches) is parsed while ``config.reader.recording()`` is on: each key a ``Section`` reads
leaves its type, default and allowed values, each key a section's ``finish`` allows its
name. The meanings are data beside the readers: the model parameters' descriptions in the
systems registry, the other sections' in ``config.key_docs``, each kind's ``[analysis]``
keys in its ``AnalysisKind.keys``. The documentation site renders ``scene_key_reference()``
at build time (docs/hooks.py); ``undocumented()`` lists the keys without a meaning (a test
keeps it empty).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..config import key_docs
from ..config.examples import CHAIN_EXAMPLE, EXAMPLES, example
from ..config.reader import recording
from ..config.scene import SECTIONS
from ..systems import LAW_KEYS, MODELS, get_system
from ..systems.base import SUPPORTED_BODIES
from . import KINDS
from .scene import parse_scene

# Variants of the examples that reach the reader's other branches: (kind, old, new).
VARIANTS = (
    ("trajectory", 'law = "paper"', 'law = "hunt-crossley"\nexponent = 1.5'),
    ("stability", "t0 = 0.0 ", 't0 = "random" '),
    ("design", "screen_n = ", "robust_n = 40\nscreen_n = "),
)
# a chain's design: the keys only a chain's design reads
CHAIN_DESIGN = """\
[system]
model = "chain"
bodies = 2
phi = [0.0, "pi"]
[[stop]]
between = [1, 2]
d = 5.0
[analysis]
kind = "design"
target = "L1^1 R1-0^1"
bounds = {"stop.1.d" = [1.0, 10.0], "phi.2" = ["pi/2", "pi"]}
grid_points = 12
[initial_conditions]
kind = "random"
n = 100
box = {x1 = [-4, 4], v1 = [-4, 4], x2 = [-4, 4], v2 = [-4, 4]}
[catalogue]
grid = 4
"""
LIST_SCENE = """\
[system]
model = "duffing"
[analysis]
kind = "stability"
[initial_conditions]
kind = "list"
states = [[1.0, 0.0, -1.0, 0.0]]
t0 = "T/4"
"""


@dataclass
class KeyEntry:
    """One key of one section as the reader reads it."""

    section: str
    key: str
    traits: dict[str, Any] = field(default_factory=dict)
    kinds: set[str] = field(default_factory=set)


def _scenes() -> list[tuple[str, str]]:
    scenes = [(kind, example(kind)) for kind in EXAMPLES]
    for kind, old, new in VARIANTS:
        if old is not None and kind in EXAMPLES and old in EXAMPLES[kind]:
            scenes.append((kind, example(kind).replace(old, new, 1)))
    scenes.append(("stability", LIST_SCENE))
    chain = CHAIN_EXAMPLE.replace('law = "paper" ', 'law = "hunt-crossley"\nexponent = 1.5 ', 1)
    scenes.append(("trajectory", chain))  # the chain's [system] keys, [[stop]], [[kink]]
    scenes.append(("design", CHAIN_DESIGN))  # a chain's design keys (grid_points)
    return scenes


def read_schema(scenes: list[tuple[str, str]] | None = None
                ) -> dict[tuple[str, str, str], KeyEntry]:
    """{(section, kind or "", key): KeyEntry} over ``scenes`` (default: every example and
    its variants). ``[analysis]`` keys are per kind; the other sections' are shared, with
    the kinds that read them."""
    entries: dict[tuple[str, str, str], KeyEntry] = {}
    for name, text in scenes if scenes is not None else _scenes():
        with recording() as record:
            scene = parse_scene(text, f"<example {name}>")
        kind = scene.analysis.kind
        for (section, key), traits in record.items():
            where = kind if section == "analysis" else ""
            entry = entries.setdefault((section, where, key), KeyEntry(section, key))
            if section == "grid" and key != "panels":
                entry.traits["type"] = 'number, list, {start, stop, num} or {start, stop, step}'

            for trait, value in traits.items():
                entry.traits.setdefault(trait, value)
            if section == "coupling" and key in LAW_KEYS:  # its range is on the law key
                law_key = LAW_KEYS[key]
                entry.traits["allowed"] = f"in [{law_key.low:g}, {law_key.high:g}]"
            entry.kinds.add(kind)
    return entries


def _parameter(name: str):
    """The model parameter ``name`` of any model and body count, or None."""
    for model in MODELS:
        for bodies in SUPPORTED_BODIES:
            for param in get_system(model, bodies).parameters:
                if param.name == name:
                    return param
    return None


def meaning(section: str, kind: str, key: str) -> str | None:
    """What a key means, from the data beside its reader (None: undocumented)."""
    if section == "analysis":
        if key == "kind":
            return key_docs.KEYS["analysis"]["kind"]
        return KINDS[kind].keys.get(key)
    if section in ("system", "coupling") and key in LAW_KEYS:
        return LAW_KEYS[key].description
    if section == "grid" and key not in key_docs.KEYS["grid"]:
        param = _parameter(key)
        described = LAW_KEYS[key].description if key in LAW_KEYS else (
            None if param is None else param.description)
        return None if described is None else f"swept: {described}"
    if section in ("system", "coupling") and key not in key_docs.KEYS.get(section, {}):
        param = _parameter(key)
        return None if param is None else param.description
    return key_docs.KEYS.get(section, {}).get(key)


def undocumented(entries=None) -> list[str]:
    """"[section] key" (with the kind for [analysis]) of every key without a meaning."""
    entries = read_schema() if entries is None else entries
    return [f"[{section}] {key}" + (f" (kind {kind!r})" if kind else "")
            for (section, kind, key) in sorted(entries) if not meaning(section, kind, key)]


def _cell(value: Any) -> str:
    if value is None:
        return "—"
    if isinstance(value, float):
        text = f"{value:g}" if math.isfinite(value) else str(value)
    elif isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = f'"{value}"'
    else:
        text = str(value).replace("'", '"')
    return "`" + text.replace("|", "\\|") + "`"


def _text(value: str | None) -> str:
    return "—" if not value else value.replace("|", "\\|")


def _parameter_range(param) -> str:
    if param.minimum == -math.inf:
        return "any finite number"
    return f"{'>' if param.strict else '>='} {param.minimum:g}"


def _system_rows(section: str) -> list[str]:
    """[system] or [coupling] rows straight from the models registry: per-model defaults."""
    rows = []
    names: dict[str, dict[str, Any]] = {}
    for model in MODELS:
        for bodies in SUPPORTED_BODIES:
            for p in get_system(model, bodies).parameters:
                pair_key = p.name in ("d", "phi", "k_c", "c_c")
                if (section == "coupling") != pair_key:
                    continue
                names.setdefault(p.name, {"param": p, "defaults": {}})["defaults"][model] = \
                    p.default
    for name, info in names.items():
        p = info["param"]
        defaults = ", ".join(f"{m}: {_cell(v)}" for m, v in info["defaults"].items())
        kind = 'number or "a*pi/b"' if name == "phi" else "number"
        rows.append(f"| `{name}` | {kind} | {defaults} | {_parameter_range(p)} | "
                    f"{_text(p.description)}{'' if p.unit == '1' else f' ({p.unit})'} |")
    return rows


def scene_key_reference() -> str:
    """The reference page (Markdown): every section and key with its type, default,
    allowed values, meaning and the kinds it applies to."""
    entries = read_schema()
    lines = ["# Scene keys", "",
             "Every section and key a scene may hold, generated from the scene reader "
             "itself when this site is built (`softimpact_cli/kinds/key_reference.py`): "
             "types, defaults and allowed values are what the reader checks, meanings are "
             "the data beside each reader. A key not given takes its default; an unknown "
             "section or key is an error naming it. `softimpact example KIND` prints a "
             "minimal scene of each kind.", ""]
    header = ["| key | type | default | allowed | meaning |", "| --- | --- | --- | --- | --- |"]
    for section in SECTIONS:
        lines += [f"## [{section}]", "", key_docs.SECTIONS[section], ""]
        if section == "analysis":
            kind_key = next(e for (s, _, k), e in entries.items() if (s, k) == ("analysis", "kind"))
            lines += header + [_row(kind_key, meaning("analysis", "", "kind")), ""]
            for kind in KINDS:
                keys = [k for (s, kd, k) in entries  # in the order the reader reads them
                        if s == "analysis" and kd == kind and k != "kind"]
                lines += [f"### kind = \"{kind}\"", "", KINDS[kind].description + ".", ""]
                if not keys:
                    lines += ["No keys besides `kind`.", ""]
                    continue
                lines += header
                for key in keys:
                    e = entries[("analysis", kind, key)]
                    lines.append(_row(e, meaning("analysis", kind, key)))
                lines.append("")
            continue
        shared = [k for (s, kd, k) in entries if s == section]  # the reader's order
        rows = []
        if section in ("system", "coupling"):
            rows = _system_rows(section)
            listed = {r.split("`")[1] for r in rows}
            shared = [k for k in shared if k not in listed]
        for key in shared:
            e = entries[(section, "", key)]
            rows.append(_row(e, meaning(section, "", key), kinds=True))
        kinds = sorted({kd for (s, _, k), e in entries.items() if s == section
                        for kd in e.kinds}, key=list(KINDS).index)
        if section not in ("system", "coupling", "integrator", "output"):
            lines += [f"Read by the kinds: {', '.join(f'`{k}`' for k in kinds)}.", ""]
        lines += header + rows + [""]
    return "\n".join(lines)


def _row(entry: KeyEntry, text: str | None, kinds: bool = False) -> str:
    t = entry.traits
    kind = {"value": "TOML value"}.get(t.get("type"), t.get("type"))
    return (f"| `{entry.key}` | {kind or '—'} | {_cell(t.get('default'))} | "
            f"{_text(t.get('allowed'))} | {_text(text)} |")
