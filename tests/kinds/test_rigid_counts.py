"""A rigid stop's counters in every sweep result, and its labels' impacts per period
(issue 33, items 2 and 3): the impact oscillator of ``test_rigid_kinds`` swept on a plane
and on a list of starts; the counts are checked against scipy's event integration
(``tests/analysis/rigid_reference.py``), independent of softimpact. Soft results and
presets keep their variables and their ``info`` text."""

from __future__ import annotations

import json

import numpy as np
import pytest

from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.kinds.results import describe, format_summary
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store import open_result
from softimpact_cli.store.sweep_store import PART, RunIdentity, SweepStore
from softimpact_cli.sweep import run_sweep

from ..analysis.rigid_reference import amplitude, period_one, scipy_sections
from .test_rigid_kinds import ZETA, R, oscillator

RIGID = ("rigid_impacts", "rigid_chatter_sequences", "rigid_sticking_phases")
PLANE = """[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "v1"]
ranges = [[-3.0, 2.0], [-4.0, 4.0]]
resolution = [6, 6]
"""


def plane_scene(out):
    """w = 1.2, a wall at 1.2 A: the free orbit and the period-1 single-impact orbit."""
    w = 1.2
    return parse_scene(oscillator(w, 1.2 * amplitude(ZETA, w), PLANE), str(out) + ".toml")


class Killed(Exception):
    """Stands in for a kill between the last chunk and the assembly."""


@pytest.fixture(scope="module")
def plane(tmp_path_factory):
    out = tmp_path_factory.mktemp("plane") / "p.h5"
    return run_sweep(plane_scene(out), out, workers=1, chunk_size=6)


def test_each_trajectory_counts_the_impacts_scipy_counts_over_its_integration(plane):
    """Every start of the plane carries its impact count from t = 0 to its
    classification (periods_used periods): scipy's event integration over as many periods
    counts the same impacts. No chatter, no sticking at this restitution and wall."""
    w = 1.2
    sigma = 1.2 * amplitude(ZETA, w)
    for name in RIGID:
        assert plane[name].dims == plane["label"].dims
    impacts = plane["rigid_impacts"].values.squeeze()
    used = plane["periods_used"].values.squeeze()
    x1, v1 = plane["x1"].values, plane["v1"].values
    assert impacts.max() > 0 and (impacts == 0).any()  # transients hit; some never do
    for i, j in [(0, 0), (2, 3), (5, 5), (3, 1)]:
        _, expected = scipy_sections(ZETA, w, sigma, R, [x1[i], v1[j]], int(used[i, j]),
                                     rtol=1e-10, atol=1e-12)
        assert int(impacts[i, j]) == expected
    assert plane["rigid_chatter_sequences"].values.sum() == 0
    assert plane["rigid_sticking_phases"].values.sum() == 0


def test_info_sums_the_counters_and_names_the_impacts_per_period(plane):
    """``info``: one line of totals, and each impacting label's impacts per period, on
    the result's line and on each grid point's share line."""
    summary = describe(plane)
    assert summary["rigid_counts"] == {
        "impacts": int(plane["rigid_impacts"].values.sum()), "chatter_sequences": 0,
        "sticking_phases": 0}
    assert summary["impacts_per_period"] == {"impacting P1": [1.0]}
    text = format_summary(summary, plane)
    total = int(plane["rigid_impacts"].values.sum())
    assert [line for line in text.splitlines() if line.startswith("rigid_counts")] == [
        f"{'rigid_counts':28s} impacts {total}, chatter_sequences 0, sticking_phases 0"]
    assert f"{'impacts_per_period':28s} impacting P1 1" in text
    assert "; impacts per period: impacting P1 1" in text


def test_a_two_impact_orbit_says_two_impacts_per_period(tmp_path):
    """w = 0.65, wall 0.3 A: a period-1 orbit hitting twice (scipy counts 2 a period)."""
    w = 0.65
    scene = parse_scene(oscillator(w, 0.3 * amplitude(ZETA, w), """[analysis]
kind = "basins"
[initial_conditions]
kind = "list"
states = [[0.0, 0.0]]
"""))
    ds = run_sweep(scene, tmp_path / "b.h5", workers=1)
    assert describe(ds)["impacts_per_period"] == {"impacting P1": [2.0]}
    assert "; impacts per period: impacting P1 2" in format_summary(describe(ds), ds)


