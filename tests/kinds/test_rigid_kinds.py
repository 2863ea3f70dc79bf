"""The sweep kinds on a rigid stop (issue 33, item 3): the impact oscillator

    x'' + 2 zeta x' + x = cos(w t),   a wall at x = sigma, restitution r = 0.8,

as a chain of one body with a rigid wall stop, through basins, bifurcation, dcrit and
lyapunov; the expectations are independent of softimpact: the linear response's amplitude
A (grazing at sigma = A), Shaw and Holmes's closed-form period-1 impacting orbit and scipy's
event integration (``tests/analysis/rigid_reference.py``). Continuation:
``test_rigid_continuation.py``. Lyapunov without saltation is refused in one line.
"""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.results import describe, format_summary
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep

from ..analysis.rigid_reference import amplitude, period_one, scipy_sections

ZETA, R = 0.05, 0.8


def oscillator(w: float, sigma: float, analysis: str) -> str:
    return f"""\
[system]
model = "chain"
bodies = 1
c = {2 * ZETA}
k1 = 1.0
F = 1.0
phi = "pi/2"
w = {w!r}

[[stop]]
body = 1
wall = {float(sigma)!r}
side = "right"
law = "rigid"
r = {R}

{analysis}"""


def linear_section(w: float) -> np.ndarray:
    """The non-impacting orbit x = A cos(w t - psi) at t = 0: (x, v)."""
    A, psi = amplitude(ZETA, w), np.arctan2(2.0 * ZETA * w, 1.0 - w * w)
    return np.array([A * np.cos(psi), A * w * np.sin(psi)])


def test_a_rigid_basin_plane_splits_between_the_free_and_the_impacting_orbit(tmp_path):
    """Above resonance (w = 1.2) a wall at 1.2 A leaves the linear orbit free and adds a
    stable period-1 impacting orbit (the closed form's fast one, v- = 2.92): the plane is
    shared by exactly these two, each at its independent section point, and a point of
    each basin integrated by scipy ends on its label's orbit."""
    w = 1.2
    sigma = 1.2 * amplitude(ZETA, w)
    scene = parse_scene(oscillator(w, sigma, """[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "v1"]
ranges = [[-3.0, 2.0], [-4.0, 4.0]]
resolution = [6, 6]
"""))
    ds = run_sweep(scene, tmp_path / "b.h5", workers=1)
    names = dict(zip(ds["label_code"].values.tolist(), ds["label_name"].values.tolist(),
                     strict=True))
    labels = ds["label"].values.squeeze()
    assert sorted(names[int(c)] for c in np.unique(labels)) == ["L1^1", "impacting P1"]
    impacting = max(period_one(ZETA, w, sigma, R), key=lambda o: o[1])
    assert impacting[1] > 0.0
    expected = {"L1^1": linear_section(w), "impacting P1": impacting[2]}
    points = ds["attractor_points"].values.squeeze()
    for i, code in enumerate(ds["label_code"].values):
        assert np.max(np.abs(points[i] - expected[names[int(code)]])) < 1e-5
    x1, v1 = ds["x1"].values, ds["v1"].values
    for code in np.unique(labels):
        i, j = np.argwhere(labels == code)[0]
        sections, _ = scipy_sections(ZETA, w, sigma, R, [x1[i], v1[j]], 80, rtol=1e-10,
                                     atol=1e-12)
        assert np.max(np.abs(sections[-1] - expected[names[int(code)]])) < 1e-4
    assert "impacting P1" in format_summary(describe(ds), ds)


def test_a_bifurcation_along_the_wall_locates_grazing_at_the_amplitude():
    """w = 0.8: the free orbit is destroyed where the wall meets its amplitude A = 2.7116
    (grazing), and the branch is then impacting."""
    w = 0.8
    A = amplitude(ZETA, w)
    ds = run_scene(parse_scene(oscillator(w, 3.0, """[analysis]
kind = "bifurcation"
parameter = "stop.1.wall"
start = 3.0
stop = 2.5
step = 0.05
""")))
    assert float(ds["destroyed_at"].values[0]) == pytest.approx(A, abs=1e-6)
    walls = ds["step"].values
    assert np.array_equal(ds["impacting"].values[0] == 1, walls < A)
    assert np.array_equal(ds["alive"].values[0] == 1, walls > A)
    # past grazing the closed form's period-1 impacting orbit is unstable (the grazing
    # bifurcation's period adding): the branch lands on a period-2 impacting orbit, whose
    # two section points scipy's event integration finds too
    assert list(ds["period"].values[0, walls < A]) == [2] * int(np.sum(walls < A))
    for j in (-3, -1):
        sections, _ = scipy_sections(ZETA, w, walls[j], R, [0.0, 0.0], 200, rtol=1e-10,
                                     atol=1e-12)
        np.testing.assert_allclose(np.sort(ds["section_x"].values[0, j, :2, 0]),
                                   np.sort(sections[-2:, 0]), atol=1e-5)


