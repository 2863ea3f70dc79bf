"""Basins and stability on a chain: labels from the chain's catalogue (its products), a
plane of any two state coordinates (by name or index, the others fixed), random starts in
the 2n-dimensional box; the result file, info and the figures.

Independent expectation: every start is integrated again here for many periods, with no
classification, and its final section state is matched to the nearest product orbit by
distance alone; a non-impacting label must be that product, and a surviving one (the
stops' critical values, tests/analysis/test_chain_catalogue.py).
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli import plot
from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.results import describe, format_summary
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep

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
d = 5.0

[[stop]]
between = [2, 3]
d = 6.0

[[stop]]
body = 3
wall = -6.0
side = "left"

[catalogue]
grid = 4
random = 0
box = {x = [-4.0, 4.0], v = [-4.0, 4.0]}
"""

PLANE = CHAIN + """
[analysis]
kind = "basins"

[initial_conditions]
kind = "plane"
axes = [0, "v2"]
ranges = [[-4.0, 4.0], [-4.0, 4.0]]
resolution = [5, 5]
fixed = {x2 = 0.5, x3 = -1.0}
"""

RANDOM = CHAIN + """
[analysis]
kind = "stability"

[grid]
stop.1.d = [4.0, 5.0]

[initial_conditions]
kind = "random"
n = 8
box = {x1 = [-1, 1], v1 = [-1, 1], x2 = [-1, 1], v2 = [-1, 1], x3 = [-1, 1], v3 = [-1, 1]}
"""

PERIODS = 300  # c = 0.05: transients decay as exp(-0.025 t), e^-34 after 300 T


def nearest_product(ds, problem: Problem, state: np.ndarray) -> tuple[str, float]:
    """(name, distance) of the product orbit nearest to where ``state`` ends up after
    PERIODS periods on the chain (every section point of each orbit)."""
    end = record_trajectory(problem, state, 0.0, PERIODS, 1).section_y[-1]
    names = [str(n) for n in ds["combination_name"].values]
    orbits = ds["combination_orbit"].values
    best = min(((float(np.nanmin(np.max(np.abs(orbit - end), axis=1))), name)
                for name, orbit in zip(names, orbits, strict=True)))
    return best[1], best[0]


def check_labels(ds, scene, flat_labels, states) -> int:
    """Each non-impacting label against the independent integration; returns how many."""
    names = dict(zip(ds["label_code"].values.tolist(),
                     (str(n) for n in ds["label_name"].values), strict=True))
    products = [str(n) for n in ds["combination_name"].values]
    crit = ds["combination_critical"].values  # gaps 1, 2 above it; the left wall below
    v = scene.values
    ok = (crit[:, 0] < v["stop.1.d"]) & (crit[:, 1] < v["stop.2.d"]) \
        & (crit[:, 2] > v["stop.3.wall"])
    surviving = {n for n, good in zip(products, ok, strict=True) if good}
    checked = 0
    for code, state in zip(flat_labels, states, strict=True):
        name = names[int(code)]
        if name not in products:
            continue
        found, distance = nearest_product(ds, Problem(scene.system, scene.values,
                                                      scene.integrator), state)
        assert distance < 1e-5 and found == name
        assert name in surviving
        checked += 1
    return checked


def test_a_plane_of_two_chain_coordinates_is_labelled_by_the_products(tmp_path):
    scene = parse_scene(PLANE)
    assert scene.initial_conditions.axes == ("x1", "v2")  # 0: x1, by its index
    ds = run_sweep(scene, tmp_path / "b.h5", workers=1)
    assert ds["label"].dims[-2:] == ("x1", "v2")
    states = scene.initial_conditions.array()
    assert np.all(states[:, 2] == 0.5) and np.all(states[:, 4] == -1.0)
    assert np.all(states[:, [1, 5]] == 0.0)  # v1, v3: not fixed, at 0
    assert check_labels(ds, scene, ds["label"].values.ravel(), states) >= 20
    text = format_summary(describe(ds), ds)
    assert "surviving (4)" in text and "t0=0:" in text and "d=0" not in text
    fig = plot.basins(ds)
    titles = " ".join([a.get_title() for a in fig.axes]
                      + [fig._suptitle.get_text() if fig._suptitle else ""])
    assert "chain of 3 bodies" in titles.replace("\n", " ")
    assert "d = 0" not in titles  # no pair's coupling on a chain


