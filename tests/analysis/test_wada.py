"""The Wada merging test: Newton's basins for z^3 = 1 (Wada), three sectors (not Wada),
two basins (not applicable), invariance under relabelling, the building blocks."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from softimpact_cli.analysis.wada import (
    NOT_APPLICABLE,
    NOT_WADA,
    WADA,
    dilate,
    edge_cells,
    wada_merge,
)
from tests.naive import newton_basins


def sectors(n: int = 150) -> np.ndarray:
    """Three 120-degree sectors meeting at the centre: three basins, three smooth
    boundary rays, each between two basins only."""
    yy, xx = np.mgrid[0:n, 0:n] - n / 2 + 0.3
    return np.floor((np.arctan2(yy, xx) + np.pi) / (2 * np.pi / 3)).astype(int) % 3


def test_newtons_basins_are_wada():
    ds = wada_merge(newton_basins(200))
    assert str(ds["verdict"].values) == WADA
    assert int(ds["wada_radius_found"]) <= 2
    assert float(ds["wada_fraction"].values[-1]) > 0.99  # boundary points on all three
    assert ds.attrs["n_basins"] == 3
    assert set(np.unique(ds["wada_map"].values)) == {0, 3}  # at r = 5: every one near all


def test_three_sectors_are_not_wada():
    ds = wada_merge(sectors())
    assert str(ds["verdict"].values) == NOT_WADA
    assert int(ds["wada_radius_found"]) == -1
    # each merged boundary is two rays, one of which the other merged boundary lacks
    assert np.all(ds["mismatch"].values == pytest.approx(0.5, abs=0.05))  # less ~r/ray
    # only the cells near the triple point are near all three: ~ r / side of them
    assert np.all(ds["wada_fraction"].values < 0.1)
    assert np.all(np.diff(ds["wada_fraction"].values) > 0)


def test_two_basins_are_not_applicable_and_a_stray_label_breaks_wada():
    two = wada_merge((newton_basins(60) > 0).astype(int))
    assert str(two["verdict"].values) == NOT_APPLICABLE
    assert np.isnan(two["mismatch"].values).all()
    assert set(np.unique(two["wada_map"].values)) == {0, 2}  # the boundary is still drawn
    # every label is a basin: a patch of "unresolved" cells is a fourth basin whose
    # boundary is not the others', and Newton's plane stops being Wada
    labels = newton_basins(200)
    labels[10:20, 10:20] = -9
    assert str(wada_merge(labels)["verdict"].values) == NOT_WADA


@settings(max_examples=10, deadline=None)
@given(st.permutations([0, 1, 2]), st.sampled_from([-5, 3, 40]))
def test_relabelling_changes_nothing(perm, offset):
    labels = newton_basins(64)
    base = wada_merge(labels)
    relabelled = wada_merge(np.asarray(perm)[labels] * 7 + offset)
    for key in ("mismatch", "wada_fraction", "wada_map"):
        np.testing.assert_array_equal(relabelled[key].values, base[key].values)
    assert str(relabelled["verdict"].values) == str(base["verdict"].values)


@settings(max_examples=40, deadline=None)
@given(arrays(bool, st.tuples(st.integers(1, 12), st.integers(1, 12))), st.integers(0, 3))
def test_dilate_is_the_chebyshev_neighbourhood(mask, r):
    got = dilate(mask, r)
    ii, jj = np.nonzero(mask)
    for i, j in np.ndindex(*mask.shape):
        near = bool(np.any((np.abs(ii - i) <= r) & (np.abs(jj - j) <= r)))
        assert got[i, j] == near


def test_edge_cells_are_both_sides_of_a_boundary():
    member = np.zeros((5, 6), dtype=bool)
    member[:, 3:] = True
    edges = edge_cells(member)
    assert edges[:, 2:4].all() and not edges[:, :2].any() and not edges[:, 4:].any()


def test_bad_settings_are_refused():
    with pytest.raises(ValueError, match="max_radius"):
        wada_merge(sectors(20), max_radius=0)
    with pytest.raises(ValueError, match="tol"):
        wada_merge(sectors(20), tol=1.0)
