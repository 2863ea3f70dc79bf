"""``plot.<kind>(ds, ax=...)``: every kind draws on the caller's Axes, sequence of Axes,
Figure or SubFigure and returns the top-level Figure; the drawing is the one of its own
figure; the backend is never touched and pyplot never imported."""

import os
import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

import softimpact_cli as si
from softimpact_cli import plot

from .test_basins_figure import basins
from .test_bifurcation_figure import followed_pair
from .test_map_figure import count_map
from .test_stability_dcrit_figures import dcrit_result, stability_sweep
from .test_trajectory_figure import trajectory

ROOT = Path(__file__).parents[2]


@pytest.fixture(scope="module")
def catalogue():
    return si.run({"system": {"model": "duffing"}, "coupling": {"phi": 0.0},
                   "analysis": {"kind": "catalogue", "grid": 4, "random": 20, "seed": 1}})


def content(ax) -> tuple[int, int, int, int]:
    """What a panel holds: lines, images, collections, texts."""
    return len(ax.lines), len(ax.images), len(ax.collections), len(ax.texts)


# kind -> (dataset builder, number of panels)
CASES = {
    "trajectory": (lambda: trajectory(-3.5, 0), 6),
    "basins": (lambda: basins(), 2),
    "stability": (stability_sweep, 1),
    "dcrit": (dcrit_result, 3),
    "bifurcation": (followed_pair, 2),
    "map": (lambda: count_map(predicted=1), 3),
}


def own_panels(fig) -> list:
    """The panels of a figure drawn by a kind (without colour-bar axes)."""
    return [a for a in fig.axes if a.axison and a.get_label() != "<colorbar>"]


def check_every_target(draw, ds, n: int) -> None:
    own = draw(ds)
    assert isinstance(own, Figure)
    expected = [content(a) for a in own_panels(own)][:n]
    # a sequence of Axes: drawn in order, the same artists as in the kind's own figure
    fig = Figure()
    axes = fig.subplots(1, n, squeeze=False)
    assert draw(ds, ax=axes) is fig
    assert [content(a) for a in axes.ravel()][: len(expected)] == expected
    # a SubFigure: the kind's layout inside it; the Figure it belongs to is returned
    fig = Figure()
    left, right = fig.subfigures(1, 2)
    left.subplots()
    assert draw(ds, ax=right) is fig
    assert len(left.axes) == 1 and len(right.axes) >= n
    assert [content(a) for a in own_panels(right)][:n] == expected
    # a Figure
    fig = Figure()
    assert draw(ds, ax=fig) is fig and len(fig.axes) >= n
    # the wrong number of Axes says how many
    with pytest.raises(ValueError, match=f"this figure has {n} panel"):
        draw(ds, ax=Figure().subplots(1, n + 1))


@pytest.mark.parametrize("kind", CASES)
def test_each_kind_draws_on_given_axes(kind):
    build, n = CASES[kind]
    check_every_target(getattr(plot, kind), build(), n)


def test_a_one_panel_figure_draws_on_one_axes():
    fig = Figure()
    ax = fig.subplots()
    assert plot.basins(basins(phis=(0.0,)), ax=ax) is fig
    # on the caller's Axes: that panel's parameters in one line (issue 31.12), not the
    # description a figure of its own carries
    assert len(fig.axes) == 1 and ax.images and ax.get_title() == r"$d = 9$, $\varphi = 0$"
    fig, ax = Figure(), None
    ax = fig.subplots()
    assert plot.stability(stability_sweep(), ax=ax) is fig and ax.lines
    with pytest.raises(ValueError, match="this figure has 2 panels"):
        plot.basins(basins(), ax=Figure().subplots())


def test_catalogue_on_axes(catalogue):
    n = 1 + catalogue.sizes["combination"]
    check_every_target(plot.catalogue, catalogue, n)


