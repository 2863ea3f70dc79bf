"""Kinds on a chain: dcrit ([grid] one parameter by its name) and bifurcation (any
parameter); refusals in one line, the results' info tables and figures (the numbers
themselves: tests/analysis/test_chain_dcrit.py and test_chain_bifurcation.py)."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli import plot
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.results import describe, format_summary
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene

CHAIN = """\
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
body = 3
wall = -3.0
side = "left"

[analysis]
kind = "dcrit"
samples = 128

[catalogue]
grid = 3
random = 0
"""


def test_the_grid_names_a_parameter_dotted_or_quoted():
    dotted = parse_scene(CHAIN + '[grid]\nphi.3 = {start = 0.0, stop = "pi", num = 3}\n')
    quoted = parse_scene(CHAIN + '[grid]\n"phi.3" = [0.0, "pi/2", "pi"]\n')
    for scene in (dotted, quoted):
        assert scene.analysis.axis == "phi.3"
        np.testing.assert_allclose(scene.analysis.phis, [0.0, np.pi / 2, np.pi])
    assert parse_scene(CHAIN).analysis.axis == "w"  # no [grid]: the scene's point


@pytest.mark.parametrize("grid, message", [
    ('"stop.1.d" = [1.0, 2.0]', "[grid] stop.1.d: a stop's own parameters do not change a "
                                "non-impacting solution"),
    ("F.7 = [1.0]", "[grid] F.7: is not a parameter dcrit can sweep"),
    ("F.1 = [1.0]\nw = [1.2]", "[grid]: dcrit sweeps one parameter; got 2 (F.1, w)"),
    ("m.2 = [0.0]", "[grid] m.2: must be > 0, got 0.0"),
])
def test_bad_axes_are_refused_in_one_line(grid, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(CHAIN + f"[grid]\n{grid}\n", "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_traces_are_a_pairs():
    with pytest.raises(ConfigError, match="traces: x1 - x2 traces are a pair's"):
        parse_scene(CHAIN.replace("samples = 128", 'traces = ["pi"]'))


def test_a_chain_dcrit_runs_and_is_described_and_drawn(tmp_path):
    scene = parse_scene(CHAIN + '[grid]\n"F.2" = [1.0, 1.5]\n'
                        + f'[output]\npath = "{tmp_path / "d.h5"}"\n')
    ds = run_scene(scene)
    assert ds["d_crit"].dims == ("stop", "combination", "point")
    assert ds.sizes["stop"] == 2 and list(ds["point"].values) == [1.0, 1.5]
    assert ds.sizes["combination"] >= 1 and np.isfinite(ds["d_crit"].values).any()
    text = format_summary(describe(ds), ds)
    assert "F.2=1" in text and "stop 2: B1:P1^1" in text
    fig = plot.dcrit(ds)
    assert len(fig.axes) == 2


BIFURCATION = CHAIN.replace('kind = "dcrit"\nsamples = 128',
                            'kind = "bifurcation"\nparameter = "stop.1.d"\nstart = 12.0\n'
                            'stop = 8.0\nstep = 1.0').replace("d = 2.0", "d = 12.0")


@pytest.mark.parametrize("change, message", [
    ('parameter = "stop.3.d"', "[analysis] parameter: must be one of"),
    ('parameter = "m.2"\nstart = -1.0', "[analysis] start: must be > 0 (a value of m.2), "
                                         "got -1.0"),
])
def test_a_chain_bifurcation_refuses_in_one_line(change, message):
    scene = BIFURCATION.replace('parameter = "stop.1.d"\nstart = 12.0', change)
    with pytest.raises(ConfigError) as err:
        parse_scene(scene, "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_chain_bifurcation_runs_and_is_described_and_drawn(tmp_path):
    scene = parse_scene(BIFURCATION + f'[output]\npath = "{tmp_path / "b.h5"}"\n')
    assert scene.analysis.parameter == "stop.1.d"
    ds = run_scene(scene)
    assert ds["section_x"].dims == ("branch", "step", "point", "body")
    assert list(ds["step"].values) == [12.0, 11.0, 10.0, 9.0, 8.0]
    text = format_summary(describe(ds), ds)
    assert "stop.1.d" in text and "B1:P1^1" in text
    assert "destroyed at stop.1.d" in text and "impacting for stop.1.d in" in text
    assert "destroyed at d" not in text  # the followed parameter is named, not a gap d
    assert len(plot.bifurcation(ds).axes) == 3
    with pytest.raises(ConfigError, match="branches: 'L1\\^1' is not a non-impacting product"):
        run_scene(parse_scene(BIFURCATION.replace('step = 1.0', 'step = 1.0\nbranches = ["L1^1"]')
                              + f'[output]\npath = "{tmp_path / "c.h5"}"\n'))


CATALOGUE = CHAIN.replace('kind = "dcrit"\nsamples = 128', 'kind = "catalogue"\ngrid = 4\n'
                          'random = 0\nbox = {x = [-4.0, 4.0], v = [-4.0, 4.0]}'
                          ).replace("[catalogue]\ngrid = 3\nrandom = 0\n", "")


def test_a_chain_catalogue_runs_and_is_described_and_drawn(tmp_path):
    """Each body's attractors, their products and the stops' verdicts, through the scene:
    the products are every body's attractors combined (2 x 2 x 2 here), and the table says
    which survive the gap 2 and the left wall at -3 (none: every product's x1 - x2 exceeds
    2; tests/analysis/test_chain_catalogue.py checks the verdicts by integration)."""
    scene = parse_scene(CATALOGUE + f'[output]\npath = "{tmp_path / "c.h5"}"\n')
    ds = run_scene(scene)
    bodies = [int(b) for b in ds["attractor_body"].values]
    assert bodies == [1, 1, 2, 2, 3, 3] and ds.sizes["combination"] == 8
    assert ds["combination_critical"].dims == ("combination", "stop")
    assert (ds["combination_critical"].values[:, 0] > 2.0).all()
    text = format_summary(describe(ds), ds)
    assert "B3:P1^2" in text and "B1:P1^2 B2:P1-0^1 B3:P1-0^2" in text
    assert "surviving (0): none" in text
    fig = plot.catalogue(ds)
    assert len(fig.axes) == 9  # the attractors, then one panel per product
    assert len(fig.axes[1].lines) == 6  # three bodies: x(t) and section points each


FATAL = """\
[system]
model = "chain"
bodies = 2
k2 = 0.05
F = 1.5
w = 1.4
phi = [0.0, "pi"]