def test_the_stable_period_one_orbit_itself_counts_one_impact_a_period(tmp_path):
    """Started on Shaw and Holmes's closed-form orbit, a trajectory hits once a period
    for as many periods as it integrates."""
    w = 1.2
    sigma = 1.2 * amplitude(ZETA, w)
    start = max(period_one(ZETA, w, sigma, R), key=lambda o: o[1])[2].tolist()
    scene = parse_scene(oscillator(w, sigma, f"""[analysis]
kind = "basins"
[initial_conditions]
kind = "list"
states = [{start}]
"""))
    ds = run_sweep(scene, tmp_path / "b.h5", workers=1)
    used = int(ds["periods_used"].values.ravel()[0])
    assert int(ds["rigid_impacts"].values.ravel()[0]) == used


def test_resume_keeps_the_counters_and_redoes_a_chunk_without_them(plane, tmp_path,
                                                                   monkeypatch):
    """The counters travel through the chunk files: a run killed before its assembly
    resumes to the same counters; a chunk file written without them (an older version)
    is named and recomputed."""
    out = tmp_path / "r.h5"

    def killed(self, result):
        raise Killed

    with monkeypatch.context() as m:
        m.setattr(SweepStore, "finish", killed)
        with pytest.raises(Killed):
            run_sweep(plane_scene(out), out, workers=1, chunk_size=6)
    store = SweepStore(out)
    last = max(store.done())  # chunks hold whole blocks of recurrence cells: maybe one
    with np.load(store.parts / PART.format(last)) as data:
        assert "rigid_impacts" in data.files
        meta = json.loads(data["meta"].tobytes().decode())
    # that chunk rewritten without the counters, its checksum valid
    identity = RunIdentity(meta["scene_sha256"], meta["chunk_size"], meta["n_total"])
    chunk, _ = store.read_chunk(last, identity)
    for name in RIGID:
        del chunk[name]
    store.write_chunk(last, chunk, identity, float(meta["session_started"]))
    said = []
    ds = run_sweep(plane_scene(out), out, workers=1, resume=True, echo=said.append)
    assert f"chunk {last}: incomplete arrays; recomputing it" in "\n".join(said)
    for name in RIGID + ("label",):
        np.testing.assert_array_equal(ds[name].values, plane[name].values)
        np.testing.assert_array_equal(open_result(out)[name].values, plane[name].values)


def test_a_soft_chain_has_no_rigid_variable_and_no_impacts_per_period(tmp_path):
    """The same oscillator with a soft wall: no rigid_* variable, no rigid line."""
    w = 1.2
    text = oscillator(w, 1.2 * amplitude(ZETA, w), PLANE).replace(
        'law = "rigid"\nr = 0.8', 'law = "paper"\nk_c = 100.0\nc_c = 0.5')
    text = text.replace("resolution = [6, 6]", "resolution = [3, 3]")
    ds = run_sweep(parse_scene(text), tmp_path / "s.h5", workers=1)
    assert not any(name.startswith("rigid_") for name in ds.data_vars)
    summary = describe(ds)
    assert "rigid_counts" not in summary and "impacts_per_period" not in summary
    assert "impacts per period" not in format_summary(summary, ds)


def test_a_chattering_start_counts_its_chatter_and_sticking_as_its_recorded_trajectory(
        tmp_path):
    """The issue's chattering case (w = 2.5, wall 0.9 A): starts that chatter and stick
    carry the counts the recorded trajectory (``record_trajectory``, the trajectory kind's)
    finds over as many periods, with the same settings."""
    w = 2.5
    sigma = 0.9 * amplitude(ZETA, w)
    starts = [[float(sigma) - 1e-6, 0.0], [0.0, 0.0], [-0.5, 1.0]]
    scene = parse_scene(oscillator(w, sigma, f"""[analysis]
kind = "basins"
[initial_conditions]
kind = "list"
states = {starts}
"""))
    ds = run_sweep(scene, tmp_path / "c.h5", workers=1)
    problem = Problem(scene.system, scene.values, scene.integrator)
    used = ds["periods_used"].values.ravel()
    for i, state in enumerate(starts):
        traj = record_trajectory(problem, state, 0.0, int(used[i]), 4)
        for name in ("impacts", "chatter_sequences", "sticking_phases"):
            assert int(ds[f"rigid_{name}"].values.ravel()[i]) == traj.impacts[name]
    assert ds["rigid_chatter_sequences"].values.sum() >= 1
    assert ds["rigid_sticking_phases"].values.sum() >= 1
