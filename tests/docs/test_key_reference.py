"""The scene-key reference is the reader's own schema: every key any scene (the examples,
configs/) makes the reader read has a meaning, types and defaults are those the reader
checks, and a key added to a reader shows up (and fails the test until described)."""

import dataclasses
import importlib
from pathlib import Path

import pytest

from softimpact_cli.config.examples import EXAMPLES, example
from softimpact_cli.config.reader import recording
from softimpact_cli.config.scene import SECTIONS, IntegratorSettings
from softimpact_cli.kinds import KINDS, REGISTRY
from softimpact_cli.kinds import key_reference as ref
from softimpact_cli.kinds.scene import parse_scene

ROOT = Path(__file__).parents[2]
CONFIG_SCENES = sorted((ROOT / "configs").rglob("*.toml"))


def all_scenes():
    scenes = [(kind, example(kind)) for kind in EXAMPLES]
    scenes += [(str(p.relative_to(ROOT)), p.read_text()) for p in CONFIG_SCENES]
    return scenes


def test_every_key_of_every_scene_has_a_meaning():
    entries = ref.read_schema(all_scenes())
    assert len(entries) > 100
    assert ref.undocumented(entries) == []


def test_every_kind_has_an_example_in_the_reference():
    entries = ref.read_schema()
    assert {kd for (s, kd, _) in entries if s == "analysis"} == set(KINDS)


def _replace_kind(monkeypatch, kind) -> None:
    """The registry reads a kind off its module's KINDS tuple: replace it there."""
    module = importlib.import_module(f"softimpact_cli.kinds.{REGISTRY[kind.name]}")
    monkeypatch.setattr(module, "KINDS", tuple(kind if k.name == kind.name else k
                                               for k in module.KINDS))


def test_a_key_without_a_meaning_is_reported(monkeypatch):
    kind = KINDS["fatal_shock"]
    keys = dict(kind.keys)
    del keys["scan"]
    _replace_kind(monkeypatch, dataclasses.replace(kind, keys=keys))
    assert ref.undocumented() == ["[analysis] scan (kind 'fatal_shock')"]


def test_a_key_a_reader_starts_to_read_appears_undescribed(monkeypatch):
    kind = KINDS["trajectory"]

    def read(sec, ctx):
        sec.integer("new_budget", 7, 1, 9)
        return kind.read(sec, ctx)

    _replace_kind(monkeypatch, dataclasses.replace(kind, read=read))
    entry = ref.read_schema()[("analysis", "trajectory", "new_budget")]
    assert entry.traits == {"type": "integer", "default": 7, "allowed": "1 .. 9"}
    assert "[analysis] new_budget (kind 'trajectory')" in ref.undocumented()


def test_defaults_and_ranges_are_the_readers():
    page = ref.scene_key_reference()
    for section in SECTIONS:
        assert f"## [{section}]" in page
    for field in dataclasses.fields(IntegratorSettings):
        default = ref._cell(field.default)
        assert f"| `{field.name}` | " in page and default in page, field.name
    assert "| `rtol` | number | `1e-08` | in [1e-14, 1) |" in page
    assert "| `steps_per_period` | integer | `1440` | 4 .. 1000000 |" in page
    assert "| `exponent` | number | `1.5` | in [1, 10] |" in page
    assert "bilinear: `0.518`, duffing: `1`" in page  # F, per model from the registry


def test_recording_is_off_outside_its_block():
    with recording() as record:
        parse_scene(example("trajectory"))
    size = len(record)
    parse_scene(example("basins"))
    assert len(record) == size > 20


@pytest.mark.parametrize("kind", list(KINDS))
def test_each_kind_table_lists_only_its_own_keys(kind):
    entries = ref.read_schema()
    own = {k for (s, kd, k) in entries if s == "analysis" and kd == kind}
    assert own <= set(KINDS[kind].keys) | {"kind"}
