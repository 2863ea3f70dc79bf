"""The work-precision benchmark's core on a tiny case: errors must fall as the settings
tighten (they would not if a setting were dropped on the way to the kernels, or if switch
location stopped working), and the basin reference's cache key must follow its settings."""

import importlib
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).parents[1] / "benchmarks"


@pytest.fixture(scope="module")
def bench():
    sys.path.insert(0, str(BENCHMARKS))
    try:
        yield importlib.import_module("bench_precision")
    finally:
        sys.path.remove(str(BENCHMARKS))


def errors(result, family):
    return [r["error"] for r in result["rows"] if r["family"] == family]


def test_error_falls_with_tighter_settings_through_contacts(bench):
    case = next(c for c in bench.TRAJECTORY_CASES if c.key == "b")  # impacting Duffing pair
    settings = ([bench.rk4(n) for n in (180, 720, 2880)] + [bench.rk4(720, located=False)]
                + [bench.adaptive("dopri5", r) for r in (1e-4, 1e-6, 1e-8)])
    result = bench.run_trajectory_case(case, settings, periods=12, min_time=0.0,
                                       floor_check=False)
    assert result["contacts"] >= 5  # the case does go through contacts
    rk4 = errors(result, bench.FAMILIES[0])
    dopri5 = errors(result, bench.FAMILIES[2])
    # order 4 with located switches: 4x the steps gives ~256x less error; ask for 30x
    assert rk4[0] > 30 * rk4[1] > 30 * 30 * rk4[2]
    # each 100x tighter rtol: at least 10x less error
    assert dopri5[0] > 10 * dopri5[1] > 100 * dopri5[2]
    # the plain scheme (mode frozen per stage) is first order through contacts
    plain = errors(result, bench.FAMILIES[1])[0]
    assert plain > 1e3 * rk4[1]
    assert all(r["wall"] > 0 for r in result["rows"])


def test_reference_cache_key_follows_its_settings(bench):
    from dataclasses import replace

    scene = bench.scene_at(10)
    names = ("L1^1 R1-0^1",)
    ref = bench.reference_settings(scene.integrator)
    assert (ref.method, ref.rtol, ref.convergence_tol) == ("dopri5", 1e-11, 1e-9)
    assert ref.capture_tol == 0.0  # the reference converges by itself
    key = bench.reference_key(scene, names, ref)
    assert key == bench.reference_key(bench.scene_at(10), names, ref)
    assert key != bench.reference_key(bench.scene_at(12), names, ref)
    assert key != bench.reference_key(scene, names, replace(ref, rtol=1e-10))
    assert key != bench.reference_key(scene, names + ("L1^2 R1-0^2",), ref)


@pytest.fixture(scope="module")
def contestants():
    sys.path.insert(0, str(BENCHMARKS))
    try:
        yield (importlib.import_module("scipy_contestant"),
               importlib.import_module("study_method"),
               importlib.import_module("where_time_goes"))
    finally:
        sys.path.remove(str(BENCHMARKS))


def test_contestants_name_a_start_on_an_orbit_as_the_catalogue_does(contestants, tmp_path):
    """The scipy loop and the study's method (the basin benchmark's contestants 2 and 3)
    must name a start on a known orbit with that orbit's name, or the agreement column
    measures the contestants' bookkeeping, not their integration."""
    scipy_contestant, study_method, _ = contestants
    from softimpact_cli.config.axes import catalogue_key
    from softimpact_cli.sweep.runner import prepare_catalogues

    scene = __import__("_common").scene_at(2)
    catalogues, _ = prepare_catalogues(scene)
    catalogue = catalogues[catalogue_key(scene.system, scene.values)]
    combination = catalogue.combinations[-1]
    start = combination.orbit[0]  # a joint section point of the orbit, at t = 0 mod T
    tol = scene.analysis.label_tol
    got = scipy_contestant.scipy_label(start, dict(scene.values), "DOP853", catalogue, tol,
                                       transient=5, record=12)
    assert got == combination.name
    assert study_method.StudyMethod.of(scene, catalogue).label(start) == combination.name


