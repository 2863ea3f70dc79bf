"""Capture near known stable orbits: the same labels as full convergence, fewer periods,
never a capture by an orbit that does not exist at this d or while touching the stop."""

from dataclasses import replace

import numpy as np
import pytest

from softimpact_cli.analysis.engine import KnownOrbits, Problem, classify_state
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.chunks import run_chunk
from softimpact_cli.sweep.runner import prepare_catalogues, sweep_context

SCENE = """
[system]
model = "{model}"
[coupling]
d = {d}
phi = {phi}
[integrator]
cell_size = 0.0  # capture alone against full convergence
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[{lo}, {hi}], [{lo}, {hi}]]
resolution = [{res}, {res}]
[catalogue]
grid = 8
random = 40
seed = 3
[output]
path = "unused.h5"
"""


def context(model="duffing", d=6.0, phi=0.0, lo=-12.0, hi=12.0, res=8, **integrator):
    scene = parse_scene(SCENE.format(model=model, d=d, phi=phi, lo=lo, hi=hi, res=res),
                        "capture.toml")
    if integrator:
        scene = replace(scene, integrator=replace(scene.integrator, **integrator))
    catalogues, names = prepare_catalogues(scene)
    return sweep_context(scene, catalogues, names, None), scene


def labels(ctx, **integrator):
    ctx = replace(ctx, integrator=replace(ctx.integrator, **integrator))
    n = ctx.states.shape[0]
    return run_chunk(ctx, 0, n)


@pytest.mark.parametrize("model, d, phi, lo, hi", [
    ("duffing", 6.0, 0.0, -12.0, 12.0),     # figure 6(d): two solutions
    ("duffing", 22.0, 0.0, -12.0, 12.0),    # figure 6(a): all four
    ("bilinear", 10.0, np.pi, -2.5, 2.5),   # figure 12(a): nine states, fine basins
])
def test_capture_gives_the_labels_of_full_convergence_in_fewer_periods(model, d, phi, lo, hi):
    ctx, _ = context(model, d, phi, lo, hi)
    fast = labels(ctx)
    full = labels(ctx, capture_tol=0.0)
    assert np.array_equal(fast["label"], full["label"])
    assert fast["captured"].sum() > 0.5 * fast["captured"].size
    assert not full["captured"].any()
    captured = fast["captured"] == 1
    assert np.all(fast["periods_used"][captured] < full["periods_used"][captured])
    assert np.all(fast["max_penetration"][captured] < 0)  # a known orbit is contact-free


def test_only_combinations_clear_of_the_stop_are_known():
    ctx, scene = context(d=6.0)  # phi = 0: d_crit is 0 (equal orbits) or 11.27
    entries = ctx.known[ctx.catalogue_key(scene.values)]
    d_crits = sorted(g for _, g in entries)
    assert len(entries) == 4 and d_crits[0] == pytest.approx(0.0, abs=1e-8)
    assert d_crits[-1] > 11.0
    known = ctx.known_orbits({**scene.values, "d": 6.0})
    assert known.points.shape[0] == 2  # the two combinations with d_crit = 0 < 6
    assert np.all(known.max_g < -5.9)
    assert ctx.known_orbits({**scene.values, "d": 30.0}).points.shape[0] == 4
    # a gap within the safety margin of a critical distance admits no capture by it
    margin_d = d_crits[-1] + 0.5
    assert ctx.known_orbits({**scene.values, "d": margin_d}).points.shape[0] == 2
    assert replace(ctx, known=None).known_orbits(scene.values) is None


def test_a_wrong_known_orbit_never_captures_a_trajectory_that_is_not_on_it():
    ctx, scene = context(d=6.0)
    problem = Problem(scene.system, scene.values, scene.integrator)
    true = classify_state(problem, [1.0, 0.0, -1.0, 0.0])
    shifted = true.orbit + 0.5  # an orbit the trajectory never approaches
    bogus = KnownOrbits.from_orbits([shifted], [-1.0], 1e-2, 3, 4)
    cls = classify_state(problem, [1.0, 0.0, -1.0, 0.0], 0.0, bogus)
    assert cls.captured == -1
    assert cls.periods_used == true.periods_used
    assert np.allclose(cls.orbit, true.orbit)


def test_capture_returns_the_known_orbit_in_time_order_ending_at_the_current_phase():
    ctx, scene = context(d=22.0)
    problem = Problem(scene.system, scene.values, scene.integrator)
    start = np.array([2.0, 0.0, -3.0, 0.0])
    full = classify_state(problem, start)
    known = ctx.known_orbits(dict(scene.values))
    cls = classify_state(problem, start, 0.0, known)
    assert cls.captured >= 0 and cls.period == full.period
    assert cls.periods_used < full.periods_used
    assert np.max(np.abs(cls.orbit - full.orbit)) < 1e-5


def test_contact_blocks_capture():
    """With a stop that the known orbit would cross (d below its d_crit), a trajectory
    near that orbit keeps touching and must not be captured by it."""
    ctx, scene = context(d=22.0)
    d_crit, orbit = max((g, o) for o, g in ctx.known[ctx.catalogue_key(scene.values)])
    problem = Problem(scene.system, {**scene.values, "d": d_crit - 1.0}, scene.integrator)
    known = KnownOrbits.from_orbits([orbit], [1.0], 1e-2, 3, 4)
    cls = classify_state(problem, orbit[0], 0.0, known)
    assert cls.captured == -1


def test_results_say_how_each_trajectory_was_classified_and_by_which_method(tmp_path):
    from softimpact_cli.kinds.results import describe
    from softimpact_cli.sweep import run_sweep

    scene = parse_scene(SCENE.format(model="duffing", d=6.0, phi=0.0, lo=-12.0, hi=12.0,
                                     res=6), "capture.toml")
    ds = run_sweep(scene, tmp_path / "r.h5", workers=1)
    summary = describe(ds)
    by = summary["classified_by"]
    assert sum(by.values()) == 36 and by["known orbit"] > 0 and by["recurrence cells"] == 0
    assert by["known orbit"] == int((ds["captured"] == 1).sum())
    steps = summary["steps_by_method"]
    assert steps["explicit"] == int(ds["steps"].sum()) > 0 and steps["stiff"] == 0
