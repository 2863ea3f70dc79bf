"""The catalogue figure stays legible with many combinations: figure 13's 28 combinations
in six columns sharing one x1/x2 scale, no font under 8 points, a panel letter each."""

from pathlib import Path

import pytest

import softimpact_cli as si
from softimpact_cli.plot.catalogue_figure import COMPACT_AFTER

ROOT = Path(__file__).parents[2]


def fonts_and_letters(fig):
    sizes, letters = [], []
    for ax in fig.axes:
        for text in [*ax.texts, ax.title, ax.xaxis.label, ax.yaxis.label,
                     *ax.get_xticklabels(), *ax.get_yticklabels()]:
            if text.get_text() and text.get_visible():
                sizes.append(text.get_fontsize())
        letters += [t.get_text() for t in ax.texts if t.get_text().startswith("(")]
    return sizes, letters


@pytest.mark.slow
def test_figure_13_catalogue_is_compact_and_legible():
    ds = si.run(ROOT / "configs" / "fig13_bilinear_catalogue.toml")
    combos = ds.sizes["combination"]
    assert combos == 28 > COMPACT_AFTER
    fig = si.plot.catalogue(ds)
    width, height = fig.get_size_inches()
    assert width <= 16 and height <= 16  # was 16 x 26.6 in, panels 4 x 2.6 in
    sizes, letters = fonts_and_letters(fig)
    assert min(sizes) >= 8
    assert len(set(letters)) == len(letters) == combos + 1
    assert letters[-1] == "(ac)" and all(t[1:-1].isalpha() for t in letters)
    combo_axes = fig.axes[1:]
    assert all(ax.get_shared_y_axes().joined(combo_axes[0], ax) for ax in combo_axes)


def test_a_small_catalogue_keeps_its_layout():
    ds = si.run({"system": {"model": "duffing"}, "coupling": {"phi": 0.0},
                 "analysis": {"kind": "catalogue", "grid": 4, "random": 20, "seed": 1}})
    assert ds.sizes["combination"] <= COMPACT_AFTER
    fig = si.plot.catalogue(ds)
    assert tuple(fig.get_size_inches()) == (16.0, 2.6 * 2 + 0.6)
    sizes, _ = fonts_and_letters(fig)
    assert min(sizes) >= 8
