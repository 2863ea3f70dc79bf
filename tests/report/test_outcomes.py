"""Warnings for results that are mostly unresolved or diverged, or without a catalogue
solution; --strict turns them into exit status 3 after the result is written."""

import subprocess
import sys

import numpy as np
import xarray as xr

from softimpact_cli.kernels.codes import DIVERGED_LABEL, UNRESOLVED_LABEL
from softimpact_cli.kinds.results import outcome_warnings
from softimpact_cli.report.outcomes import STRICT_STATUS


def _sweep(codes, kind="basins"):
    return xr.Dataset({"label": (("x1",), np.asarray(codes, dtype=np.int32))},
                      attrs={"analysis": kind})


def test_shares_over_five_percent_are_named():
    assert outcome_warnings(_sweep([0] * 95 + [UNRESOLVED_LABEL] * 5), 400) == []
    (message,) = outcome_warnings(_sweep([0] * 94 + [UNRESOLVED_LABEL] * 6, "map"), 400)
    assert message.startswith("6.0% of trajectories unresolved (no period within "
                              "max_periods = 400); raise [integrator] max_periods")
    both = outcome_warnings(_sweep([UNRESOLVED_LABEL] * 10 + [DIVERGED_LABEL] * 10), 5)
    assert [m.split(" (")[0] for m in both] == ["50.0% of trajectories unresolved",
                                               "50.0% of trajectories diverged"]


def test_an_empty_catalogue_is_said():
    ds = xr.Dataset({"attractor_name": (("attractor",), np.array([], dtype=object))},
                    attrs={"analysis": "catalogue", "n_samples": 40, "count_converged": 0,
                           "count_unresolved": 40, "count_diverged": 0})
    (message,) = outcome_warnings(ds, 5)
    assert message.startswith("the catalogue found no solution among 40 initial conditions "
                              "(converged 0, unresolved 40, diverged 0)")


def test_design_verification_counts_only_verified_points():
    ds = xr.Dataset({"rank": (("design_point",), [0, -1]),
                     "n_samples": (("design_point",), [100, 100]),
                     "count": (("design_point", "group"), [[90, 10], [0, 100]])},
                    coords={"group": ["L1^1 R1-0^1", "unresolved"]},
                    attrs={"analysis": "design"})
    (message,) = outcome_warnings(ds, 400)
    assert message.startswith("10.0% of trajectories unresolved")


SCENE = """
[system]
model = "duffing"
[coupling]
d = 6.0
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [3, 3]
[integrator]
max_periods = 5
section_periods = 0    # the second stage off: nothing resolves
[catalogue]
grid = 2
random = 4
[output]
path = "{out}"
"""


def test_a_sweep_that_resolves_nothing_warns_and_strict_fails_after_writing(tmp_path):
    out = tmp_path / "r.h5"
    scene = tmp_path / "r.toml"
    scene.write_text(SCENE.format(out=out))
    strict = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene), "-q",
                             "--workers", "1", "--strict"], capture_output=True, text=True)
    assert strict.returncode == STRICT_STATUS == 3, strict.stderr
    assert "Traceback" not in strict.stderr
    assert "softimpact: warning: 100.0% of trajectories unresolved (no period within " \
           "max_periods = 5)" in strict.stderr
    assert "softimpact: warning: the catalogue found no solution among" in strict.stderr
    with xr.open_dataset(out) as ds:  # written all the same
        assert ds.attrs["complete"] == 1 and (ds["label"] == UNRESOLVED_LABEL).all()
