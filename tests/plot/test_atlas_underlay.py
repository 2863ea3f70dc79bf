"""The atlas figure's underlay: a map's counts as cells, a dcrit result's curves as lines,
told apart by their data (a map also holds a d_crit table of its own)."""

import matplotlib
import numpy as np
import xarray as xr

from softimpact_cli.plot.atlas_figure import _underlay

matplotlib.use("Agg")

PHI = np.linspace(0.0, 6.0, 4)
D = np.linspace(0.0, 20.0, 5)


def _axes():
    from matplotlib.figure import Figure

    return Figure().subplots()


def test_a_map_is_drawn_as_its_counts_even_though_it_holds_a_d_crit_table():
    result = xr.Dataset({"found_count": (("d", "phi"), np.arange(20.0).reshape(5, 4)),
                         "d_crit": (("dcrit_combination", "dcrit_phi"), np.ones((2, 3)))},
                        coords={"d": D, "phi": PHI})
    ax = _axes()
    _underlay(ax, result, "phi", "d")
    assert len(ax.images) == 1 and not ax.lines
    assert np.array_equal(ax.images[0].get_array(), result["found_count"].values)


def test_a_dcrit_result_is_drawn_as_one_curve_per_combination():
    result = xr.Dataset({"d_crit": (("combination", "phi"), np.ones((3, 4)))},
                        coords={"phi": PHI})
    ax = _axes()
    _underlay(ax, result, "phi", "d")
    assert not ax.images and len(ax.lines) == 3
