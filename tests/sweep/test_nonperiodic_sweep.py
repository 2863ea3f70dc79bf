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


def test_a_trajectory_names_its_attractor_as_the_sweep_does(serial):
    """The trajectory kind from the sweep's first start (2.5, 0), same settings: the same
    second stage, the same attractor and the very same exponents (issue 31, item 2)."""
    from softimpact_cli.analysis.engine import Problem
    from softimpact_cli.analysis.trajectory import trajectory_dataset

    text = SCENE.replace('kind = "basins"', 'kind = "trajectory"\nstate = [2.5, 0.0]')
    text = text[: text.index("[initial_conditions]")] + '[output]\npath = "t.h5"\n'
    sc = parse_scene(text, "ueda_trajectory.toml")
    ds = trajectory_dataset(Problem(sc.system, sc.values, sc.integrator), [2.5, 0.0], 0.0,
                            50, 8)
    assert ds.attrs["outcome"] == "chaotic" and ds.attrs["label"] == "chaotic A1"
    assert ds.attrs["periods_used"] == int(serial["periods_used"].values.ravel()[0])
    for var in ("nonperiodic_exponents", "nonperiodic_stderr", "nonperiodic_cloud"):
        assert np.array_equal(ds[var].values[0], serial[var].values[0]), var


def test_the_messages_say_what_happened(tmp_path, monkeypatch):
    """Issue 31, item 3, through the CLI: the catalogue line before the chunks, the
    progress line, the closing note (no warning to raise max_periods) and info's status
    line all agree with the labels `chaotic A1`."""
    from click.testing import CliRunner

    from softimpact_cli.cli import main

    monkeypatch.setenv("SOFTIMPACT_PROGRESS_INTERVAL", "600")  # the last line only
    out = tmp_path / "r.h5"
    path = tmp_path / "ueda.toml"
    path.write_text(SCENE.format(out=out))
    run = CliRunner().invoke(main, ["sweep", str(path), "--workers", "1", "--no-verify"])
    assert run.exit_code == 0, run.output
    err = run.stderr
    assert "no non-impacting solution found" not in err and "warning" not in err
    assert "catalogue: no periodic non-impacting solution among " in err
    assert "labels will be impacting periodic orbits, attractors that are not periodic " \
           "(the second stage names them after the last chunk), unresolved or diverged" in err
    assert "unresolved 0 (0.00%), on a recurrent set 6 (100.00%, named at the end)" in err
    assert "softimpact: note: the catalogue search found no periodic solution among " in err
    assert "the sweep's second stage found 1 attractor that is not periodic: chaotic A1 " \
           "(6 trajectories)" in err
    assert "found no solution among 0" not in err and "raise [integrator]" not in err
    info = CliRunner().invoke(main, ["info", str(out)]).output
    (status,) = [x for x in info.splitlines() if x.startswith("status ")]
    assert status.split(None, 1)[1] == ("converged 0, unresolved 6 (first pass; then named "
                                         "not periodic 6, left unresolved 0), diverged 0")
    line = next(x for x in info.splitlines() if x.strip().startswith("chaotic A1"))
    assert "d=" not in line  # one body: no stop, no d, phi, k_c, c_c to show


def test_later_trajectories_stop_on_the_known_attractor(serial, tmp_path):
    """Issue 31, item 3: once the block's first trajectory found chaotic A1 (full second
    stage), the next ones are found on its cells within the probe and stop there; the
    labels and the attractor are those of a run that follows every trajectory in full
    (cells off, as the verification runs)."""
    from dataclasses import replace

    from softimpact_cli.analysis.section_follow import PROBE_PERIODS

    used = serial["periods_used"].values.ravel()
    assert used[0] > 40 + PROBE_PERIODS  # the first: max_periods, then the full stage
    assert (used[1:] <= 40 + PROBE_PERIODS).all()  # the others: the probe only
    sc = scene(tmp_path / "full.h5")
    full = run_sweep(replace(sc, integrator=replace(sc.integrator, cell_size=0.0)),
                     tmp_path / "full.h5", workers=1)
    assert np.array_equal(full["label"].values, serial["label"].values)
    assert (full["periods_used"].values.ravel()[1:] > 40 + PROBE_PERIODS).all()
    for var in ("nonperiodic_code", "nonperiodic_members", "nonperiodic_exponents"):
        assert np.array_equal(full[var].values, serial[var].values), var
