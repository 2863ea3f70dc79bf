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


def _chaotic_sweep(settling=False):
    """A one-body stability sweep whose catalogue search (first pass only) found nothing
    and whose second stage named every trajectory chaotic A1 (or left one settling)."""
    from softimpact_cli.kernels.codes import CHAOTIC_BASE, UNRESOLVED

    labels = [CHAOTIC_BASE + 1] * 39 + [UNRESOLVED_LABEL if settling else CHAOTIC_BASE + 1]
    rows = [(CHAOTIC_BASE + 1, "chaotic A1", 39 + (not settling))]
    if settling:
        rows.append((UNRESOLVED_LABEL, "unresolved (settling)", 1))
    return xr.Dataset(
        {"label": (("sample",), np.array(labels, dtype=np.int32)),
         "status": (("sample",), np.full(40, UNRESOLVED, dtype=np.int8)),
         "attractor_name": (("attractor",), np.array([], dtype=object)),
         "nonperiodic_code": (("nonperiodic",), [r[0] for r in rows]),
         "nonperiodic_name": (("nonperiodic",), [r[1] for r in rows]),
         "nonperiodic_members": (("nonperiodic",), [r[2] for r in rows])},
        attrs={"analysis": "stability", "catalogue_n_samples": 456,
               "catalogue_count_converged": 0, "catalogue_count_unresolved": 456,
               "catalogue_count_diverged": 0})


def test_an_empty_catalogue_beside_a_chaotic_attractor_is_a_note_not_a_warning():
    """Issue 31, item 3: no "found no solution among 0 initial conditions; raise
    max_periods" when the sweep found the attractor chaotic."""
    from softimpact_cli.report.outcomes import outcome_notes

    ds = _chaotic_sweep()
    assert outcome_warnings(ds, 3000, section_periods=4000) == []
    (note,) = outcome_notes(ds)
    assert note == ("the catalogue search found no periodic solution among 456 initial "
                    "conditions (converged 0, unresolved 456, diverged 0); the sweep's "
                    "second stage found 1 attractor that is not periodic: chaotic A1 "
                    "(40 trajectories)")
    # the settling set is no attractor: it is not listed, and the one trajectory left
    # unresolved is below the warning's share
    (note,) = outcome_notes(_chaotic_sweep(settling=True))
    assert note.endswith("chaotic A1 (39 trajectories)")


def test_a_sweeps_empty_catalogue_counts_its_search():
    ds = _chaotic_sweep().drop_vars(["nonperiodic_code", "nonperiodic_name",
                                     "nonperiodic_members"])
    ds["label"][:] = UNRESOLVED_LABEL
    catalogue, share = outcome_warnings(ds, 3000, section_periods=4000)
    assert catalogue.startswith("the catalogue found no solution among 456 initial "
                                "conditions (converged 0, unresolved 456, diverged 0); "
                                "raise [integrator] max_periods (now 3000)")
    assert share == ("100.0% of trajectories unresolved (no period within max_periods = "
                     "3000, nor a period or a recurrent set in section_periods = 4000 more); "
                     "raise [integrator] max_periods or section_periods, or check the scene")


def test_info_tells_named_from_left_unresolved():
    from softimpact_cli.report.info import unresolved_then_named
    from softimpact_cli.report.info_text import _status_text

    then = unresolved_then_named(_chaotic_sweep(settling=True))
    assert then == {"named not periodic": 39, "left unresolved": 1}
    assert _status_text({"converged": 0, "unresolved": 40, "diverged": 0}, then) == (
        "converged 0, unresolved 40 (first pass; then named not periodic 39, left "
        "unresolved 1), diverged 0")
    plain = _chaotic_sweep()
    plain["label"][:] = UNRESOLVED_LABEL
    assert unresolved_then_named(plain) is None  # nothing named: the plain status line
