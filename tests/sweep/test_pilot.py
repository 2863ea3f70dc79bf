"""The tolerance pilot: when it runs, what sample it draws, what it chooses on a smooth
plane and on a fractal one, and that the result records and resumes the choice."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import softimpact_cli as si
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.report.verification import pilot_line
from softimpact_cli.sweep import pilot
from softimpact_cli.sweep import verification as v
from softimpact_cli.sweep.check import sample_indices
from tests.sweep.test_verification import PLANE, sweep_with_verification_killed

# figure 6(d)'s smooth Duffing plane at 32 x 32 = 1024 >= 50 x 20 trajectories
SMOOTH = (PLANE.replace("resolution = [16, 16]", "resolution = [32, 32]")
          + "[verification]\npilot_sample = 20\n")

# figure 12(a)'s fractal bilinear plane (d = 10, phi = pi), where looser tolerances move
# 2-16% of the labels between the two phase-shifted copies of the period-2 orbit
FRACTAL = """
[system]
model = "bilinear"
w = 0.86
F = 0.518
[coupling]
d = 10.0
phi = "pi"
k_c = 8.0
c_c = 10.0
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-2.5, 2.5], [-2.5, 2.5]]
resolution = [32, 32]
t0 = 0.0
[verification]
pilot_sample = 20
"""


def scene(text: str, **integrator):
    extra = "".join(f"{k} = {v!r}\n" for k, v in integrator.items())
    return parse_scene(text + ("[integrator]\n" + extra if extra else ""), "<test>")


def test_the_pilot_runs_only_where_it_can_pay_and_the_tolerance_is_not_the_users():
    assert pilot.skip_reason(scene(SMOOTH), 1024) is None
    assert "rtol set by hand" in pilot.skip_reason(scene(SMOOTH, rtol=1e-8), 1024)
    assert "atol set by hand" in pilot.skip_reason(scene(SMOOTH, atol=1e-10), 1024)
    assert "rk4" in pilot.skip_reason(scene(SMOOTH, method="rk4"), 1024)
    assert "999 trajectories < 50 x pilot_sample (20)" in pilot.skip_reason(
        scene(SMOOTH), 999)
    off = parse_scene(SMOOTH + "pilot = false\n", "<test>")
    assert pilot.skip_reason(off, 10**6) == "[verification] pilot = false"


@given(total=st.integers(2, 3000), pilot_n=st.integers(1, 500), verify_n=st.integers(1, 500),
       seed=st.integers(0, 2**32))
def test_pilot_sample_is_disjoint_from_the_verification_sample(total, pilot_n, verify_n,
                                                                seed):
    verify_n = min(verify_n, total - 1)
    picks = pilot.pilot_indices(total, pilot_n, verify_n, seed)
    taken = sample_indices(total, verify_n, seed)
    assert picks.size == min(pilot_n, total - verify_n)
    assert np.all(np.diff(picks) > 0) and picks.min() >= 0 and picks.max() < total
    assert not np.intersect1d(picks, taken).size
    np.testing.assert_array_equal(picks, pilot.pilot_indices(total, pilot_n, verify_n, seed))


def test_candidate_keeps_the_atol_to_rtol_ratio():
    s = scene(SMOOTH).integrator
    c = pilot.candidate(s, 1e-5)
    assert c.rtol == 1e-5 and c.atol == pytest.approx(s.atol * 1e3)
    assert dataclasses.replace(c, rtol=s.rtol, atol=s.atol) == s


def test_smooth_plane_runs_at_the_loosest_candidate_with_the_same_labels(tmp_path):
    ds = si.sweep(SMOOTH, tmp_path / "p.h5", workers=1)
    assert ds.attrs["pilot_status"] == "chose rtol 1e-05"
    assert ds.attrs["pilot_rtol"] == 1e-5 and ds.attrs["pilot_atol"] == pytest.approx(1e-7)
    assert "# tolerance pilot: rtol 1e-05, atol 1e-07" in ds.attrs["scene_text"]
    assert "rtol 1e-05" in ds.attrs["verify_run_settings"]  # verified as it ran
    stored = si.open_result(tmp_path / "p.h5")
    assert stored.attrs["pilot_rtol"] == 1e-5
    # the same labels as a sweep told that tolerance by hand
    by_hand = si.run(SMOOTH + "[integrator]\nrtol = 1e-5\natol = 1e-7\n", workers=1,
                     verify=False)
    np.testing.assert_array_equal(ds["label"].values, by_hand["label"].values)
    # and the same labels as the default tolerance on this smooth plane
    default = si.run(SMOOTH, workers=1, verify=False)
    np.testing.assert_array_equal(ds["label"].values, default["label"].values)
    line = pilot_line(ds.attrs)
    assert line.startswith("tolerance pilot: chose rtol 1e-05 (20 trajectories against "
                           "rtol 1e-10; rtol 1e-05: 0 of 20 disagree")


def test_fractal_plane_keeps_the_default_when_every_candidate_disagrees():
    # on auto (a bilinear scene that names no method runs on its exact flow: no pilot)
    assert pilot.skip_reason(scene(FRACTAL), 10**6) == "the exact flow has no tolerance"
    chosen, attrs = pilot.choose_tolerance(scene(FRACTAL, method="auto"))
    assert attrs["pilot_status"] == "kept rtol 1e-08 (no looser candidate agreed)"
    assert chosen == scene(FRACTAL, method="auto")
    trials = pilot.json.loads(attrs["pilot_trials"])
    assert [t["rtol"] for t in trials] == [1e-5, 1e-6, 1e-7]
    assert all(t["disagreements"] > 0 for t in trials)


def test_no_verify_runs_no_pilot_and_a_skipped_pilot_says_why(tmp_path):
    ds = si.run(SMOOTH, workers=1, verify=False)
    assert "pilot_status" not in ds.attrs
    small = SMOOTH.replace("resolution = [32, 32]", "resolution = [8, 8]")
    ds = si.run(small, workers=1)
    assert ds.attrs["pilot_status"].startswith("not run (64 trajectories < 50 x")
    assert "pilot_rtol" not in ds.attrs


def test_a_resumed_verification_judges_the_tolerance_the_sweep_ran_at(tmp_path,
                                                                      monkeypatch):
    out = tmp_path / "k.h5"
    kept = sweep_with_verification_killed(SMOOTH, out, monkeypatch)
    assert kept.attrs["verify_status"] == v.PENDING and kept.attrs["pilot_rtol"] == 1e-5
    ds = si.sweep(SMOOTH, out, workers=1, resume=True)
    assert "rtol 1e-05" in ds.attrs["verify_run_settings"]
    assert ds.attrs["pilot_rtol"] == 1e-5


def test_scene_as_run_rebuilds_the_choice_from_the_attributes():
    sc = scene(SMOOTH)
    assert pilot.scene_as_run(sc, {}) is sc
    assert pilot.scene_as_run(sc, {"pilot_rtol": 1e-8, "pilot_atol": 1e-10}) is sc
    ran = pilot.scene_as_run(sc, {"pilot_rtol": 1e-6, "pilot_atol": 1e-8})
    assert (ran.integrator.rtol, ran.integrator.atol) == (1e-6, 1e-8)
    assert ran.text.endswith("# tolerance pilot: rtol 1e-06, atol 1e-08\n")


def test_an_existing_result_is_refused_before_the_pilot_spends_anything(tmp_path,
                                                                         monkeypatch):
    out = tmp_path / "p.h5"
    si.sweep(SMOOTH.replace("resolution = [32, 32]", "resolution = [4, 4]"), out, workers=1)

    def no_pilot(*args, **kwargs):
        raise AssertionError("the pilot ran before the refusal")

    monkeypatch.setattr(v, "choose_tolerance", no_pilot)  # where the sweep calls it
    with pytest.raises(si.ConfigError, match="result exists; pass --overwrite"):
        si.sweep(SMOOTH, out, workers=1)
