"""A planted chaotic case through the whole sweep: Ueda's oscillator (one body,
x'' + 0.05 x' + x^3 = 7.5 sin t; lambda1 = 0.0999 / time, Sprott 2001) with a first pass
too short to settle, so every trajectory ends unresolved and the second stage must name
it. The labels and the attractor table are the same serially, on a pool of two with
small chunks, in memory and on a Dask cluster."""

import numpy as np
import pytest

from softimpact_cli.kernels.codes import BY_SECTION, CHAOTIC_BASE, UNRESOLVED
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep
from softimpact_cli.sweep.in_memory import sweep_in_memory

SCENE = """
[system]
model = "duffing"
bodies = 1
c = 0.05
k1 = 0.0
k2 = 1.0
F = 7.5
w = 1.0

[integrator]
max_periods = 40
section_periods = 1500
section_lyapunov_periods = 300

[analysis]
kind = "basins"

[initial_conditions]
kind = "list"
states = [[2.5, 0.0], [0.0, 0.0], [-2.0, 1.0], [3.0, -3.0], [1.0, 1.0], [-1.5, -0.5]]

[verification]
enabled = false

[output]
path = "{out}"
"""

TABLE = ("nonperiodic_code", "nonperiodic_point", "nonperiodic_flat", "nonperiodic_members",
         "nonperiodic_cells", "nonperiodic_exponents", "nonperiodic_cloud")


def scene(out):
    return parse_scene(SCENE.format(out=out), "ueda_planted.toml")


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial") / "r.h5"
    return run_sweep(scene(out), out, workers=1)


def same(a, b):
    for var in ("label", "status", "period", "periods_used", "captured", *TABLE):
        assert np.array_equal(a[var].values, b[var].values, equal_nan=True), var


def test_every_trajectory_is_the_one_chaotic_attractor(serial):
    assert serial["label"].values.ravel().tolist() == [CHAOTIC_BASE + 1] * 6
    assert (serial["status"] == UNRESOLVED).all()  # the first pass found no period
    assert (serial["captured"] == BY_SECTION).all()
    assert serial["nonperiodic_name"].values.tolist() == ["chaotic A1"]
    assert "chaotic A1" in serial["label_name"].values.tolist()
    lam = serial["nonperiodic_exponents"].values[0]
    # 300 periods from one trajectory: within a few standard errors of the published
    # 0.0999 and -0.1499, and the sum is -c = -0.05 up to the integration error
    assert 0.07 < lam[0] < 0.14 and -0.19 < lam[1] < -0.12
    assert lam.sum() == pytest.approx(-0.05, abs=2e-3)
    cloud = serial["nonperiodic_cloud"].values[0]
    assert np.isfinite(cloud).all() and np.ptp(cloud[:, 0]) > 2.0  # a spread set


@pytest.mark.slow
def test_the_same_labels_on_a_pool_in_memory_and_on_dask(serial, tmp_path):
    out = tmp_path / "pool.h5"
    same(serial, run_sweep(scene(out), out, workers=2, chunk_size=2))
    same(serial, sweep_in_memory(scene(tmp_path / "m.h5"), workers=2, chunk_size=3))
    pytest.importorskip("dask.distributed")
    out = tmp_path / "dask.h5"
    same(serial, run_sweep(scene(out), out, scheduler="local:2", chunk_size=2))


def test_info_lists_the_attractor_with_its_exponents(serial):
    from softimpact_cli.kinds.results import describe, format_summary

    summary = describe(serial)
    (row,) = summary["nonperiodic"]
    assert row["name"] == "chaotic A1" and row["members"] == 6 and row["kind"] == "chaotic"
    line = next(x for x in format_summary(summary, serial).splitlines()
                if x.strip().startswith("chaotic A1"))
    assert "6 trajectories" in line and f"{row['exponents'][0]:+.4f}" in line