[[stop]]
between = [1, 2]
d = 6.5

[catalogue]
grid = 4
random = 0
box = {x = [-4.0, 4.0], v = [-4.0, 4.0]}

[analysis]
kind = "fatal_shock"
solution = "L1^1 R1-0^1"
phases = 1
directions = 3
scan = 3
max_shock = 6.0
tol = 0.1
"""


def test_a_chains_fatal_shock_lands_where_an_independent_run_ends(tmp_path):
    """Two Duffing bodies, three products surviving d = 6.5: each direction's fatal kick,
    integrated here for 300 periods, ends on the product the result names (nearest
    catalogue orbit), and the unkicked orbit stays on the solution."""
    from softimpact_cli.analysis.engine import Problem, record_trajectory
    from softimpact_cli.store.catalogues import scene_catalogue

    scene = parse_scene(FATAL + f'[output]\npath = "{tmp_path / "f.h5"}"\n')
    ds = run_scene(scene)
    orbits = scene_catalogue(scene).orbits
    problem = Problem(scene.system, scene.values, scene.integrator)

    def ends_on(state, t0):
        end = record_trajectory(problem, state, t0, 300, 1).section_y[-1]
        return min(orbits, key=lambda n: float(np.min(np.max(np.abs(orbits[n] - end),
                                                             axis=1))))

    t0, orbit = float(ds["shock_time"].values[0]), ds["orbit_state"].values[0]
    assert ends_on(orbit, t0) == "L1^1 R1-0^1"
    fatal = 0
    for j, r in enumerate(ds["shock_magnitude"].values[0]):
        if np.isfinite(r):
            kicked = orbit + r * ds["direction"].values[j]
            assert ends_on(kicked, t0) == str(ds["shock_destination"].values[0, j])
            fatal += 1
    assert fatal >= 1
    assert "mfs" in describe(ds) and len(plot.fatal_shock(ds).axes) >= 1
