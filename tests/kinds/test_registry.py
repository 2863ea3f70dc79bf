"""The analysis-kind registry: every kind has one home, the CLI, config, run, check and
info dispatch through it, and a new kind is one module (here: one registry entry)."""

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.config.examples import example as example_scene
from softimpact_cli.kinds import (
    ANALYSIS_KINDS,
    KINDS,
    REGISTRY,
    SWEEP_KINDS,
    AnalysisKind,
    get,
)
from softimpact_cli.kinds.check import check_scene
from softimpact_cli.kinds.results import describe
from softimpact_cli.kinds.run import plan_text, run_scene
from softimpact_cli.kinds.scene import parse_scene


def test_every_kind_declares_a_figure_and_the_plot_commands_follow_the_registry():
    from softimpact_cli import plot

    assert all(kind.plot is not None for kind in KINDS.values())
    for name, kind in KINDS.items():
        assert callable(kind.figure_function())
        assert getattr(plot, name) is not None  # the API's si.plot.<kind>
    out = CliRunner().invoke(main, ["plot", "--help"]).output
    assert all(f"  {name} " in out for name in KINDS)


def test_every_kind_has_a_home_and_sweeps_are_those_without_a_run():
    assert set(ANALYSIS_KINDS) == {"trajectory", "catalogue", "basins", "stability", "dcrit",
                                   "bifurcation", "map", "tipping", "fatal_shock", "design",
                                   "fractality", "lyapunov", "continuation", "atlas"}
    assert SWEEP_KINDS == ("basins", "stability", "map", "tipping")
    for name, kind in KINDS.items():
        assert kind.name == name and kind.description and callable(kind.read)
        assert kind.sweep == (kind.run is None)
        assert kind.__class__ is AnalysisKind
    with pytest.raises(ConfigError, match="analysis kind 'orbit': unknown; one of trajectory"):
        get("orbit")


@pytest.mark.parametrize("name", ANALYSIS_KINDS)
def test_every_kind_reads_its_example_and_plans_it(name):
    scene = parse_scene(example_scene(name), f"{name}.toml")
    assert scene.analysis.kind == name
    plan = plan_text(scene)
    assert plan.splitlines()[0].startswith(f"{name}: ")
    assert plan.splitlines()[-1].startswith("output: ")
    # a catalogue section is read exactly by the kinds that need one
    assert (scene.catalogue is not None) == (name in (*SWEEP_KINDS, "dcrit", "bifurcation",
                                                      "continuation", "atlas",
                                                      "fatal_shock", "design", "fractality"))


def test_a_kind_without_a_check_names_those_with_one():
    scene = parse_scene(example_scene("trajectory"), "t.toml")
    with pytest.raises(ValueError, match="check covers the kinds basins, stability, dcrit, "
                                         "bifurcation, map, tipping, not 'trajectory'"):
        check_scene(scene)


def test_a_new_kind_is_one_registry_entry(monkeypatch, tmp_path):
    """Registered, a kind is read, planned, run, written, described and plotted by the
    existing code, with no other change."""
    monkeypatch.setitem(REGISTRY, "toy", "tests.kinds.toy_kind")
    text = ('[system]\nmodel = "duffing"\n[analysis]\nkind = "toy"\nscale = 2.0\n'
            f'[output]\npath = "{tmp_path / "toy.h5"}"\n')
    scene = parse_scene(text, "toy.toml")
    assert plan_text(scene).startswith("toy: scale the frequency")
    ds = run_scene(scene)
    assert float(ds["omega"]) == pytest.approx(2.6) and ds.attrs["scene_sha256"]
    assert describe(ds)["omega"] == pytest.approx(2.6)
    (tmp_path / "toy.toml").write_text(text)
    result = CliRunner().invoke(main, ["sweep", str(tmp_path / "toy.toml")])
    assert result.exit_code == 0, result.output
    assert result.output.startswith("toy: done (") and (tmp_path / "toy.h5").is_file()
    with pytest.raises(ConfigError, match="scale: must be a number"):
        parse_scene(text.replace("2.0", '"two"'), "toy.toml")
    # its figure: `softimpact plot toy` exists, takes the kind's options, refuses others
    plot = CliRunner().invoke(main, ["plot", "toy", str(tmp_path / "toy.h5"), "-o",
                                     str(tmp_path / "toy.png"), "--marker", "x"])
    assert plot.exit_code == 0, plot.output
    assert (tmp_path / "toy.png").stat().st_size > 1000
    assert "toy" in CliRunner().invoke(main, ["plot", "--help"]).output
    wrong = CliRunner().invoke(main, ["plot", "basins", str(tmp_path / "toy.h5"), "-o",
                                      str(tmp_path / "b.png")])
    assert wrong.exit_code == 2 and "holds a 'toy' result" in wrong.output


def test_unregistered_kind_is_refused_with_the_registry_list():
    text = '[system]\nmodel = "duffing"\n[analysis]\nkind = "toy"\n'
    with pytest.raises(ConfigError, match=r"\[analysis\] kind: must be one of 'trajectory', "
                                          r"'catalogue', 'basins'"):
        parse_scene(text, "t.toml")


def test_sweep_kinds_refuse_resume_for_the_others(tmp_path):
    (tmp_path / "t.toml").write_text(example_scene("trajectory"))
    result = CliRunner().invoke(main, ["sweep", str(tmp_path / "t.toml"), "--resume"])
    assert result.exit_code == 2
    assert "--resume is for sweeps (kinds basins, stability, map, tipping); a trajectory reruns " \
           "whole" in result.output


# Kind-specific guards of commands that exist for one kind only (`softimpact design`,
# `design --target`, the design example's header, `info --compare` of a basins result
# with a stability result, `measure` of a basins result); everything else asks the registry.
ALLOWED_KIND_TESTS = {
    "analysis/fractality.py": 1,
    "commands.py": 3,
    "config/examples.py": 1,
}


def test_no_module_outside_the_registry_branches_on_a_kind_name():
    import re
    from pathlib import Path

    import softimpact_cli

    names = "|".join(ANALYSIS_KINDS)
    chain = re.compile(rf"(kind|analysis\"\)|analysis\"\])\s*(==|!=|in)\s*\(?\"({names})\"")
    root = Path(softimpact_cli.__file__).parent
    found = {}
    for path in root.rglob("*.py"):
        rel = path.relative_to(root).as_posix()
        if rel.startswith("kinds/"):
            continue
        hits = len(chain.findall(path.read_text()))
        if hits:
            found[rel] = hits
    assert found == ALLOWED_KIND_TESTS