@pytest.mark.slow
def test_design_on_axes():
    ds = si.run(ROOT / "configs" / "design_duffing.toml", quick=True, workers=2)
    check_every_target(plot.design, ds, 4)


def test_a_result_of_another_kind_is_refused():
    with pytest.raises(ValueError, match="holds a 'trajectory' result, not a map result"):
        plot.map(trajectory(-3.5, 0))
    with pytest.raises(ValueError, match="needs a sweep over a plane"):
        plot.basins(stability_sweep())
    with pytest.raises(ValueError, match="combination: 'X' is not one of"):
        plot.dcrit(dcrit_result(), combination="X")


def test_every_kind_has_its_function():
    from softimpact_cli.kinds import ANALYSIS_KINDS

    assert set(plot.KINDS) == set(ANALYSIS_KINDS)
    assert all(callable(getattr(plot, kind)) for kind in plot.KINDS)


def test_basins_on_axes_keeps_the_backend_and_never_calls_use(monkeypatch):
    """The acceptance line: ``si.plot.basins(ds, ax=ax)`` returns a Figure without
    changing ``matplotlib.get_backend()``."""
    before = matplotlib.get_backend()

    def refuse(*args, **kwargs):
        raise AssertionError("matplotlib.use called")

    monkeypatch.setattr(matplotlib, "use", refuse)
    fig = Figure()
    ax = fig.subplots()
    assert isinstance(si.plot.basins(basins(phis=(0.0,)), ax=ax), Figure)
    assert matplotlib.get_backend() == before


def test_a_notebook_backend_survives_drawing_and_pyplot_stays_unloaded(tmp_path):
    """In a fresh process with a backend chosen by the user (MPLBACKEND, as Jupyter's
    inline backend is), drawing every figure and saving one changes nothing."""
    code = f"""
import sys, matplotlib
before = matplotlib.get_backend()
def refuse(*a, **k):
    raise AssertionError("matplotlib.use called")
matplotlib.use = refuse
sys.path.insert(0, {str(ROOT)!r})
from matplotlib.figure import Figure
import softimpact_cli as si
from tests.plot.test_basins_figure import basins
ax = Figure().subplots()
fig = si.plot.basins(basins(phis=(0.0,)), ax=ax)
fig.savefig({str(tmp_path / 'b.png')!r})
si.plot.basins(basins())
assert matplotlib.get_backend() == before == "svg", (before, matplotlib.get_backend())
assert "matplotlib.pyplot" not in sys.modules
"""
    env = {**os.environ, "MPLBACKEND": "svg"}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=tmp_path)
    assert (tmp_path / "b.png").stat().st_size > 0


def test_place_panels_rejects_what_is_not_axes():
    with pytest.raises(ValueError, match="this figure has 2 panels"):
        plot.place_panels(["a", "b"], (1, 2), [(0, 0), (0, 1)], None)
    fig, panels = plot.place_panels(None, (2, 2), [(0, 0), (1, 1)], (4, 4))
    assert [p.axison for p in fig.axes] == [True, False, False, True]
    assert np.array_equal([p.get_subplotspec().rowspan.start for p in panels], [0, 1])


@pytest.mark.parametrize("kind, ds", [
    ("trajectory", trajectory(-3.5, 0)),
    ("basins", basins(phis=(0.0, 1.0), scene_text="# synthetic", complete=1)),
])
def test_the_cli_saves_the_figure_the_api_draws(kind, ds, tmp_path):
    from click.testing import CliRunner

    from softimpact_cli.cli import main
    from softimpact_cli.store import write_result

    result = write_result(ds, tmp_path / "r.h5")
    run = CliRunner().invoke(main, ["plot", kind, str(result), "-o", str(tmp_path / "cli.png"),
                                    "--dpi", "40"])
    assert run.exit_code == 0, run.output
    mine = plot.save(getattr(si.plot, kind)(si.open_result(result)), tmp_path / "api.png", 40)
    assert mine.read_bytes() == (tmp_path / "cli.png").read_bytes()
