"""[grid] axes: every model parameter can be swept by the kinds that take a grid, the
axes are defined once (``config.axes``), and a bad axis is one line naming the allowed."""

import subprocess
import sys

import pytest

from softimpact_cli.config import COUPLING_AXES, GRID_AXES, ConfigError
from softimpact_cli.config.axes import allowed_axes, every_axis, parameter_axes
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.systems import get_system

PAIR = """
[system]
model = "{model}"
[analysis]
kind = "{kind}"
[grid]
{grid}
[initial_conditions]
kind = "random"
box = {{x1 = [-1, 1], v1 = [-1, 1], x2 = [-1, 1], v2 = [-1, 1]}}
n = 4
"""


def test_the_axes_are_the_models_parameters():
    assert GRID_AXES == COUPLING_AXES + ("t0",) == ("d", "phi", "k_c", "c_c", "t0")
    assert parameter_axes(get_system("duffing", 1)) == ("c", "k1", "k2", "F", "w")
    assert parameter_axes(get_system("bilinear", 2)) == ("c", "k1", "k2", "F", "w", "d1",
                                                         "exponent")
    assert allowed_axes(get_system("duffing", 2)) == ("c", "k1", "k2", "F", "w", "exponent",
                                                      "d", "phi", "k_c", "c_c", "t0")
    assert every_axis() == ("c", "k1", "k2", "F", "w", "d1", "exponent", "d", "phi", "k_c",
                            "c_c", "t0")


@pytest.mark.parametrize("kind", ["basins", "stability", "map"])
@pytest.mark.parametrize("model, axis", [("duffing", "c"), ("duffing", "k1"),
                                         ("duffing", "k2"), ("duffing", "F"),
                                         ("duffing", "w"), ("bilinear", "d1")])
def test_every_model_parameter_is_a_grid_axis(kind, model, axis):
    text = PAIR.format(model=model, kind=kind, grid=f"{axis} = [0.5, 0.7]\nd = [6.0, 8.0]")
    if kind == "basins":
        text = text.replace('kind = "random"', 'kind = "plane"')
        text = text.split("box =")[0] + "resolution = [2, 2]\nranges = [[-1, 1], [-1, 1]]\n"
    grid = parse_scene(text, "s.toml").grid
    assert grid.parameters == (axis,) and grid.dims == (axis,) + GRID_AXES
    assert grid.shape == (2, 2, 1, 1, 1, 1) and grid.point(1)[axis] == 0.5
    assert grid.point(2) == {axis: 0.7, "d": 6.0, "phi": 0.0, "k_c": 8.0, "c_c": 10.0,
                             "t0": 0.0}


def test_a_scene_without_parameter_axes_keeps_its_grid():
    grid = parse_scene(PAIR.format(model="duffing", kind="stability", grid="d = [6.0, 8.0]"),
                       "s.toml").grid
    assert grid.parameters == () and grid.dims == GRID_AXES and grid.swept == ("d",)


def test_the_stop_laws_exponent_is_an_axis_where_the_law_has_it():
    text = PAIR.format(model="duffing", kind="stability", grid="exponent = [1.5, 2.0]")
    hertz = text + '[coupling]\nlaw = "hunt-crossley"\n'
    assert parse_scene(hertz, "s.toml").grid.axes["exponent"] == (1.5, 2.0)
    with pytest.raises(ConfigError, match=r"s.toml: \[grid\] exponent: is not a parameter of "
                                          r"this scene \(its stop law 'paper' has no "
                                          r"exponent\)"):
        parse_scene(text, "s.toml")
    with pytest.raises(ConfigError, match=r"\[grid\] exponent: must be in"):
        parse_scene(hertz.replace("[1.5, 2.0]", "[0.5]"), "s.toml")


