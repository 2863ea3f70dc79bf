"""Uncertainty exponent alpha and boundary dimension D = 2 - alpha: a straight boundary
(alpha = 1, the uncertain share by hand), Cantor combs of known box-counting dimension,
Newton's basins, the fit and its interval."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from softimpact_cli.analysis.uncertainty import (
    default_radii,
    fit_slope,
    t975,
    uncertain_fraction,
    uncertainty_exponent,
    window_extremes,
)
from tests.naive import cantor_comb, newton_basins


def test_a_straight_boundary_has_alpha_one_and_the_uncertain_share_by_hand():
    """Columns >= 40 of 100 in basin 1: the windows of radius r centred on columns
    40 - r .. 39 + r straddle it, 2 r of the 100 - 2 r columns whose window fits."""
    labels = np.zeros((60, 100), dtype=int)
    labels[:, 40:] = 1
    for r in (1, 2, 5, 9):
        assert uncertain_fraction(labels, r) == pytest.approx(2 * r / (100 - 2 * r))
    wide = np.zeros((40, 400), dtype=int)
    wide[:, 123:] = 1
    ds = uncertainty_exponent(wide, (1, 2, 3, 5, 8, 13))
    assert float(ds["alpha"]) == pytest.approx(1.0, abs=0.03)  # 1 / (400 - 2r): a bit > 1
    assert float(ds["dimension"]) == pytest.approx(1.0, abs=0.03)
    yy, xx = np.mgrid[0:400, 0:400]
    tilted = uncertainty_exponent((yy > 0.37 * xx + 80).astype(int), (1, 2, 3, 5, 8, 13))
    assert float(tilted["alpha"]) == pytest.approx(1.0, abs=0.03)
    assert tilted["alpha_ci_low"] <= tilted["alpha"] <= tilted["alpha_ci_high"]


@pytest.mark.parametrize("base, kept, level, radii", [
    (3, (0, 2), 8, (1, 2, 3, 5, 8, 12, 18, 27)),  # middle thirds: D = 1 + ln 2 / ln 3
    (4, (0, 3), 7, (1, 2, 4, 8, 16)),              # D = 1 + ln 2 / ln 4 = 1.5
])
def test_a_cantor_comb_gives_its_box_counting_dimension(base, kept, level, radii):
    """The boundary C x [0, 1] of a Cantor set C of ``kept`` base-``base`` digits has
    box-counting dimension 1 + ln|kept| / ln base. At a finite construction level the
    smallest gaps are single cells and the estimate approaches the limit from below (a
    level lower is farther off: the test would notice a fit that does not converge)."""
    expected = 1.0 - math.log(len(kept)) / math.log(base)
    rows = 2 * max(radii) + 3
    ds = uncertainty_exponent(cantor_comb(base, kept, level, rows), radii)
    coarse = uncertainty_exponent(cantor_comb(base, kept, level - 2, rows), radii)
    assert float(ds["alpha"]) == pytest.approx(expected, abs=0.02)
    assert float(ds["dimension"]) == pytest.approx(2.0 - expected, abs=0.02)
    assert abs(float(ds["alpha"]) - expected) < abs(float(coarse["alpha"]) - expected)


def test_newtons_basins_have_a_fractal_boundary():
    ds = uncertainty_exponent(newton_basins(200))
    assert 1.2 < float(ds["dimension"]) < 1.7
    assert float(ds["alpha_ci_high"]) < 0.8  # far from a smooth boundary's 1
    assert bool(ds["in_fit"].all())


def test_no_boundary_gives_nan_and_bad_radii_are_refused():
    ds = uncertainty_exponent(np.ones((30, 30), dtype=int), (1, 2, 3))
    assert math.isnan(float(ds["alpha"])) and not ds["in_fit"].any()
    with pytest.raises(ValueError, match="radii: whole numbers of cells >= 1 with 2 r"):
        uncertainty_exponent(np.ones((30, 30)), (1, 15))
    with pytest.raises(ValueError, match="radii"):
        uncertainty_exponent(np.ones((30, 30)), (0, 2))
    assert default_radii((100, 100))[0] == 1 and default_radii((100, 100))[-1] == 10
    assert default_radii((20, 400)) == (1, 2, 3)


@settings(max_examples=40, deadline=None)
@given(arrays(np.int64, st.tuples(st.integers(3, 14), st.integers(3, 14)),
              elements=st.integers(0, 5)), st.integers(1, 3))
def test_window_extremes_are_those_of_every_window(codes, r):
    if 2 * r + 1 > min(codes.shape):
        return
    lo, hi = window_extremes(codes, r)
    for i, j in np.ndindex(*lo.shape):
        window = codes[i:i + 2 * r + 1, j:j + 2 * r + 1]
        assert lo[i, j] == window.min() and hi[i, j] == window.max()


@settings(max_examples=30, deadline=None)
@given(st.floats(-3, 3), st.floats(-5, 5))
def test_the_fit_recovers_a_line_exactly(slope, intercept):
    x = np.log(np.arange(1, 9, dtype=float))
    fit = fit_slope(x, intercept + slope * x)
    assert fit["slope"] == pytest.approx(slope, abs=1e-9)
    assert fit["stderr"] == pytest.approx(0.0, abs=1e-9)
    assert math.isnan(fit_slope(x[:2], x[:2])["slope"])


def test_the_t_quantile_matches_scipy():
    from scipy.stats import t

    for df in range(1, 60):
        tol = 1e-12 if df <= 5 else 1.1e-4
        assert t975(df) == pytest.approx(t.ppf(0.975, df), abs=tol)


def test_the_published_grebogi_map_boundary_has_alpha_near_0_2():
    """McDonald, Grebogi, Ott and Yorke's map (Physica D 17, 125 (1985); a = 1.32,
    b = 0.9, J0 = 0.3), basins of its fixed points (0, -J0) and (pi, J0) on a 251 x 251
    grid of theta in [0, 2 pi], x in [-0.5, 0.5]: the paper gives alpha roughly 0.2
    (D ~ 1.8); Attractors.jl's test of the same grid accepts 0.2 <= alpha <= 0.3."""
    a, b, j0 = 1.32, 0.9, 0.3
    th, x = np.meshgrid(np.linspace(0, 2 * np.pi, 251), np.linspace(-0.5, 0.5, 251),
                        indexing="ij")
    for _ in range(300):
        th, x = (np.mod(th + a * np.sin(2 * th) - b * np.sin(4 * th) - x * np.sin(th),
                        2 * np.pi), -j0 * np.cos(th))
    labels = np.where(np.cos(th) > 0, 0, 1)
    assert np.all(np.abs(np.abs(np.cos(th)) - 1) < 1e-3)  # every start reached a fixed point
    ds = uncertainty_exponent(labels)
    assert 0.15 <= float(ds["alpha"]) <= 0.3
    assert float(ds["alpha_ci_low"]) <= 0.2 <= float(ds["alpha_ci_high"])
    assert float(ds["dimension"]) == pytest.approx(2 - float(ds["alpha"]))