def test_random_starts_fill_the_chains_box_at_each_gap(tmp_path):
    scene = parse_scene(RANDOM)
    assert scene.grid.swept == ("stop.1.d",)
    ds = run_sweep(scene, tmp_path / "s.h5", workers=1)
    states = ds["initial_state"].values
    assert states.shape == (8, 6) and np.all(np.abs(states) <= 1.0)
    assert np.ptp(states, axis=0).min() > 0.5  # every coordinate drawn
    assert list(ds["stop.1.d"].values) == [4.0, 5.0]
    checked = 0
    for i, gap in enumerate((4.0, 5.0)):
        at = parse_scene(RANDOM.replace("d = 5.0", f"d = {gap}"))
        labels = ds["label"].isel({"stop.1.d": i}).values.ravel()
        checked += check_labels(ds, at, labels, states)
    assert checked >= 8  # most of the 16 starts end on a product
    text = format_summary(describe(ds), ds)
    assert "stop.1.d=4, t0=0 (n = 8)" in text
    assert "chain of 3 bodies" in plot.stability(ds).axes[0].get_title()


@pytest.mark.parametrize("initial, message", [
    ('axes = [0, 6]', "axes: must be two different state variables out of x1, v1, x2, v2, "
                      "x3, v3 (or their indices 0 to 5)"),
    ('axes = ["x1", "x1"]', "axes: must be two different state variables"),
])
def test_bad_plane_axes_are_refused_in_one_line(initial, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(PLANE.replace('axes = [0, "v2"]', initial), "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_chain_grid_names_its_parameters():
    with pytest.raises(ConfigError) as err:
        parse_scene(RANDOM.replace("stop.1.d = [4.0, 5.0]", "d = [4.0, 5.0]"), "s.toml")
    assert "s.toml: [grid] d: unknown key; allowed: F.1, F.2" in str(err.value)
    assert "stop.1.d" in str(err.value) and "\n" not in str(err.value)


PAIR_MAP = """\
[system]
model = "chain"
bodies = 2
k2 = 0.05
F = 1.5
w = 1.4
phi = [0.0, "pi/2"]

[[stop]]
between = [1, 2]
d = 4.0

[catalogue]
grid = 4
random = 0
box = {x = [-4.0, 4.0], v = [-4.0, 4.0]}

[analysis]
kind = "map"

[grid]
stop.1.d = [2.0, 4.0, 6.5]
phi.2 = ["pi/2", "pi"]

[initial_conditions]
kind = "plane"
ranges = [[-4.0, 4.0], [-4.0, 4.0]]
resolution = [3, 3]
"""


def test_a_two_body_chain_map_predicts_the_duffing_pairs_counts(tmp_path):
    """Over (stop.1.d, phi.2) a chain of two Duffing bodies predicts, at every point, the
    number of the preset pair's combinations whose own critical distance d_crit(phi)
    lies below d (analysis.critical_distance on the preset); what the starts find
    without contact never exceeds it."""
    from softimpact_cli.analysis.catalogue import body_catalogue, body_problem
    from softimpact_cli.analysis.critical_distance import critical_distances
    from softimpact_cli.config import IntegratorSettings
    from softimpact_cli.systems import get_system

    scene = parse_scene(PAIR_MAP)
    ds = run_sweep(scene, tmp_path / "m.h5", workers=1)
    preset = get_system("duffing", 2)
    values = {"c": 0.05, "k1": 1.0, "k2": 0.05, "F": 1.5, "w": 1.4, "d": 4.0, "phi": 0.0,
              "k_c": 8.0, "c_c": 10.0}
    left, _ = body_catalogue(body_problem(preset, values, IntegratorSettings()),
                             np.array(np.meshgrid(np.linspace(-4, 4, 4), np.linspace(-4, 4, 4),
                                                  indexing="ij")).reshape(2, -1).T)
    phis = np.array([np.pi / 2, np.pi])
    d_crit = critical_distances(preset, values, left, phis)["d_crit"].values  # (combo, phi)
    predicted = ds["predicted_count"].squeeze(drop=True).transpose("stop.1.d", "phi.2").values
    for i, d in enumerate((2.0, 4.0, 6.5)):
        for j in range(2):
            assert predicted[i, j] == int(np.sum(d_crit[:, j] < d))
    assert predicted.min() < predicted.max()  # the gaps span the critical distances
    found = ds["found_nonimpacting"].squeeze(drop=True).transpose("stop.1.d", "phi.2").values
    assert np.all(found <= predicted)
    assert len(plot.map(ds).axes) == 6  # three panels and their colour bars


def test_fractality_measures_a_chains_plane_as_its_basins(tmp_path):
    """kind = "fractality" on a chain sweeps the same plane as kind = "basins": its label
    shares are the basins result's, and it counts that result's basins."""
    from softimpact_cli.kinds.run import run_scene

    plane = parse_scene(PLANE)
    basins = run_sweep(plane, tmp_path / "b.h5", workers=1)
    measured = run_scene(parse_scene(PLANE.replace(
        'kind = "basins"', 'kind = "fractality"\nradii = [1, 2]\nbox_sizes = [2]')),
                         workers=1)
    names = [str(n) for n in basins["label_name"].values]
    codes = basins["label"].values.ravel()
    shares = {n: float(np.mean(codes == c)) for n, c in
              zip(names, basins["label_code"].values, strict=True)}
    got = dict(zip((str(n) for n in measured["label_name"].values),
                   measured["label_share"].values[0].tolist(), strict=True))
    assert got == pytest.approx(shares)
    assert int(measured["n_basins"].values[0]) == sum(v > 0 for v in shares.values())


TIPPING = PAIR_MAP.replace('kind = "map"', 'kind = "tipping"').replace(
    'stop.1.d = [2.0, 4.0, 6.5]\nphi.2 = ["pi/2", "pi"]',
    'panels = [{stop.1.d = 6.5}, {stop.1.d = 4.0}]').replace('"pi/2"]', '"pi"]')


def test_a_chains_tipping_sends_the_products_the_new_gap_touches_elsewhere(tmp_path):
    """Two Duffing bodies (phi.2 = pi) as the gap closes from 6.5 to 4: a product whose
    critical value lies below 4 stays itself; one above it touches the stop, so its
    orbit is sent elsewhere; the tipping shares of each row sum to one."""
    scene = parse_scene(TIPPING)
    assert scene.grid.swept == ("stop.1.d",)
    ds = run_sweep(scene, tmp_path / "t.h5", workers=1)
    crit = dict(zip((str(n) for n in ds["combination_name"].values),
                    ds["combination_critical"].values[:, 0], strict=True))
    checked = 0
    for i, name in enumerate(ds["tip_solution"].values):
        goes = {str(d) for d in ds["tip_destination"].values[i] if str(d)}
        if crit[str(name)] < 4.0:
            assert goes == {str(name)}
        else:
            assert str(name) not in goes
        checked += 1
    assert checked >= 2 and "stop.1.d = 6.5" in ds.attrs["tip_before"]
    assert "d = 0" not in ds.attrs["tip_before"].replace("stop.1.d", "")
    rows = ds["tip_probability"].sum("tip_to").values
    assert np.allclose(rows[np.isfinite(rows) & (rows > 0)], 1.0)
    assert len(plot.tipping(ds).axes) >= 3  # before, after, the tipping matrix


GAPS = """\
[system]
model = "chain"
bodies = 2
k2 = 0.05
F = 1.5
w = 1.4
phi = [0.0, "5*pi/8"]

[[stop]]
between = [1, 2]
d = 5.0

[catalogue]
grid = 4
random = 0
box = {x = [-4.0, 4.0], v = [-4.0, 4.0]}

[analysis]
kind = "stability"

[initial_conditions]
kind = "random"
n = 10
box = {x1 = [-4, 4], v1 = [-4, 4], x2 = [-4, 4], v2 = [-4, 4]}
"""


def test_each_gap_of_a_chain_sweep_stores_its_own_surviving_products(tmp_path):
    """Over stop.1.d = [4, 6.5] the products' critical gaps (about 2.95, 4.72, 5.92,
    9.27) leave one surviving product at 4 and three at 6.5: each point stores its own
    (the scene at that gap alone says the same), its labels are that scene's, and a
    non-impacting label is one of that point's survivors."""
    ds = run_sweep(parse_scene(GAPS + "\n[grid]\nstop.1.d = [4.0, 6.5]\n"),
                   tmp_path / "s.h5", workers=1)
    survives = ds["combination_survives"].squeeze(drop=True)
    assert survives.dims == ("stop.1.d", "combination")
    names = [str(n) for n in ds["combination_name"].values]
    table = dict(zip(ds["label_code"].values.tolist(),
                     (str(n) for n in ds["label_name"].values), strict=True))
    survivors = []
    for i, gap in enumerate((4.0, 6.5)):
        alone = run_sweep(parse_scene(GAPS.replace("d = 5.0", f"d = {gap}")),
                          tmp_path / f"a{i}.h5", workers=1)
        expected = alone["combination_survives"].values.ravel()
        np.testing.assert_array_equal(survives.isel({"stop.1.d": i}).values, expected)
        assert float(ds["stop_value"].squeeze(drop=True).isel({"stop.1.d": i})) == gap
        alone_table = dict(zip(alone["label_code"].values.tolist(),
                               (str(n) for n in alone["label_name"].values), strict=True))
        labels = [table[int(c)] for c in ds["label"].isel({"stop.1.d": i}).values.ravel()]
        assert labels == [alone_table[int(c)] for c in alone["label"].values.ravel()]
        alive = {n for n, ok in zip(names, expected, strict=True) if ok}
        assert all(label in alive for label in labels if label in names)
        survivors.append(alive)
    assert len(survivors[0]) == 1 and len(survivors[1]) == 3
    text = format_summary(describe(ds), ds)
    assert "surviving at stop.1.d=4, t0=0 (1): L1^1 R1-0^1" in text
    assert "surviving at stop.1.d=6.5, t0=0 (3): " in text


def test_capture_by_known_products_keeps_a_chains_labels(tmp_path):
    """Capture by known orbits on a chain (the stable products each point's stops leave,
    by CAPTURE_MARGIN capture radii): over stop.1.d = [4, 6.5] the labels, statuses and
    periods are those of the same sweep with capture off, some starts are captured,
    and only where that point's catalogue says the product survives."""
    grid = "\n[grid]\nstop.1.d = [4.0, 6.5]\n"
    captured = run_sweep(parse_scene(GAPS + grid), tmp_path / "c.h5", workers=1)
    plain = run_sweep(parse_scene(GAPS + grid + "\n[integrator]\ncapture_tol = 0.0\n"),
                      tmp_path / "p.h5", workers=1)
    assert list(captured["label_name"].values) == list(plain["label_name"].values)
    for var in ("label", "status", "period"):
        np.testing.assert_array_equal(captured[var].values, plain[var].values)
    how = captured["captured"].values
    assert np.sum(how == 1) > 0 and np.sum(plain["captured"].values == 1) == 0
    names = dict(zip(captured["label_code"].values.tolist(),
                     (str(n) for n in captured["label_name"].values), strict=True))
    survives = captured["combination_survives"].squeeze(drop=True)
    products = [str(n) for n in captured["combination_name"].values]
    for i in range(2):
        alive = {n for n, ok in zip(products, survives.isel({"stop.1.d": i}).values,
                                    strict=True) if ok}
        at = captured.isel({"stop.1.d": i})
        for code, how_i in zip(at["label"].values.ravel(), at["captured"].values.ravel(),
                               strict=True):
            if how_i == 1:
                assert names[int(code)] in alive
