"""`softimpact example KIND`: every kind has a scene that parses; the small ones run."""

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.config.examples import EXAMPLES, example
from softimpact_cli.kinds import ANALYSIS_KINDS
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene


def test_every_analysis_kind_has_an_example():
    assert list(EXAMPLES) == list(ANALYSIS_KINDS)


@pytest.mark.parametrize("kind", ANALYSIS_KINDS)
def test_example_parses_as_its_kind_and_is_commented(kind):
    text = CliRunner().invoke(main, ["example", kind]).output
    assert text == example(kind)
    scene = parse_scene(text, f"example {kind}")
    assert scene.analysis.kind == kind
    assert str(scene.output) == f"results/example_{kind}.h5"
    comments = [line for line in text.splitlines() if "#" in line]
    assert len(comments) >= 4  # a newcomer's scene explains its keys


@pytest.mark.parametrize("kind", ["trajectory", "catalogue"])
def test_small_examples_run(kind):
    ds = run_scene(parse_scene(example(kind), f"example {kind}"))
    assert ds.attrs["analysis"] == kind
    if kind == "trajectory":
        assert ds.attrs["outcome"] in ("converged", "unresolved")
    else:  # the Duffing oscillator's two period-1 attractors and the pair's 4 combinations
        assert ds.sizes["attractor"] == 2 and ds.sizes["combination"] == 4


def test_example_without_kind_lists_the_kinds():
    result = CliRunner().invoke(main, ["example"])
    assert result.exit_code == 0
    assert all(kind in result.output for kind in ANALYSIS_KINDS)


def test_unknown_example_kind_is_one_line_and_exit_2():
    result = CliRunner().invoke(main, ["example", "basin"])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and "unknown kind 'basin'" in lines[0] and "basins" in lines[0]