def test_one_body_sweeps_its_parameters_but_has_no_coupling():
    text = PAIR.format(model="duffing", kind="stability", grid="w = [1.0, 1.2]").replace(
        '[system]\n', '[system]\nbodies = 1\n').replace(
        "box = {x1 = [-1, 1], v1 = [-1, 1], x2 = [-1, 1], v2 = [-1, 1]}",
        "box = {x = [-1, 1], v = [-1, 1]}")
    assert parse_scene(text, "s.toml").grid.parameters == ("w",)
    with pytest.raises(ConfigError) as err:
        parse_scene(text.replace("w = [1.0, 1.2]", "d = [1.0, 1.2]"), "s.toml")
    assert str(err.value) == ("s.toml: [grid] d: unknown key; allowed: F, c, k1, k2, t0, w")


@pytest.mark.parametrize("grid, ic, message", [
    ("w = [0.5, 1.0]\nt0 = [0.0, 1.0]", "", "[grid] t0: cannot be set while w is swept"),
    ("w = [0.5, 1.0]", 't0 = "T/4"\n', "[initial_conditions] t0: cannot be set while w is "
                                       "swept"),
    ("w = [0.5, 1.0]", 't0 = "random"\n', "[initial_conditions] t0: cannot be set while w"),
    ("w = [0.0, 1.0]", "", "[grid] w: must be"),
    ("F = [1.0, \"pi\"]", "", "[grid] F: must be finite numbers, got 'pi'"),
])
def test_a_swept_w_keeps_every_start_at_its_section_time(grid, ic, message):
    text = PAIR.format(model="duffing", kind="stability", grid=grid) + ic
    with pytest.raises(ConfigError) as err:
        parse_scene(text, "s.toml")
    assert str(err.value).startswith(f"s.toml: {message}")


def test_w_swept_with_t0_zero_is_accepted():
    text = PAIR.format(model="duffing", kind="stability", grid="w = [0.5, 1.0]") + "t0 = 0\n"
    assert parse_scene(text, "s.toml").grid.axes["w"] == (0.5, 1.0)


def test_exact_flow_only_where_every_point_is_piecewise_linear():
    """A bilinear scene defaults to its exact flow over its body parameters; a stop law
    that is not linear runs on auto; asked for exact there, one line names the point."""
    base = PAIR.format(model="bilinear", kind="stability", grid="F = [0.4, 0.6]")
    assert parse_scene(base, "s.toml").integrator.method == "exact"
    hertz = (PAIR.format(model="bilinear", kind="stability", grid="exponent = [1.0, 1.5]")
             + '[coupling]\nlaw = "hunt-crossley"\n')
    assert parse_scene(hertz, "s.toml").integrator.method == "auto"
    with pytest.raises(ConfigError, match=r'\[integrator\] method = "exact": .* at the grid '
                                          r"point exponent = 1; use \"auto\""):
        parse_scene(hertz + '[integrator]\nmethod = "exact"\n', "s.toml")


def test_panels_take_parameter_axes_too():
    text = PAIR.format(model="duffing", kind="stability",
                       grid='panels = [{F = 0.5, d = 6.0}, {d = 8.0}]')
    grid = parse_scene(text, "s.toml").grid
    assert grid.parameters == ("F",) and grid.axes["F"] == (0.5, 1.0)
    assert grid.point(1)["F"] == 1.0 and grid.point(0)["d"] == 6.0


def test_cli_bad_axis_is_one_line_exit_2_naming_the_allowed_axes(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(PAIR.format(model="duffing", kind="stability", grid="omega = [1, 2]"))
    out = tmp_path / "s.h5"
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene), "-o",
                           str(out)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == [
        f"softimpact: error: {scene}: [grid] omega: unknown key; allowed: F, c, c_c, d, "
        "exponent, k1, k2, k_c, phi, t0, w"]
    assert not out.exists()


def test_the_docs_list_the_axes_from_their_definition():
    from pathlib import Path

    page = Path(__file__).parents[2] / "docs" / "howto" / "sweeps.md"  # the sweeps how-to
    assert f"`{', '.join(every_axis())}`" in " ".join(page.read_text().split())
