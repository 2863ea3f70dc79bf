"""The forcing phase at the start: t0 is explicit, sweepable and random (issue 10)."""

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import label_orbit, sample_states
from softimpact_cli.analysis.engine import Problem, classify_state, flow, record_trajectory
from softimpact_cli.config.axes import catalogue_key
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import prepare_catalogues, run_sweep
from softimpact_cli.systems import get_system

DUFFING = dict(c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3, d=3.0, phi=1.0, k_c=8.0, c_c=10.0,
               law="paper")


def test_start_at_T_equals_start_at_0():
    pr = Problem(get_system("duffing", 2), DUFFING)
    T = pr.period
    for state in ([3.0, 0.0, -3.0, 0.0], [-6.0, 2.0, 5.0, -1.0], [9.0, 0.0, 0.0, 0.0]):
        a = classify_state(pr, state, 0.0)
        b = classify_state(pr, state, T)
        assert a.status == b.status == 0 and a.period == b.period
        assert np.max(np.abs(a.orbit - b.orbit)) < 1e-9
        assert a.impacting == b.impacting


def test_trajectory_started_at_t0_continues_one_started_at_0():
    """Start at 0, read the state at t0; a start at t0 from that state is the same
    trajectory, shifted: equal section points from then on."""
    pr = Problem(get_system("duffing", 2), DUFFING).with_integrator(rtol=1e-11, atol=1e-12)
    T = pr.period
    y0 = np.array([3.0, 0.0, -3.0, 0.0])
    t0 = 0.37 * T
    _, y_t0, _ = flow(pr, y0, 0.0, t0)
    whole = record_trajectory(pr, y0, 0.0, 6, 16)
    later = record_trajectory(pr, y_t0, t0, 5, 16)
    assert later.section_t[0] == pytest.approx(T)
    assert np.max(np.abs(later.section_y[:6] - whole.section_y[1:7])) < 1e-8
    # and the forcing phase at the start matters: the same state imposed at 0 differs
    moved = record_trajectory(pr, y_t0, 0.0, 5, 16)
    assert np.max(np.abs(moved.section_y[1] - later.section_y[0])) > 1e-3


def test_section_stays_at_multiples_of_T():
    pr = Problem(get_system("duffing", 2), DUFFING)
    T = pr.period
    traj = record_trajectory(pr, [1.0, 0.0, -1.0, 0.0], 0.6 * T, 3, 8)
    assert np.allclose(traj.section_t, [T, 2 * T, 3 * T, 4 * T])
    assert traj.t[0] == pytest.approx(0.6 * T)


SCENE = """
[system]
model = "duffing"
[coupling]
d = 10.5
phi = 5.28
c_c = 10.0
[analysis]
kind = "stability"
{grid}
[initial_conditions]
kind = "random"
box = {{x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}}
n = 24
seed = 5
{t0}
[catalogue]
grid = 6
random = 30
"""


def test_t0_as_grid_axis(tmp_path):
    scene = parse_scene(SCENE.format(grid='[grid]\nt0 = [0.0, "T/4", "T/2", "3*T/4"]',
                                     t0=""), "t0grid.toml")
    ds = run_sweep(scene, tmp_path / "g.h5", workers=1)
    T = 2 * np.pi / 1.3
    assert np.allclose(ds["t0"].values, [0, T / 4, T / 2, 3 * T / 4])
    assert ds["label"].sizes["t0"] == 4 and ds.attrs["t0_mode"] == "grid"
    # the start at t0 = 0 equals a plain run of the same samples
    plain = parse_scene(SCENE.format(grid="", t0=""), "plain.toml")
    base = run_sweep(plain, tmp_path / "p.h5", workers=1)
    assert np.array_equal(ds["label"].isel(t0=0).values, base["label"].isel(t0=0).values)


def test_random_t0_is_stored_per_sample_and_labels_match_direct_runs(tmp_path):
    scene = parse_scene(SCENE.format(grid="", t0='t0 = "random"'), "rand.toml")
    ds = run_sweep(scene, tmp_path / "r.h5", workers=1)
    T = 2 * np.pi / 1.3
    t0 = ds["sample_t0"].values
    assert t0.shape == (24,) and np.all((t0 >= 0) & (t0 < T)) and np.unique(t0).size == 24
    assert ds.attrs["t0_mode"] == "random"
    catalogues, names = prepare_catalogues(scene)
    pr = Problem(scene.system, scene.values, scene.integrator)
    for i in (0, 7, 23):
        cls = classify_state(pr, ds["initial_state"].values[i], t0[i])
        if cls.status == 0:
            label = label_orbit(catalogues[catalogue_key(scene.system, scene.values)],
                                cls.orbit, cls.impacting)
            assert ds["label_name"].values[list(ds["label_code"].values).index(
                int(ds["label"].values.ravel()[i]))] == label.name


def test_sample_states_helper_unaffected_by_t0():
    a = sample_states({"x": (-1, 1), "v": (-1, 1)}, 3, 5, 0)
    assert a.shape == (14, 2)
