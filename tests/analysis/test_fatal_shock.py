"""Minimal fatal shock: known boundaries (a ball, a box) found to the bisection width,
directions, and the result's minimum."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.analysis.fatal_shock import (
    fatal_shock_dataset,
    fatal_shocks,
    unit_directions,
)


def ball_labeller(orbit, radii):
    """Basin of "A": a ball of radius radii[k] around the orbit point of phase k."""
    def label(states, k):
        r = np.linalg.norm(states - orbit[k], axis=1)
        return ["A" if x < radii[k] else "B" for x in r]
    return label


@given(radius=st.floats(0.05, 4.0), tol=st.sampled_from([1e-2, 1e-3, 1e-4]))
def test_a_ball_is_found_to_the_bisection_width_in_every_direction(radius, tol):
    orbit = np.array([[0.3, -0.2, 1.0, 0.5]])
    directions = unit_directions(12, 4, seed=1)
    mag, dest = fatal_shocks(orbit, "A", ball_labeller(orbit, [radius]), directions,
                             max_shock=5.0, scan=10, tol=tol)
    assert np.all(mag >= radius) and np.all(mag <= radius + tol)
    assert np.all(dest == "B")


def test_the_minimum_is_over_phases_and_an_anisotropic_basin_has_its_axis():
    orbit = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])

    def label(states, k):  # a box |dx| < a_k, |dv| < 2 a_k around each phase's point
        a = (1.0, 0.4, 0.7)[k]
        d = np.abs(states - orbit[k])
        return ["A" if x < a and v < 2 * a else "B" for x, v in d]

    ds = fatal_shock_dataset(orbit, np.array([0.0, 1.0, 2.0]), "A", label,
                             unit_directions(360, 2, None), 3.0, 12, 1e-4, ("x", "v"))
    assert ds.attrs["mfs"] == pytest.approx(0.4, abs=1e-4)
    assert ds.attrs["mfs_time"] == 1.0 and ds.attrs["mfs_destination"] == "B"
    assert abs(ds.attrs["mfs_direction"][0]) == pytest.approx(1.0, abs=1e-9)  # along x
    per_phase = np.min(ds["shock_magnitude"].values, axis=1)
    np.testing.assert_allclose(per_phase, [1.0, 0.4, 0.7], atol=1e-4)


def test_nothing_fatal_up_to_max_shock_is_inf_and_said():
    orbit = np.zeros((2, 2))
    ds = fatal_shock_dataset(orbit, np.array([0.0, 3.0]), "A",
                             lambda s, k: ["A"] * len(s), unit_directions(8, 2, None), 2.0,
                             4, 1e-3, ("x", "v"))
    assert np.all(np.isinf(ds["shock_magnitude"].values))
    assert ds.attrs["mfs"] == np.inf
    assert ds.attrs["outcome"] == "no fatal shock up to 2 (2 phases x 8 directions)"


def test_directions_are_unit_and_one_body_gets_even_angles():
    d = unit_directions(100, 4, seed=3)
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0)
    np.testing.assert_array_equal(d, unit_directions(100, 4, seed=3))
    even = unit_directions(4, 2, None)
    np.testing.assert_allclose(even, [[1, 0], [0, 1], [-1, 0], [0, -1]], atol=1e-15)


def test_bad_search_settings_are_refused():
    with pytest.raises(ValueError, match="max_shock > 0"):
        fatal_shocks(np.zeros((1, 2)), "A", lambda s, k: ["A"] * len(s),
                     unit_directions(2, 2, None), 0.0)
