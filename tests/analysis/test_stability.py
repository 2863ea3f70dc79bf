"""Basin stability: Wilson intervals, shares that add up, determinism."""

import numpy as np
import pytest

from softimpact_cli.analysis.labels import parse_label
from softimpact_cli.analysis.stability import basin_stability, wilson_interval
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep


def test_wilson_known_values():
    lo, hi = wilson_interval(np.array([0]), 10)
    assert lo[0] == 0.0 and hi[0] == pytest.approx(1.959963984540054**2 / (10 + 1.96**2),
                                                   rel=1e-3)
    lo, hi = wilson_interval(np.array([50]), 100)  # symmetric around 1/2
    assert 0.5 - lo[0] == pytest.approx(hi[0] - 0.5)
    # 2 z / (1 + z^2/n) * sqrt(p(1-p)/n + z^2/(4 n^2)) at p = 1/2, n = 100
    assert hi[0] - lo[0] == pytest.approx(0.192337, abs=1e-6)


@pytest.mark.parametrize("p", [0.05, 0.3, 0.5])
def test_intervals_shrink_as_one_over_sqrt_n(p):
    widths = []
    for n in (1000, 4000, 16000):
        lo, hi = wilson_interval(np.array([p * n]), n)
        widths.append(hi[0] - lo[0])
    assert widths[0] / widths[1] == pytest.approx(2.0, rel=0.02)
    assert widths[1] / widths[2] == pytest.approx(2.0, rel=0.01)


SCENE = """
[system]
model = "duffing"
[coupling]
d = 10.5
phi = 5.28
k_c = 8.0
[analysis]
kind = "stability"
[grid]
c_c = [2.0, 10.0]
[initial_conditions]
kind = "random"
box = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}
n = 60
seed = 9
[catalogue]
grid = 6
random = 30
"""


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("bs")
    return run_sweep(parse_scene(SCENE, "bs.toml"), tmp / "a.h5", workers=1)


def test_shares_sum_to_one_and_aggregates_add_up(result):
    bs = basin_stability(result)
    groups = [str(g) for g in bs["group"].values]
    singles = [g for g in groups if "(" not in g]
    total = bs["share"].sel(group=singles).sum("group")
    assert np.allclose(total.values, 1.0)
    impacting = [g for g in singles if parse_label(g).kind == "impacting"]
    non = [g for g in singles if parse_label(g).kind in ("pair", "unmatched")]
    assert np.allclose(bs["share"].sel(group="impacting (all)").values,
                       bs["share"].sel(group=impacting).sum("group").values)
    assert np.allclose(bs["share"].sel(group="non-impacting (sum)").values,
                       bs["share"].sel(group=non).sum("group").values)
    assert (bs["ci_low"] <= bs["share"]).all() and (bs["share"] <= bs["ci_high"]).all()
    assert bs.attrs["n"] == 60


def test_same_seed_same_shares(result, tmp_path):
    again = run_sweep(parse_scene(SCENE, "bs.toml"), tmp_path / "b.h5", workers=2,
                      chunk_size=17)
    assert np.array_equal(basin_stability(result)["count"].values,
                          basin_stability(again)["count"].values)


def test_plane_shares_compared_with_4d_stability(result, tmp_path):
    from softimpact_cli.report.info import compare_shares

    plane = SCENE.replace('kind = "stability"', 'kind = "basins"').replace(
        'kind = "random"\nbox = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}'
        '\nn = 60\nseed = 9',
        'kind = "plane"\naxes = ["x1", "x2"]\nranges = [[-12, 12], [-12, 12]]\nresolution = 6')
    basins = run_sweep(parse_scene(plane, "plane.toml"), tmp_path / "p.h5", workers=1)
    rows = compare_shares(basins, result)
    assert [r["c_c"] for r in rows] == [2.0, 10.0]
    for row in rows:
        assert sum(v["plane"] for v in row["shares"].values()) == pytest.approx(1.0)
        assert sum(v["stability"] for v in row["shares"].values()) == pytest.approx(1.0)
        for v in row["shares"].values():
            assert v["ci95"][0] <= v["stability"] <= v["ci95"][1]
