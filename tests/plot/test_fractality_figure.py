"""The fractality figure: entropy against the box size with ln 2, the log-log fit with
alpha and its interval, the boundary map the right way round."""

import math

import numpy as np
import pytest

import softimpact_cli as si
from tests.kinds.test_fractality import basins_dataset


@pytest.fixture(scope="module")
def measured():
    return si.measure(basins_dataset(), box_sizes=(2, 4, 8), radii=(1, 2, 4, 8))


def test_each_plane_has_entropy_fit_and_boundary_panels(measured):
    fig = si.plot.fractality(measured)
    entropy, fit, wada = fig.axes[:3]
    assert entropy.get_xlabel() == "box size n (cells)"
    assert any(np.allclose(line.get_ydata(), math.log(2)) for line in entropy.get_lines())
    s_bb = [line for line in entropy.get_lines() if line.get_label() == r"$S_{bb}$"][0]
    np.testing.assert_allclose(s_bb.get_ydata(), measured["S_bb"].values[0])
    legend = [t.get_text() for t in fit.get_legend().get_texts()]
    alpha = float(measured["alpha"].values[0])
    assert any(f"\\alpha = {alpha:.3f}" in t and "D = " in t for t in legend)
    assert fit.get_xscale() == "log" and fit.get_yscale() == "log"
    assert "Wada Wada" in wada.get_title() and "Wada not Wada" in fig.axes[5].get_title()


def test_the_boundary_map_puts_the_planes_first_axis_across(measured):
    fig = si.plot.fractality(measured, max_panels=1)
    wada = fig.axes[2]
    assert (wada.get_xlabel(), wada.get_ylabel()) == ("$x_1$", "$x_2$")
    shown = wada.get_images()[0].get_array()
    stored = measured["wada_map"].values[0].astype(float)  # (x1, x2): rows are x1
    np.testing.assert_array_equal(np.ma.filled(shown, 0), stored.T)
    assert "first 1 of 2" in fig._suptitle.get_text()
