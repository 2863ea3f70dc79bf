"""Kind "design" on a chain: the scene form (bounds over the chain's parameters by name),
its refusals in one line, and a small design run whole: its pick lies where only the
target survives by integration of the coupled chain, and the result is described and
drawn (the region itself against brute force: tests/analysis/test_chain_design.py)."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli import plot
from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.design_settings import with_target
from softimpact_cli.kinds.results import describe, format_summary
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.report.info import design_summary
from softimpact_cli.store.catalogues import scene_catalogue

TARGET = "B1:P1^1 B2:P1-0^1 B3:P1-0^1"
DESIGN = f"""\
[system]
model = "chain"
bodies = 3
k2 = 0.05
F = 1.5
w = 1.4
phi = [0.0, "5*pi/8", "5*pi/4"]

[[stop]]
between = [1, 2]
d = 2.0

[[stop]]
between = [2, 3]
d = 2.0

[analysis]
kind = "design"
target = "{TARGET}"
bounds = {{ "stop.1.d" = [1.0, 10.0], "stop.2.d" = [1.0, 10.0], "stop.1.k_c" = [4.0, 12.0] }}
candidates = 4
screen_n = 6
refine = 2
shock_directions = 0

[initial_conditions]
kind = "random"
n = 8
seed = 3
box = {{x1 = [-3, 3], v1 = [-3, 3], x2 = [-3, 3], v2 = [-3, 3], x3 = [-3, 3], v3 = [-3, 3]}}

[catalogue]
grid = 4
random = 0
box = {{x = [-4.0, 4.0], v = [-4.0, 4.0]}}
"""


@pytest.mark.parametrize("change, message", [
    (('"stop.1.k_c" = [4.0, 12.0]', '"stop.3.d" = [1.0, 2.0]'),
     "[analysis] bounds.stop.3.d: unknown parameter; allowed: w, m.1"),
    (('"stop.1.d" = [1.0, 10.0]', '"stop.1.d" = [0.0, 10.0]'),
     "[analysis] bounds.stop.1.d: must be above 0 (margins are relative to the gap)"),
    (("candidates = 4", "candidates = 4\nphi_points = 24"),
     "[analysis] phi_points: is a pair's phase grid; a chain's region grid takes "
     "grid_points"),
    ((f'target = "{TARGET}"', 'target = "impacting P1"'),
     "[analysis] target: 'impacting P1' is not a non-impacting product"),
], ids=["unknown-axis", "gap-at-zero", "phi-points", "impacting-target"])
def test_bad_design_keys_on_a_chain_are_refused_in_one_line(change, message):
    old, new = change
    with pytest.raises(ConfigError) as err:
        parse_scene(DESIGN.replace(old, new), "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_too_many_body_grid_points_are_refused():
    scene = DESIGN.replace('"stop.1.k_c" = [4.0, 12.0]',
                           '"phi.2" = [0.0, "pi"], "F.3" = [1.0, 2.0]')
    with pytest.raises(ConfigError, match=r"grid_points: 30\^2 body grid points \(one "
                                          r"catalogue each\); at most 400"):
        parse_scene(scene.replace("candidates = 4", "candidates = 4\ngrid_points = 30"))


def test_a_random_start_time_is_refused_when_the_design_moves_w():
    scene = DESIGN.replace('"stop.1.k_c" = [4.0, 12.0]', 'w = [1.3, 1.5]').replace(
        "seed = 3\n", 'seed = 3\nt0 = "random"\n')
    with pytest.raises(ConfigError, match=r"\[initial_conditions\] t0: cannot be set while "
                                          r"w is swept"):
        parse_scene(scene, "s.toml")


def test_a_phase_axis_reads_multiples_of_pi():
    scene = parse_scene(DESIGN.replace('"stop.1.k_c" = [4.0, 12.0]', 'phi.3 = ["pi", "2*pi"]'))
    assert scene.analysis.bounds["phi.3"] == pytest.approx((np.pi, 2 * np.pi))
    assert tuple(scene.analysis.bounds) == ("stop.1.d", "stop.2.d", "phi.3")


def survivors_by_integration(scene, values: dict) -> set[str]:
    """The catalogue's products that never touch a stop on the coupled chain at values."""
    problem = Problem(scene.system, values, scene.integrator)
    out = set()
    for p in scene_catalogue(scene).products:
        y = record_trajectory(problem, p.orbit[0], 0.0, 2 * p.orbit.shape[0], 2048).y
        if (y[:, 0] - y[:, 2] < values["stop.1.d"]).all() and \
                (y[:, 2] - y[:, 4] < values["stop.2.d"]).all():
            out.add(p.name)
    return out


@pytest.fixture(scope="module")
def chain_design(tmp_path_factory):
    path = tmp_path_factory.mktemp("design") / "d.h5"
    scene = parse_scene(DESIGN + f'[output]\npath = "{path}"\n', "design.toml")
    return scene, run_scene(scene, workers=1)


def test_the_pick_keeps_only_the_target_by_integration(chain_design):
    scene, ds = chain_design
    best = design_summary(ds)["best"]
    assert set(best) >= {"stop.1.d", "stop.2.d", "stop.1.k_c"}
    values = {**scene.values, **{a: best[a] for a in ("stop.1.d", "stop.2.d", "stop.1.k_c")}}
    assert survivors_by_integration(scene, values) == {TARGET}
    assert best["target_exists"] is True and len(best["multipliers"]) == 6
    assert all(abs(complex(*z)) < 1.0 for z in best["multipliers"])  # stable bodies
    # screened + runners-up + best inside the bounds, ranked, each with the samples asked
    role = [str(r) for r in ds["role"].values]
    assert role[0] == "best" and role.count("perturbed") == 6
    assert ds["n_samples"].values[0] == 8
    assert ds["map_target"].dims == ("map_y", "map_x")
    assert ds.attrs["map_x_axis"] == "stop.1.d" and ds.attrs["map_y_axis"] == "stop.2.d"
    # the figure's map, at the cell nearest the pick: only the target survives there
    i = int(np.argmin(np.abs(ds["map_x"].values - best["stop.1.d"])))
    j = int(np.argmin(np.abs(ds["map_y"].values - best["stop.2.d"])))
    assert ds["map_survivors"].values[j, i] == 1 and ds["map_target"].values[j, i] == 1
    assert (ds["map_survivors"].values[0] >= 0).all() and ds["map_target"].values.sum() > 1


def test_the_chain_design_is_described_and_drawn(chain_design):
    _, ds = chain_design
    text = format_summary(describe(ds), ds)
    assert f"design for {TARGET}" in text and "stop.1.k_c" in text
    assert "stop.2.d +1 step: stop.2.d = " in text
    assert len(plot.design(ds).axes) >= 3


def test_target_override_and_a_target_that_is_no_product(tmp_path):
    scene = parse_scene(DESIGN + f'[output]\npath = "{tmp_path / "x.h5"}"\n', "s.toml")
    other = with_target(scene, "B1:P1^3 B2:P1-0^1 B3:P1-0^1")
    assert other.analysis.target == "B1:P1^3 B2:P1-0^1 B3:P1-0^1"
    with pytest.raises(ConfigError, match="is not a product of the chain's catalogue"):
        run_scene(other, workers=1)
    assert not (tmp_path / "x.h5").exists()
