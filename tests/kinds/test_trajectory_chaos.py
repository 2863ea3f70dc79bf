"""A single trajectory on a chaotic attractor is named as sweeps name it (issue 31, item
2): Ueda's oscillator from (2.5, 0) (configs/ueda_trajectory.toml) finds no period within
max_periods, and the second stage follows it on the section and calls it `chaotic A1`
with its Lyapunov exponents, which `info`, `info --json` and `plot trajectory` show."""

import json

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.kernels.codes import UNRESOLVED

from ..regression.reference import ROOT

SCENE = ROOT / "configs" / "ueda_trajectory.toml"


@pytest.fixture(scope="module")
def ueda(tmp_path_factory):
    out = tmp_path_factory.mktemp("ueda") / "ueda.h5"
    run = CliRunner().invoke(main, ["sweep", str(SCENE), "-o", str(out), "-q"])
    assert run.exit_code == 0, run.output
    assert "trajectory: chaotic" in run.output
    with xr.open_dataset(out) as ds:
        return out, ds.load()


def test_ueda_is_chaotic_with_its_exponents(ueda):
    _, ds = ueda
    a = ds.attrs
    assert a["outcome"] == "chaotic" and a["label"] == "chaotic A1"
    assert a["status"] == UNRESOLVED  # the first pass's, as a sweep keeps it
    assert a["second_stage"] == "recurrent" and a["classified_by"] == "followed on the section"
    assert a["periods_used"] > 3000  # the first pass's max_periods, then the section
    assert ds["nonperiodic_name"].values.tolist() == ["chaotic A1"]
    lam = ds["nonperiodic_exponents"].values[0]
    err = ds["nonperiodic_stderr"].values[0]
    # published 0.0999 and -0.1499 (Sprott 2001): within 3 standard errors of 400 periods
    assert abs(lam[0] - 0.0999) < 3 * err[0] + 0.005 and lam[0] > 0
    assert abs(lam[1] + 0.1499) < 3 * err[1] + 0.005
    assert lam.sum() == pytest.approx(-0.05, abs=2e-3)  # trace J = -c
    assert f"{lam[0]:+.4g}" in a["status_message"]


def test_info_and_info_json_show_the_attractor(ueda):
    out, ds = ueda
    lam = ds["nonperiodic_exponents"].values[0]
    text = CliRunner().invoke(main, ["info", str(out)]).output
    assert any(line.split() == ["outcome", "chaotic"] for line in text.splitlines())
    assert any(line.split() == ["label", "chaotic", "A1"] for line in text.splitlines())
    line = next(x for x in text.splitlines() if x.strip().startswith("chaotic A1:"))
    assert "1 trajectories" in line and f"{lam[0]:+.4f}" in line
    info = json.loads(CliRunner().invoke(main, ["info", str(out), "--json"]).output)
    assert info["outcome"] == "chaotic" and info["label"] == "chaotic A1"
    (row,) = info["nonperiodic"]
    assert row["name"] == "chaotic A1" and row["kind"] == "chaotic" and row["at"] == {}
    assert np.allclose(row["exponents"], lam)


def test_plot_trajectory_names_it_and_draws_its_section_cloud(ueda, tmp_path):
    from softimpact_cli.plot.trajectory_figure import draw_trajectory

    out, ds = ueda
    fig = draw_trajectory(ds)
    lam = ds["nonperiodic_exponents"].values[0]
    assert "chaotic A1" in fig.get_suptitle() and f"{lam[0]:+.4f}" in fig.get_suptitle()
    phase = fig.axes[1]
    assert any("chaotic A1" in str(line.get_label()) for line in phase.get_lines())
    png = tmp_path / "u.png"
    run = CliRunner().invoke(main, ["plot", "trajectory", str(out), "-o", str(png)])
    assert run.exit_code == 0, run.output
    assert png.stat().st_size > 10_000