def test_a_bifurcation_along_w_is_destroyed_where_the_amplitude_reaches_the_wall():
    """Wall at 2: A(w) = 2 at w* = 0.7079 (the root of (1 - w^2)^2 + (2 zeta w)^2 = 1/4);
    rising in w from 0.6, the free orbit lives below w* and impacts above it."""
    roots = np.roots([1.0, 4 * ZETA ** 2 - 2.0, 0.75])  # in w^2
    w_star = float(np.sqrt(min(r.real for r in roots if r.real > 0.0)))
    ds = run_scene(parse_scene(oscillator(0.6, 2.0, """[analysis]
kind = "bifurcation"
parameter = "w"
start = 0.6
stop = 0.8
step = 0.025
""")))
    ws = ds["step"].values
    assert np.array_equal(ds["alive"].values[0] == 1, ws < w_star)
    assert np.array_equal(ds["impacting"].values[0] == 1, ws > w_star)
    assert w_star < float(ds["destroyed_at"].values[0]) < w_star + 0.025


def test_dcrit_of_a_rigid_wall_is_the_free_orbits_amplitude():
    ds = run_scene(parse_scene(oscillator(0.8, 1.0, """[analysis]
kind = "dcrit"
samples = 128
[grid]
w = [0.8, 1.2]
""")))
    expected = [amplitude(ZETA, w) for w in (0.8, 1.2)]
    np.testing.assert_allclose(ds["d_crit"].values[0, 0], expected, rtol=1e-8)


def test_lyapunov_exponents_of_a_chaotic_rigid_orbit():
    """w = 2.8, wall at 0 (chaotic: a positive exponent), 400 periods from (-0.5, 0): the
    exponents' sum is the damping's -2 zeta plus ln det S = 2 ln r per impact (the
    switches the kernel crossed are the impacts), and the spectrum is (+, -)."""
    ds = run_scene(parse_scene(oscillator(2.8, 0.0, """[analysis]
kind = "lyapunov"
start = "state"
state = [-0.5, 0.0]
periods = 400
transient = 0
segments = 4
""")))
    exponents, errors = ds["exponent"].values[0], ds["exponent_stderr"].values[0]
    assert int(ds["status"].values[0]) == 0
    assert exponents[0] - 3.0 * errors[0] > 0.0 > exponents[1]
    duration = 400 * 2.0 * np.pi / 2.8
    impacts = int(ds["switches"].values[0])
    assert impacts > 400
    expected = -2.0 * ZETA * duration + 2.0 * np.log(R) * impacts
    assert float(exponents.sum()) * duration == pytest.approx(expected, abs=1e-5)


def test_lyapunov_without_saltation_on_a_rigid_stop_is_refused_in_one_line(tmp_path):
    """``saltation = false`` (a comparison) cannot leave out an impact's saltation matrix
    (the impact loop applies it): one line naming the key, exit 2, nothing written."""
    path = tmp_path / "s.toml"
    out = tmp_path / "out.h5"
    path.write_text(oscillator(2.8, 0.0, f"""[analysis]
kind = "lyapunov"
start = "state"
state = [-0.5, 0.0]
saltation = false
[output]
path = "{out}"
"""))
    with pytest.raises(ConfigError) as err:
        parse_scene(path.read_text(), "s.toml")
    message = str(err.value)
    assert "[analysis] saltation" in message and "rigid stop" in message
    assert "\n" not in message
    result = CliRunner().invoke(main, ["sweep", str(path)])
    assert result.exit_code == 2
    assert len(result.output.strip().splitlines()) == 1 and "saltation" in result.output
    assert not out.exists()


@pytest.mark.parametrize("w, wall, impacts", [(1.2, 1.2, 1), (0.65, 0.3, 2)])
def test_a_rigid_impacting_orbit_counts_its_impacts_per_period(tmp_path, w, wall, impacts):
    """The sweep kinds count a rigid orbit's impacts as they count a soft stop's contact
    onsets (``contacts``: per orbit of one period, here): Shaw and Holmes's period-1
    single-impact orbit (w = 1.2, wall 1.2 A) has 1, a period-1 orbit hitting twice
    (w = 0.65, wall 0.3 A) has 2, as scipy's event integration counts over one period
    after 300; both are named "impacting P1"."""
    sigma = wall * amplitude(ZETA, w)
    start = [0.0, 0.0]
    if impacts == 1:  # the closed form's stable (fast) orbit
        start = max(period_one(ZETA, w, sigma, R), key=lambda o: o[1])[2].tolist()
    scene = parse_scene(oscillator(w, sigma, f"""[analysis]
kind = "basins"
[initial_conditions]
kind = "list"
states = [{start}]
"""))
    ds = run_sweep(scene, tmp_path / "b.h5", workers=1)
    names = dict(zip(ds["label_code"].values.tolist(), ds["label_name"].values.tolist(),
                     strict=True))
    assert names[int(ds["label"].values.ravel()[0])] == "impacting P1"
    assert int(ds["period"].values.ravel()[0]) == 1
    assert int(ds["contacts"].values.ravel()[0]) == impacts
    _, before = scipy_sections(ZETA, w, sigma, R, start, 300, rtol=1e-10, atol=1e-12)
    sections, after = scipy_sections(ZETA, w, sigma, R, start, 301, rtol=1e-10, atol=1e-12)
    assert np.max(np.abs(sections[-1] - sections[-2])) < 1e-6  # settled on a period-1 orbit
    assert after - before == impacts
