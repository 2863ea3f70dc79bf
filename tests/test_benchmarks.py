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
