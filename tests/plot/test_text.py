"""Shared figure text: phases in multiples of pi, the start time read from any result."""

import math

import numpy as np
import pytest
import xarray as xr
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.plot import multiple_text, parameter_text, phase_text, start_text


@pytest.mark.parametrize("phi, text", [
    (0.573 * math.pi, r"0.573\pi"), (5 * math.pi / 8, r"5\pi/8"), (math.pi, r"\pi"),
    (-math.pi / 2, r"-\pi/2"), (2 * math.pi, r"2\pi"), (0.0, "0"), (5.28, "5.28"),
    (1.80013, "1.80013"),  # a rounded 0.573 pi is not claimed to be one
])
def test_phase_text(phi, text):
    assert phase_text(phi) == text


@given(st.integers(-64, 64), st.integers(1, 64))
def test_every_fraction_of_pi_reads_back(a, b):
    text = phase_text(a * math.pi / b)
    if a == 0:
        assert text == "0"
        return
    head, _, den = text.partition("/")
    num = head.replace(r"\pi", "") or "1"
    num = "-1" if num == "-" else num
    assert float(num) / float(den or 1) == pytest.approx(a / b)


def test_t_multiples():
    assert multiple_text(0.5, "T", 1.0) == "T/2"
    assert multiple_text(0.25, "T", 1.0) == "T/4"


def ds_with(**attrs):
    return xr.Dataset(attrs={"forcing_period": 4.0, **attrs})


def test_start_time_from_whichever_record_exists():
    # trajectory results: attrs['t0'] in time units
    assert start_text(ds_with(t0=2.0)) == "$t_0 = T/2$"
    # the store's global attributes
    assert start_text(ds_with(t0=1.0, t0_over_T=0.25, t0_mode="fixed")) == "$t_0 = T/4$"
    assert start_text(ds_with(t0_mode="random")).startswith("random $t_0$")
    # sweeps: a t0 coordinate over the grid
    sweep = xr.Dataset(coords={"t0": ("panel", [3.0, 3.0])},
                       attrs={"forcing_period": 4.0, "t0_mode": "fixed"})
    assert start_text(sweep) == "$t_0 = 3T/4$"
    swept = xr.Dataset(coords={"t0": ("t0", np.array([0.0, 2.0]))},
                       attrs={"forcing_period": 4.0, "t0_mode": "grid"})
    assert start_text(swept) == "$t_0$ swept"
    assert start_text(ds_with()) == "$t_0 = 0$"


def test_parameter_text_in_tex_with_phi_in_pi():
    ds = ds_with(parameters=f"c=0.05, w=1.3, phi={0.573 * math.pi!r}, k_c=8.0, law=paper")
    text = parameter_text(ds, exclude=("k_c",))
    assert text == r"$c = 0.05$, $\omega = 1.3$, $\varphi = 0.573\pi$"


def test_the_recorded_start_time_wins_over_a_stale_coordinate():
    # the store records the t0 actually used as global attributes (issue 20, defect 3)
    sweep = xr.Dataset(coords={"t0": ("panel", [0.0, 0.0])},
                       attrs={"forcing_period": 4.0, "t0_mode": "fixed", "t0": 2.0,
                              "t0_over_T": 0.5})
    assert start_text(sweep) == "$t_0 = T/2$"


def test_a_start_time_that_differs_between_panels_is_read_per_panel():
    panels = xr.Dataset(coords={"t0": ("panel", [0.0, 1.0])},
                        attrs={"forcing_period": 4.0, "t0_mode": "fixed"})
    assert start_text(panels, (1,)) == "$t_0 = T/4$"
    assert start_text(panels) == "$t_0$ swept"


@pytest.mark.parametrize("lo, hi, expected", [
    (0.0, 2 * np.pi, [r"$\pi/2$", r"$\pi$", r"$2\pi$"]),
    (3.0, 4.0, [r"$\pi$", r"$9\pi/8$", r"$5\pi/4$"]),
    (1.0, 1.2, [r"$0.32\pi$", r"$0.34\pi$"]),  # a zoom: decimal multiples, still of pi
])
def test_phase_axis_ticks_are_multiples_of_pi(lo, hi, expected):
    from softimpact_cli.plot import new_figure, pi_ticks

    fig = new_figure()
    ax = fig.subplots()
    ax.plot([lo, hi], [0, 1])
    pi_ticks(ax.xaxis, lo, hi)
    fig.canvas.draw()
    labels = [t.get_text() for t in ax.get_xticklabels()]
    assert set(expected) <= set(labels)
