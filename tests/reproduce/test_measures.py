"""What the checks read from results: the boundary dimension tells a smooth boundary from
a ragged one; shares carry Wilson intervals; survivors follow d_crit."""

import numpy as np
import xarray as xr

from softimpact_cli.reproduce import measures as M


def test_boundary_dimension_is_one_for_a_straight_or_curved_boundary():
    y, x = np.mgrid[0:256, 0:256]
    assert abs(M.boundary_dimension((x > 100).astype(int)) - 1.0) < 0.05
    disc = ((x - 128) ** 2 + (y - 128) ** 2 < 80 ** 2).astype(int)
    assert abs(M.boundary_dimension(disc) - 1.0) < 0.1


def test_boundary_dimension_is_near_two_for_interleaved_basins():
    rng = np.random.default_rng(0)
    assert M.boundary_dimension(rng.integers(0, 2, (256, 256))) > 1.8


def test_share_groups_and_wilson_interval():
    point = {"counts": {"L1^1 R1-0^1": 900, "impacting P1": 60, "impacting P3": 40},
             "n": 1000}
    s, (lo, hi) = M.share(point, "impacting (all)")
    assert s == 0.1 and lo < 0.1 < hi and hi - lo < 0.04
    assert M.share(point, "non-impacting (sum)")[0] == 0.9
    assert M.found(point) == (["L1^1 R1-0^1"], ["impacting P1", "impacting P3"])


def test_survivors_are_the_combinations_below_d():
    ds = xr.Dataset({"d_crit": (("combination", "phi"), [[1.0, 3.0], [2.0, 0.5]]),
                     "combination_label": (("combination",), ["A", "B"])},
                    coords={"phi": [0.0, 1.0]})
    assert M.survivors(ds, 1.5, 0.0) == ["A"]
    assert M.survivors(ds, 1.5, 1.0) == ["B"]
    assert M.dcrit_at(ds, "A", 1.0) == 3.0
