"""A kind is its own files plus one registry line.

The toy kind below is three new files outside the package (its kind module with reader,
plan, run, info and compare hooks, example scene and help line; its analysis module; its
figure) and one line in ``kinds.REGISTRY``. Every command that lists or handles kinds
must pick it up: ``example``, ``sweep --help``, ``sweep``, ``info`` (text and JSON),
``plot`` and ``compare``.
"""

import json
import re
import textwrap

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.kinds import REGISTRY

KIND = '''
"""[analysis] kind = "toy": the forcing frequency times a scale."""

from dataclasses import dataclass

from softimpact_cli.config.reader import positive
from softimpact_cli.kinds.base import AnalysisKind, PlotOption, PlotSpec

from .analysis import scaled_frequency

EXAMPLE = """\\
# a toy kind: the forcing frequency times a scale
[system]
model = "duffing"
[analysis]
kind = "toy"
scale = 2.0
"""


@dataclass(frozen=True)
class ToyAnalysis:
    kind: str
    scale: float = 1.0


def read(sec, ctx):
    return ToyAnalysis("toy", sec.number("scale", 1.0, positive))


def plan(scene, workers=None, chunk_size=None):
    return f"toy: scale the frequency by {scene.analysis.scale:g}"


def run(scene, progress=None, **_):
    return scaled_frequency(float(scene.values["w"]), scene.analysis.scale)


def compare(a, b, name_a, name_b):
    return {"omega_change": float(b["omega"]) - float(a["omega"])}


def compare_text(report, max_points):
    return [f"omega changed by {report['omega_change']:+.3f}"]


KINDS = (AnalysisKind(
    "toy", "the forcing frequency times a scale (a toy)", read, plan, run=run,
    summary=lambda ds: {"omega": float(ds["omega"])},
    info_lines=lambda ds: [f"toy omega: {float(ds['omega']):.3f}"],
    compare=compare, compare_text=compare_text, example=EXAMPLE,
    plot=PlotSpec("The toy's frequency as a point.", draw="toykind.figure:draw",
                  options=(PlotOption("--marker", "marker", "A marker.", kind="choice",
                                      choices=("o", "x")),))),)
'''

ANALYSIS = '''
import xarray as xr


def scaled_frequency(w, scale):
    return xr.Dataset({"omega": ((), scale * w)}, attrs={"analysis": "toy",
                                                         "outcome": "done"})
'''

FIGURE = '''
from softimpact_cli.plot import new_figure


def draw(ds, ax=None, marker="o"):
    fig = new_figure() if ax is None else ax.figure
    (fig.add_subplot() if ax is None else ax).plot([0.0], [float(ds["omega"])], marker)
    return fig
'''


@pytest.fixture
def toy(tmp_path, monkeypatch):
    """The toy kind's files in a package of its own, and its registry line."""
    package = tmp_path / "toykind"
    package.mkdir()
    for name, text in (("__init__", ""), ("kind", KIND), ("analysis", ANALYSIS),
                       ("figure", FIGURE)):
        (package / f"{name}.py").write_text(textwrap.dedent(text))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setitem(REGISTRY, "toy", "toykind.kind")
    return tmp_path


def test_a_kind_in_its_own_files_is_picked_up_by_every_command(toy):
    cli = CliRunner()
    listed = cli.invoke(main, ["example"])
    assert listed.exit_code == 0 and "toy" in listed.output
    example = cli.invoke(main, ["example", "toy"])
    assert example.exit_code == 0 and 'kind = "toy"' in example.output
    helped = cli.invoke(main, ["sweep", "--help"]).output
    assert re.search(r"\n +toy +the forcing frequency times a scale \(a toy\)\n", helped)
    assert "continuation" in helped  # every kind, one line each

    scene = toy / "toy.toml"
    scene.write_text(example.output)
    a, b = toy / "a.h5", toy / "b.h5"
    for out, scale in ((a, "2.0"), (b, "3.0")):
        scene.write_text(example.output.replace("2.0", scale))
        ran = cli.invoke(main, ["sweep", str(scene), "-o", str(out)])
        assert ran.exit_code == 0, ran.output
    info = cli.invoke(main, ["info", str(a)])
    assert info.exit_code == 0 and "toy omega: 2.600" in info.output
    data = json.loads(cli.invoke(main, ["info", str(a), "--json"]).output)
    assert data["analysis"] == "toy" and data["omega"] == pytest.approx(2.6)
    plot = cli.invoke(main, ["plot", "toy", str(a), "-o", str(toy / "toy.png"),
                             "--marker", "x"])
    assert plot.exit_code == 0, plot.output
    assert (toy / "toy.png").stat().st_size > 1000
    compared = cli.invoke(main, ["compare", str(a), str(b)])
    assert compared.exit_code == 0, compared.output
    assert "omega changed by +1.300" in compared.output
    as_json = json.loads(cli.invoke(main, ["compare", str(a), str(b), "--json"]).output)
    assert as_json["omega_change"] == pytest.approx(1.3)


def test_the_commands_list_every_registered_kind(toy):
    """`sweep --help` and `example` list the registry, in its order, one line each."""
    helped = CliRunner().invoke(main, ["sweep", "--help"]).output.splitlines()
    lines = [line.split()[0] for line in helped if line.startswith("    ") and
             line.split() and line.split()[0] in REGISTRY]
    assert lines == list(REGISTRY)
    listed = CliRunner().invoke(main, ["example"]).output
    assert listed.startswith("kinds: " + ", ".join(REGISTRY))
