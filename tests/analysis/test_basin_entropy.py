"""Basin entropy S_b, S_bb (Daza et al. 2016) against a loop-by-loop reference, exact
values on a straight boundary, invariances, Newton's fractal basins; the entropy of the
shares of one random sampling."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from softimpact_cli.analysis.basin_entropy import (
    LN2,
    basin_entropy,
    box_entropy,
    default_box_sizes,
    share_entropy,
)
from tests.naive import basin_entropy_loops, newton_basins

planes = arrays(np.int32, st.tuples(st.integers(4, 24), st.integers(4, 24)),
                elements=st.sampled_from([-2, 0, 1, 7]))


@settings(max_examples=60, deadline=None)
@given(planes, st.integers(2, 4))
def test_matches_the_loop_by_loop_definition(labels, n):
    got = box_entropy(labels, n)
    s_b, s_bb = basin_entropy_loops(labels, n)
    assert got["S_b"] == pytest.approx(s_b, abs=1e-12)
    if math.isnan(s_bb):
        assert math.isnan(got["S_bb"]) and got["boundary_boxes"] == 0
    else:
        assert got["S_bb"] == pytest.approx(s_bb, abs=1e-12)
    assert got["boxes"] == (labels.shape[0] // n) * (labels.shape[1] // n)


@settings(max_examples=40, deadline=None)
@given(planes, st.permutations([-2, 0, 1, 7]), st.integers(2, 4))
def test_relabelling_or_transposing_the_plane_changes_nothing(labels, perm, n):
    relabelled = np.select([labels == v for v in (-2, 0, 1, 7)], perm)
    a, b, c = (box_entropy(x, n) for x in (labels, relabelled, labels.T))
    for other in (b, c):
        assert other["S_b"] == pytest.approx(a["S_b"], abs=1e-12)
        assert other["boundary_boxes"] == a["boundary_boxes"]


def test_a_straight_boundary_gives_the_values_by_hand_and_never_exceeds_ln2():
    """Columns >= 30 of a 60 x 60 plane in basin 1: with 4-cell boxes the boundary boxes
    (columns 28..31, 15 of them) hold two cells of each basin per row: S = ln 2 each."""
    labels = np.zeros((60, 60), dtype=int)
    labels[:, 30:] = 1
    got = box_entropy(labels, 4)
    assert got["boundary_boxes"] == 15 and got["boxes"] == 225
    assert got["S_bb"] == pytest.approx(LN2, abs=1e-15)
    assert got["S_b"] == pytest.approx(15 * LN2 / 225, abs=1e-15)
    assert math.isnan(box_entropy(labels, 5)["S_bb"])  # boundary on box edges: none seen
    # a tilted line: every box size, S_bb <= ln 2 (two basins), and not "fractal"
    yy, xx = np.mgrid[0:120, 0:120]
    tilted = basin_entropy((yy > 0.37 * xx + 20).astype(int), range(2, 21))
    assert np.all(tilted["S_bb"].values <= LN2 + 1e-12)
    assert not tilted["fractal_boundary"].values.any()
    # S_b falls as the boxes shrink (fewer of them straddle the line): ~ n for a line
    s_b = tilted["S_b"].sel(box_size=[4, 8, 16]).values
    assert s_b[0] < s_b[1] < s_b[2]
    assert s_b[2] / s_b[0] == pytest.approx(4.0, rel=0.3)


def test_newtons_basins_have_a_fractal_boundary_by_the_ln2_criterion():
    """Newton's method for z^3 = 1 on [-2, 2]^2, 200 x 200 cells (no published S_bb was
    found to compare with; the values are checked against the loop-by-loop reference
    above). S_bb exceeds ln 2 with boxes of a tenth of the window: boxes holding all
    three basins are common, which a smooth boundary cannot give."""
    labels = newton_basins(200)
    assert set(np.unique(labels)) == {0, 1, 2}
    ds = basin_entropy(labels, (5, 10, 20, 25))
    assert ds["S_bb"].sel(box_size=20) > LN2
    assert ds["fractal_boundary"].sel(box_size=20)
    for n in (5, 20):  # the vectorised result is the definition's
        s_b, s_bb = basin_entropy_loops(labels, n)
        assert float(ds["S_b"].sel(box_size=n)) == pytest.approx(s_b, abs=1e-12)
        assert float(ds["S_bb"].sel(box_size=n)) == pytest.approx(s_bb, abs=1e-12)


def test_box_sizes_are_checked_and_defaulted():
    assert default_box_sizes((100, 300)) == tuple(range(2, 21))
    assert default_box_sizes((12, 12)) == (2, 3)
    with pytest.raises(ValueError, match="box size: a whole number of cells in 2..10"):
        box_entropy(np.zeros((10, 12)), 11)
    with pytest.raises(ValueError, match="2-D plane"):
        box_entropy(np.zeros(10), 2)


def test_share_entropy_of_one_sampling():
    h, lo, hi = share_entropy([250, 250, 250, 250])
    assert h == pytest.approx(math.log(4))
    assert lo < h <= hi <= math.log(4) + 1e-12 and lo > 1.3
    assert share_entropy([1000, 0, 0]) == (0.0, 0.0, 0.0)
    # the interval shrinks like 1 / sqrt(N) and is reproducible
    small = share_entropy([70, 30])
    large = share_entropy([7000, 3000])
    assert small == share_entropy([70, 30])
    assert small[0] == pytest.approx(large[0])
    assert (large[2] - large[1]) < (small[2] - small[1]) / 5
    assert all(math.isnan(v) for v in share_entropy([0, 0]))


def test_a_stability_result_reports_the_entropy_of_its_shares():
    from softimpact_cli.analysis.stability import basin_stability
    from softimpact_cli.report.info import stability_summary
    from tests.plot.test_stability_dcrit_figures import stability_sweep

    ds = stability_sweep()  # 7 of 10 samples on one solution, 3 on the other
    bs = basin_stability(ds)
    expected = -(0.7 * math.log(0.7) + 0.3 * math.log(0.3))
    assert bs["entropy"].values == pytest.approx(np.full(4, expected))
    assert np.all(bs["entropy_ci_low"].values <= expected)
    point = stability_summary(ds)[0]
    assert point["entropy"]["H"] == pytest.approx(expected)
    assert point["entropy"]["ci95"][1] >= expected
