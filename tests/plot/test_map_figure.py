"""Map figure: an all-zero panel says so; phi ticks in multiples of pi."""

import numpy as np
import xarray as xr

from softimpact_cli.plot.map_figure import ALL_ZERO, draw_map


def count_map(predicted: int = 0) -> xr.Dataset:
    d = np.array([1.0, 2.0, 3.0])
    phi = np.linspace(0, 3 * np.pi / 2, 4)
    shape = (3, 4)
    found = np.ones(shape, dtype=np.int16)
    return xr.Dataset(
        {"predicted_count": (("d", "phi"), np.full(shape, predicted, dtype=np.int16)),
         "found_count": (("d", "phi"), found),
         "found_nonimpacting": (("d", "phi"), found * 0),
         "x1": (("sample",), np.zeros(5))},
        coords={"d": d, "phi": phi, "sample": np.arange(5)},
        attrs={"analysis": "map", "ic_dims": "sample", "model": "duffing",
               "ic_kind": "random", "t0_mode": "fixed", "forcing_period": 4.0,
               "parameters": "c=0.05, d=6.0, phi=0.0"})


def test_an_all_zero_panel_says_so_in_words():
    fig = draw_map(count_map(predicted=0))
    words = [t.get_text() for t in fig.axes[0].texts]
    assert ALL_ZERO[0] in words
    assert "no coexisting non-impacting solution" in ALL_ZERO[0]
    assert not any(ALL_ZERO[1] == t.get_text() for t in fig.axes[1].texts)
    busy = draw_map(count_map(predicted=1))
    assert ALL_ZERO[0] not in [t.get_text() for t in busy.axes[0].texts]


def test_phi_axis_in_multiples_of_pi_and_panel_letters():
    fig = draw_map(count_map(predicted=1))
    ticks = [t.get_text() for t in fig.axes[0].get_yticklabels()]  # phi: second grid axis
    assert r"$\pi/2$" in ticks and r"$\pi$" in ticks
    letters = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert {"(a)", "(b)", "(c)"} <= letters
    assert "t_0 = 0" in fig.get_suptitle()
