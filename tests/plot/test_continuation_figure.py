"""The continuation figure: each branch in its solution's colour (the basin figures'),
named as the basin figures name it, and event labels that do not overlap, however close
the events."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Annotation, Text

import softimpact_cli as si
from softimpact_cli.analysis.labels import latex_of
from softimpact_cli.plot.palette import colour_of


@pytest.fixture(scope="module")
def fold():
    """The single Duffing body's two period-1 orbits in F, --quick (two folds)."""
    scene = Path(__file__).parents[2] / "configs" / "continuation" / "duffing_fold_F.toml"
    return si.run(scene, quick=True)


def test_branches_take_the_catalogues_colours_and_typeset_names(fold):
    order = list(fold.attrs["catalogue_names"])  # a list attribute (analysis.attributes)
    assert order == ["L1^1", "L1^2"]
    fig = si.plot.continuation(fold)
    legend = {t.get_text(): h for t, h in zip(fig.axes[0].get_legend().get_texts(),
                                               fig.axes[0].get_legend().legend_handles,
                                               strict=True)}
    for name in order:
        assert latex_of(name) in legend  # $L^{1}_{1}$, not L1^1
        assert legend[latex_of(name)].get_color() == colour_of(name, order)
    assert colour_of("L1^1", order) != colour_of("L1^2", order)


def crowded(ds: xr.Dataset, copies: int) -> xr.Dataset:
    """``ds`` with each event repeated ``copies`` times at (almost) the same point."""
    events = ds[[v for v in ds.data_vars if "event" in ds[v].dims]]
    jittered = [events.assign(event_parameter=events.event_parameter + 1e-4 * k)
                for k in range(copies)]
    return xr.merge([ds.drop_dims("event"), xr.concat(jittered, "event")])


def test_event_labels_do_not_overlap(fold):
    ds = crowded(fold, 4)
    assert ds.sizes["event"] == 4 * fold.sizes["event"]
    fig = si.plot.continuation(ds)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    for ax in fig.axes[:-1]:
        boxes = [Text.get_window_extent(a, renderer)  # the label, not its leader line
                 for a in ax.texts if isinstance(a, Annotation)]
        assert len(boxes) == ds.sizes["event"]
        for i, a in enumerate(boxes):
            for b in boxes[i + 1:]:
                overlap = (min(a.x1, b.x1) - max(a.x0, b.x0), min(a.y1, b.y1) - max(a.y0, b.y0))
                assert not (overlap[0] > 0.5 and overlap[1] > 0.5), (a, b)
    assert np.isfinite(ds.event_parameter.values).all()


def test_switched_branches_are_typeset_as_their_solution(fold):
    """A branch switched onto at a branch point or a doubling is named after its parent
    (``L1^1 BP1+``): the parent's part typeset as the basin figures typeset it."""
    names = fold["branch_name"].values.astype(object)
    names[0] = f"{names[0]} BP1+"
    fig = si.plot.continuation(fold.assign(branch_name=("branch", names.astype(str))))
    texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert f"{latex_of(str(fold['branch_name'].values[0]))} BP1+" in texts, texts
    assert not any("^" in t and "$" not in t for t in texts), texts


def test_crowded_event_labels_stay_inside_their_axes(fold):
    """Many events at one place (the pitchfork scene has ten within 0.02 in w): the labels
    spread up, down and sideways inside the axes instead of climbing out of them."""
    ds = crowded(fold, 10)
    fig = si.plot.continuation(ds)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    for ax in fig.axes[:-1]:
        frame = ax.get_window_extent(renderer)
        boxes = [Text.get_window_extent(a, renderer)
                 for a in ax.texts if isinstance(a, Annotation)]
        assert len(boxes) == ds.sizes["event"]
        outside = [b for b in boxes if b.y1 > frame.y1 + 1 or b.y0 < frame.y0 - 1
                   or b.x1 > frame.x1 + 1 or b.x0 < frame.x0 - 1]
        assert not outside, outside
        for i, a in enumerate(boxes):
            for b in boxes[i + 1:]:
                overlap = (min(a.x1, b.x1) - max(a.x0, b.x0), min(a.y1, b.y1) - max(a.y0, b.y0))
                assert not (overlap[0] > 0.5 and overlap[1] > 0.5), (a, b)


def test_no_brute_force_legend_without_sweeps(fold):
    """A scene without brute-force sweeps (the pitchfork's: a start on the symmetric orbit
    stays on it) stores an empty sweep dimension: no legend entry for sweeps not drawn."""
    def legend(ds):
        return [t.get_text() for t in si.plot.continuation(ds).axes[0].get_legend().get_texts()]

    assert fold.sizes["sweep"] > 0
    assert "brute force, up" in legend(fold)
    without = fold.isel(sweep=slice(0, 0))
    assert not [t for t in legend(without) if t.startswith("brute force")]
