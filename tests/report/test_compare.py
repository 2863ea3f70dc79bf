"""softimpact compare: labels point by point, shares with Wilson intervals, limits."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.results import compare_results
from softimpact_cli.report.compare import limits_exceeded
from softimpact_cli.store import open_result, write_result
from tests.kinds.test_kinds import SCENES


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    """A tiny basins result A and a copy B with three labels moved to another solution."""
    tmp = tmp_path_factory.mktemp("compare")
    scene = tmp / "basins.toml"
    scene.write_text(SCENES["basins"])
    a = tmp / "a.h5"
    proc = run("sweep", scene, "-o", a, "-q", "--workers", 1)
    assert proc.exit_code == 0, proc.output
    ds = open_result(a).load()
    label = ds["label"].values.copy()
    flat = label.reshape(-1)
    codes = [int(c) for c in ds["label_code"].values]
    moved = [i for i in range(flat.size) if flat[i] != codes[0]][:3]
    flat[moved] = codes[0]
    b = tmp / "b.h5"
    write_result(ds.assign(label=(ds["label"].dims, label, ds["label"].attrs)), b)
    return a, b, len(moved), flat.size


def test_identical_results_agree(pair):
    a, _, _, n = pair
    report = compare_results(open_result(a), open_result(a))
    assert report["label_changed"] == 0 and report["trajectories"] == n
    assert report["max_share_change"] == 0.0
    assert limits_exceeded(report, 0.0, 0.0) == []


def test_changed_labels_are_counted_and_fail_the_limits(pair):
    a, b, moved, n = pair
    report = compare_results(open_result(a), open_result(b))
    assert report["label_changed"] == moved
    assert report["label_change_share"] == pytest.approx(moved / n)
    assert sum(report["changes"].values()) == moved
    # one grid point: the target solution's share rises by exactly moved / n
    rows = report["points"][0]["shares"]
    assert max(r["change"] for r in rows.values()) == pytest.approx(moved / n)
    for r in rows.values():  # each share lies inside its own 95% interval
        assert r["a_ci95"][0] <= r["a"] <= r["a_ci95"][1]
    proc = run("compare", a, b, "--max-label-change", 0.1)
    assert proc.exit_code == 1 and "--max-label-change" in proc.output
    proc = run("compare", a, b, "--max-label-change", 0.5, "--max-share-change", 0.5)
    assert proc.exit_code == 0, proc.output
    assert f"{moved} of {n} changed" in proc.output
    data = json.loads(run("compare", a, b, "--json").stdout)
    assert data["label_changed"] == moved and data["failed"] == []


def test_another_grid_or_initial_conditions_is_one_clear_error(pair, tmp_path):
    a, _, _, _ = pair
    ds = open_result(a).load()
    shifted = tmp_path / "shifted.h5"
    write_result(ds.assign_coords(x1=ds["x1"] + 0.5), shifted)
    with pytest.raises(ConfigError, match=r"initial conditions \(x1\)"):
        compare_results(open_result(a), open_result(shifted))
    proc = run("compare", a, shifted)
    assert proc.exit_code == 2 and proc.output.count("\n") == 1
    moved = tmp_path / "moved.h5"
    write_result(ds.assign_coords(d=ds["d"] + 1.0), moved)
    with pytest.raises(ConfigError, match="grid axis d"):
        compare_results(open_result(a), open_result(moved))


def test_bifurcation_destruction_points():
    import xarray as xr

    def result(values):
        return xr.Dataset({"branch_name": ("branch", ["P", "Q"]),
                           "destroyed_at": ("branch", np.array(values))},
                          attrs={"analysis": "bifurcation", "complete": 1})

    report = compare_results(result([5.0, np.nan]), result([5.25, np.nan]))
    assert report["branches"]["P"]["change"] == pytest.approx(0.25)
    assert limits_exceeded(report, max_d_change=0.1)
    assert not limits_exceeded(report, max_d_change=0.3)
    one_sided = compare_results(result([5.0, np.nan]), result([5.0, 4.0]))
    assert one_sided["differ_in_kind"] == ["Q"]
    assert limits_exceeded(one_sided, max_d_change=1.0)
