"""A chain's results beyond their numbers: each stop's maximum penetration in a trajectory
(and in ``info``), the trajectory figure with every body, ``softimpact check`` and
``compare`` on a chain's dcrit and bifurcation, and the printed example reaching every
stop."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli import plot
from softimpact_cli.config.examples import CHAIN_EXAMPLE
from softimpact_cli.kinds.check import check_scene
from softimpact_cli.kinds.results import compare_results, describe, format_summary
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene

from .test_chain_kinds import BIFURCATION, CHAIN

# stop 1 impacts, stop 2 (bodies 2-3) and the left wall of body 3 stay clear
TRAJECTORY = """\
[system]
model = "chain"
bodies = 3
k2 = 0.01
w = 1.3
phi = [0.0, "5*pi/8", "5*pi/4"]

[[stop]]
between = [1, 2]
d = 2.0

[[stop]]
between = [2, 3]
d = 4.0

[[stop]]
body = 3
wall = -4.0
side = "left"

[analysis]
kind = "trajectory"
state = [1.5, 0.0, -0.5, 1.0, -2.0, 0.0]
periods = 120
samples_per_period = 512
"""


@pytest.fixture(scope="module")
def trajectory():
    return run_scene(parse_scene(TRAJECTORY))


def test_a_chain_trajectory_holds_each_stops_maximum(trajectory):
    """One maximum per stop, each the stop's own compression: against the dense samples
    of the last period of the (period-1) orbit, which lie below it and within a sample's
    reach of it; their largest is the trajectory's one maximum."""
    ds = trajectory
    assert ds.attrs["outcome"] == "converged" and ds.attrs["period"] == 1
    per_stop = ds["stop_max_penetration"]
    assert per_stop.dims == ("stop",) and list(ds["stop"].values) == [1, 2, 3]
    assert list(ds["stop_between"].values) == ["bodies 1-2", "bodies 2-3",
                                               "body 3 / left wall"]
    T = ds.attrs["forcing_period"]
    last = ds["time"].values >= ds["time"].values[-1] - T
    x = ds["state"].values[last][:, 0::2]
    sampled = [np.max(x[:, 0] - x[:, 1] - 2.0), np.max(x[:, 1] - x[:, 2] - 4.0),
               np.max(-4.0 - x[:, 2])]
    assert per_stop.values[0] > 0 > per_stop.values[1] and per_stop.values[2] < 0
    for exact, seen in zip(per_stop.values, sampled, strict=True):
        assert seen - 1e-6 <= exact <= seen + 2e-3
    assert np.max(per_stop.values) == pytest.approx(ds.attrs["max_penetration"], abs=1e-6)
    text = format_summary(describe(ds), ds)
    assert "stop 1 (bodies 1-2) 0." in text and "stop 3 (body 3 / left wall) -" in text


def test_a_chain_trajectory_figure_draws_every_body(trajectory):
    """A panel per body (its phase portrait), every body's displacement, and every stop's
    compression, whose top is the stop's maximum."""
    fig = plot.trajectory(trajectory)
    titles = [ax.get_title() for ax in fig.axes]
    assert [t for t in titles if t.startswith("phase portrait")] == [
        f"phase portrait, body {k}" for k in (1, 2, 3)]
    series = fig.axes[titles.index("time series (dots: $t = t_0 + nT$)")]
    assert [line.get_label() for line in series.get_lines()][:5:2] == ["$x_1$", "$x_2$",
                                                                       "$x_3$"]
    stops = fig.axes[titles.index("stops")]
    curves = [line for line in stops.get_lines() if line.get_label().startswith("stop ")]
    assert len(curves) == 3
    t = curves[0].get_xdata()
    last = t >= t[-1] - 1.0  # the last forcing period: on the orbit
    for curve, exact in zip(curves, trajectory["stop_max_penetration"].values, strict=True):
        assert exact - 2e-3 <= np.max(curve.get_ydata()[last]) <= exact + 1e-6


def test_the_printed_example_reaches_every_stop():
    """`softimpact example chain`: each stop (one per law) in contact on the final orbit."""
    ds = run_scene(parse_scene(CHAIN_EXAMPLE))
    laws = [stop.law for stop in parse_scene(CHAIN_EXAMPLE).system.extra["chain"].stops]
    assert sorted(laws) == ["hunt-crossley", "no-tension", "paper"]
    assert ds.attrs["outcome"] == "converged"
    assert (ds["stop_max_penetration"].values >= 0).all()


def _chain_dcrit(tmp_path):
    return run_scene(parse_scene(CHAIN + '[grid]\n"F.2" = [1.0, 1.5]\n'
                                 + f'[output]\npath = "{tmp_path / "d.h5"}"\n'))


@pytest.mark.slow
def test_compare_and_check_take_a_chains_dcrit(tmp_path):
    """compare: B - A per stop and product along the chain's axis; check: the critical
    values at tightened settings move by little."""
    a = _chain_dcrit(tmp_path)
    b = a.copy(deep=True)
    b["d_crit"].values[1, 0, 1] += 0.25
    report = compare_results(a, b, "a.h5", "b.h5")
    moved = f"stop 2: {a['combination_label'].values[0]}"
    assert report["axis"] == "F.2" and report["max_d_change"] == pytest.approx(0.25)
    assert report["combinations"][moved] == {"max_change": pytest.approx(0.25), "at": 1.5}
    scene = parse_scene(CHAIN + '[grid]\n"F.2" = [1.0, 1.5]\n')
    checked = check_scene(scene, 1, 0)
    assert checked["sample"] == 1 and checked["max_change"] < 1e-6


def test_compare_and_check_take_a_chains_bifurcation(tmp_path):
    """compare names the followed parameter; check follows the branches again at
    tightened settings and half the step (matched by name)."""
    scene = parse_scene(BIFURCATION + f'[output]\npath = "{tmp_path / "b.h5"}"\n')
    a = run_scene(scene)
    b = a.copy(deep=True)
    b["destroyed_at"].values[0] += 0.1
    report = compare_results(a, b, "a.h5", "b.h5")
    assert report["parameter"] == "stop.1.d"
    assert report["max_d_change"] == pytest.approx(0.1)
    checked = check_scene(scene, 1, 0)
    assert checked["kind"] == "destruction points" and checked["max_change"] < 0.05
    assert checked["appeared_or_vanished"] == 0