def test_stage_clock_times_the_catalogue_of_a_sweep(contestants, tmp_path):
    import time

    from softimpact_cli.sweep.runner import run_sweep

    _, _, where = contestants
    clock = where.StageClock()
    t = time.perf_counter()
    run_sweep(__import__("_common").scene_at(2), tmp_path / "s.h5", workers=1, echo=clock)
    total = time.perf_counter() - t
    assert 0.0 < clock.catalogue_s() < total


@pytest.mark.parametrize("plane", ["9", "12a"])
def test_scipy_contestant_names_bilinear_orbits_as_the_catalogue_does(contestants, plane):
    """The targets benchmark runs the scipy loop on the bilinear planes too (one body for
    figure 9, the pair for 12(a), d = 10: no contact): a start on a catalogue orbit gets that
    orbit's name."""
    scipy_contestant, _, _ = contestants
    from softimpact_cli.sweep.runner import prepare_catalogues

    scene = __import__("_common").plane_scene(plane, 2)
    catalogues, _ = prepare_catalogues(scene)
    catalogue = next(iter(catalogues.values()))
    if scene.system.bodies == 2:
        entry = next(c for c in catalogue.combinations if c.left.stable and c.right.stable)
        start = entry.orbit[0]
    else:
        entry = next(a for a in catalogue.attractors if a.stable)
        start = entry.points[0]
    got = scipy_contestant.scipy_label(start, dict(scene.values), "DOP853", catalogue,
                                       scene.analysis.label_tol, transient=5, record=40,
                                       model=scene.system.model, bodies=scene.system.bodies)
    assert got == entry.name


def test_plane_scenes_are_the_figures_panels():
    common = __import__("_common")
    assert common.plane_scene("12a", 3).values["d"] == 10.0
    assert common.plane_scene("12a", 3).grid.size == 1  # one panel, not the figure's four
    assert common.plane_scene("14a", 3).values["k_c"] == 8.0
    scene = common.plane_scene("9", 5, {"rtol": 1e-6})
    assert scene.initial_conditions.count == 25 and scene.integrator.rtol == 1e-6
    assert scene.initial_conditions.t0 == 0.0


def test_the_never_seen_chains_are_valid_scenes():
    """bench_chain_targets' never-seen models (body count, kinks, stops and laws drawn):
    each a scene the reader takes, with the structure its summary states."""
    import numpy as np

    from softimpact_cli.kinds.scene import parse_scene

    sys.path.insert(0, str(BENCHMARKS))
    try:
        targets = importlib.import_module("bench_chain_targets")
    finally:
        sys.path.remove(str(BENCHMARKS))
    for seed in range(12):
        text, summary = targets.fresh_scene(np.random.default_rng(seed))
        model = parse_scene(text, f"<fresh {seed}>").system.extra["chain"]
        assert summary.startswith(f"{model.bodies} bodies, {len(model.kinks)} kink(s), "
                                  f"{len(model.stops)} stops")
        assert model.stops[-1].wall and 2 <= model.bodies <= 7


def test_the_rigid_target_compares_like_with_like(tmp_path):
    """bench_rigid_targets: the soft wall's c_c gives the rigid wall's restitution (a linear
    spring-dashpot released at zero overlap: r = exp(-zeta_c pi / sqrt(1 - zeta_c^2))), and
    a 3 x 3 plane's run writes its three rows, the outcomes of both stops agreeing."""
    import numpy as np

    sys.path.insert(0, str(BENCHMARKS))
    try:
        targets = importlib.import_module("bench_rigid_targets")
    finally:
        sys.path.remove(str(BENCHMARKS))
    z = targets.ZETA_C
    assert np.exp(-z * np.pi / np.sqrt(1.0 - z * z)) == pytest.approx(targets.R, rel=1e-12)
    assert "c_c = " in targets.scene_text("paper") and "r = 0.8" in targets.scene_text("rigid")
    out = tmp_path / "rigid.md"
    assert targets.main(["--size", "3", "--out", str(out)]) == 0
    rows = [line for line in out.read_text().splitlines() if line.startswith("| impact")]
    assert len(rows) == 3 and "(exact)" in rows[1] and "(auto)" in rows[2]
    assert all("agree on 100.0% of starts" in row for row in rows[1:])
