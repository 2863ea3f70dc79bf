"""Every sweep measures its label error: Wilson bounds, the decision rule, the ladder,
and whole runs (a planted mislabel is caught and tightened; a clean run is reported as
the rule says; a killed verification loses nothing)."""

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.analysis.stability import wilson_interval
from softimpact_cli.cli import main
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.sweep import verification as v

PLANE = """
[system]
model = "duffing"
[coupling]
d = 6.0
phi = 0.0
k_c = 8.0
c_c = 10.0
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [16, 16]
[catalogue]
grid = 6
random = 30
"""
# recurrence cells far too large, labelling after one period in a cell: about 15% of
# this plane (two basins) takes the label of whichever start reached the cell first
MISLABEL = PLANE + "[integrator]\ncell_size = 10.0\ncell_hits = 1\n"


@pytest.mark.parametrize("k, n, low, high", [
    (0, 50, 0.0, 0.071348), (0, 800, 0.0, 0.004779), (5, 100, 0.021543, 0.111750),
    (50, 50, 0.928651, 1.0)])
def test_wilson_bounds_of_known_cases(k, n, low, high):
    (lo,), (hi,) = wilson_interval(np.array([k]), n)
    assert lo == pytest.approx(low, abs=2e-6) and hi == pytest.approx(high, abs=2e-6)


def attempt(disagreements, sample, threshold_free=True):
    (lo,), (hi,) = wilson_interval(np.array([disagreements]), sample)
    return v.Attempt("s", "r", sample, 10 * sample, disagreements, float(lo), float(hi), {},
                     1.0, 2.0)


def test_decision_rule():
    assert attempt(0, 800).outcome(0.005) == v.VERIFIED  # upper 0.48%
    assert attempt(0, 50).outcome(0.005) == v.BOUNDED  # upper 7.1%: reported as a bound
    assert attempt(1, 2000).outcome(0.005) == v.VERIFIED  # one change, bound still low
    assert attempt(3, 50).outcome(0.005) == v.OVER
    assert v.final_status([attempt(3, 50), attempt(0, 50)], 0.005) == v.TIGHTENED
    assert v.final_status([attempt(3, 50), attempt(2, 50)], 0.005) == v.OVER
    assert "the label error is at most 7.13% (95% upper bound); 765 reruns" in \
        v.status_message([attempt(0, 50)], 0.005, True)


@pytest.mark.parametrize("threshold", [0.005, 0.01, 0.001, 0.2])
def test_the_sample_for_a_threshold_is_the_fewest_that_bound_it(threshold):
    """Zero disagreements in ``sample_for_threshold`` reruns verify; one rerun fewer
    does not (765 for the default 0.5%)."""
    n = v.sample_for_threshold(threshold)
    assert attempt(0, n).outcome(threshold) == v.VERIFIED
    assert attempt(0, n - 1).outcome(threshold) == v.BOUNDED
    assert v.sample_for_threshold(0.005) == 765


def test_ladder_turns_cells_and_capture_off_first_then_tolerances():
    loose = IntegratorSettings(cell_size=5.0, cell_hits=1)
    (first, s1), (second, s2) = v.ladder(loose)
    assert "cells and capture off" in first and (s1.cell_size, s1.capture_tol) == (0, 0)
    assert s1.rtol == loose.rtol
    assert (s2.rtol, s2.atol, s2.cell_size) == (1e-10, 1e-12, 0.0)
    assert s2.steps_per_period == 4 * loose.steps_per_period
    plain = IntegratorSettings(capture_tol=0.0, cell_size=0.0)
    assert [s.rtol for _, s in v.ladder(plain)] == [1e-10]  # nothing to switch off


def test_the_sample_says_whether_tolerance_or_shortcuts_are_to_blame():
    """Rerun alone at its own settings, the sample tells a tolerance error (the labels
    disagree already without capture and cells) from a shortcut error; the ladder then
    tightens what is to blame first and keeps the cells where they cost nothing."""
    def with_alone(n):
        return dataclasses.replace(attempt(12, 400), alone_disagreements=n)

    assert with_alone(11).blame(0.005) == "tolerance"
    assert with_alone(0).blame(0.005) == "shortcuts"
    assert with_alone(None).blame(0.005) == "shortcuts"  # nothing to tell: as before
    assert with_alone(1).blame(0.05) == "shortcuts"  # within the threshold on its own
    s = IntegratorSettings()
    (first, s1), (second, s2) = v.ladder(s, "tolerance")
    assert (s1.rtol, s1.cell_size, s1.capture_tol) == (s.rtol / 100, s.cell_size,
                                                      s.capture_tol)
    assert (s2.rtol, s2.cell_size, s2.capture_tol) == (s.rtol / 100, 0.0, 0.0)
    assert "cells and capture off" in second and "cells" not in first


def sweep_cli(tmp_path, text, *flags):
    scene = tmp_path / "s.toml"
    scene.write_text(text)
    out = tmp_path / "s.h5"
    result = CliRunner().invoke(main, ["sweep", str(scene), "-o", str(out), "--workers", "1",
                                       "-q", *flags])
    return result, out


def test_planted_mislabel_is_reported_and_tightened(tmp_path):
    result, out = sweep_cli(tmp_path, MISLABEL)
    assert result.exit_code == 0, result.output
    ds = si.open_result(out)
    history = json.loads(ds.attrs["verify_history"])
    assert history[0]["disagreements"] > 0 and history[0]["outcome"] == v.OVER
    assert "cells 10 x 1" in history[0]["settings"]
    assert ds.attrs["verify_status"] == v.TIGHTENED and ds.attrs["verify_rungs"] >= 1
    assert history[-1]["disagreements"] < history[0]["disagreements"]
    assert history[-1]["outcome"] != v.OVER
    # the kept result is the redone sweep, complete, and says how it was made
    assert ds.attrs["complete"] == 1 and ds.attrs["integrator_cell_size"] == 0.0
    assert "# verification: redone with recurrence cells and capture off" in \
        ds.attrs["scene_text"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.h5", "s.toml"]
    assert "label error (tightened" in result.output


def test_mislabel_without_tighten_is_over_threshold_and_warned(tmp_path):
    text = MISLABEL + "[verification]\ntighten = false\n"
    result, out = sweep_cli(tmp_path, text)
    assert result.exit_code == 0, result.output
    assert "softimpact: warning: label error over the threshold" in result.output
    ds = si.open_result(out)
    assert ds.attrs["verify_status"] == v.OVER and ds.attrs["verify_disagreements"] > 0
    assert ds.attrs["integrator_cell_size"] == 10.0  # kept as the user set it
    assert "tighten = false" in ds.attrs["verify_message"]
    strict, _ = sweep_cli(tmp_path, text, "--overwrite", "--strict")
    assert strict.exit_code == 3, strict.output


def test_clean_run_reads_clean_with_the_default_settings(tmp_path):
    """None of the default sample disagreed: the line states the bound it gives, and
    nothing is noted or warned (the demo used to end on "label error inconclusive")."""
    result, out = sweep_cli(tmp_path, PLANE)
    assert result.exit_code == 0, result.output
    ds = si.open_result(out)
    assert ds.attrs["verify_sample"] == 50 and ds.attrs["verify_disagreements"] == 0
    assert ds.attrs["verify_status"] == v.BOUNDED  # 0 / 50 bounds it below 7.13%
    assert "label error <= 7.13% (95%), measured on 50 of 256 trajectories rerun at auto, " \
        "rtol 1e-10" in result.output
    assert "none disagreed" in result.output
    assert "note" not in result.output and "warning" not in result.output
    assert "inconclusive" not in result.output
    info = CliRunner().invoke(main, ["info", str(out)])
    assert "label error <= 7.13% (95%), measured on 50 of 256" in info.output
    assert "765 reruns without a change would bound it at 0.50% (--check 765" in info.output
    loose = PLANE + "[verification]\nthreshold = 0.1\n"
    result, out = sweep_cli(tmp_path, loose, "--overwrite")
    assert si.open_result(out).attrs["verify_status"] == v.VERIFIED
    info = CliRunner().invoke(main, ["info", str(out)])
    assert "label error (verified, 50 of 256 rerun at auto, rtol 1e-10" in info.output
    assert "0 / 50 disagree, 95% interval [0.00%, 7.13%] <= 10.00%" in info.output
    report = json.loads(CliRunner().invoke(main, ["info", str(out), "--json"]).output)
    assert report["verification"]["status"] == v.VERIFIED
    assert report["verification"]["ci95_high"] == pytest.approx(0.071348, abs=1e-6)


def test_disagreements_within_the_threshold_are_noted(tmp_path):
    """Some labels disagreed but the bound is within the threshold: verified, with a
    note saying what changed (a clean run has none)."""
    text = MISLABEL + "[verification]\nthreshold = 0.6\ntighten = false\n"
    result, out = sweep_cli(tmp_path, text)
    assert result.exit_code == 0, result.output
    ds = si.open_result(out)
    assert ds.attrs["verify_status"] == v.VERIFIED and ds.attrs["verify_disagreements"] > 0
    assert (f"softimpact: note: {ds.attrs['verify_disagreements']} of 50 rerun labels "
            "disagreed (") in result.output


def test_no_verify_and_disabled_are_recorded(tmp_path):
    result, out = sweep_cli(tmp_path, PLANE, "--no-verify")
    assert result.exit_code == 0, result.output
    assert si.open_result(out).attrs["verify_status"] == \
        "not verified (disabled by --no-verify)"
    assert "label error: not verified (disabled by --no-verify)" in result.output
    both, _ = sweep_cli(tmp_path, PLANE, "--check", "10", "--no-verify", "--overwrite")
    assert both.exit_code == 2 and "--check 10 and --no-verify: choose one" in both.output
    off = PLANE + "[verification]\nenabled = false\n"
    ds = si.run(off, workers=1)
    assert ds.attrs["verify_status"] == \
        "not verified (disabled by [verification] enabled = false)"


def test_api_run_verifies_in_memory_and_can_be_told_not_to():
    ds = si.run(MISLABEL, workers=1, verify_sample=30)
    assert ds.attrs["verify_status"] == v.TIGHTENED and ds.attrs["verify_sample"] == 30
    assert si.run(PLANE, workers=1, verify=False).attrs["verify_status"] == \
        "not verified (disabled by --no-verify)"
    with pytest.raises(si.ConfigError, match="verify_sample: must be a whole number >= 1"):
        si.run(PLANE, verify_sample=0)


def sweep_with_verification_killed(scene: str, out, monkeypatch):
    """Run ``scene`` into ``out`` with its verification stopped by a Ctrl-C; return what
    the file kept (the patch undone: a resume then verifies)."""
    def killed(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(v, "check_result", killed)
    with pytest.raises(KeyboardInterrupt):
        si.sweep(scene, out, workers=1)
    monkeypatch.undo()
    return si.open_result(out)


def test_a_killed_verification_keeps_the_sweep_and_resume_verifies_it(tmp_path,
                                                                       monkeypatch):
    out = tmp_path / "k.h5"
    kept = sweep_with_verification_killed(PLANE, out, monkeypatch)
    assert kept.attrs["complete"] == 1 and kept.attrs["verify_status"] == v.PENDING
    ds = si.sweep(PLANE, out, workers=1, resume=True)
    assert ds.attrs["verify_status"] == v.BOUNDED
    assert si.open_result(out).attrs["verify_status"] == v.BOUNDED
    np.testing.assert_array_equal(ds["label"].values, kept["label"].values)


def test_interrupted_line_says_how_to_verify(tmp_path, monkeypatch):
    from softimpact_cli.sweep.interrupt import sweep_kept

    out = tmp_path / "k.h5"
    sweep_with_verification_killed(PLANE, out, monkeypatch)
    assert "is complete but not verified; verify with: softimpact sweep s.toml -o " \
        in sweep_kept(out, "s.toml")


def test_other_kinds_say_why_they_are_not_verified():
    ds = si.run('[system]\nmodel = "duffing"\n[analysis]\nkind = "trajectory"\n'
                "state = [1.0, 0.0, -1.0, 0.0]\nperiods = 5\n")
    assert ds.attrs["verify_status"].startswith("not applicable (a trajectory result")


def test_plot_prints_the_error_line(tmp_path):
    result, out = sweep_cli(tmp_path, PLANE, "--check", "20")
    assert result.exit_code == 0, result.output
    fig = si.plot.basins(si.open_result(out), show_error=True)
    assert "label error <= 16.11% (95%), measured on 20 of 256" in \
        fig._supxlabel.get_text()
    drawn = CliRunner().invoke(main, ["plot", "basins", str(out), "-o",
                                      str(tmp_path / "b.png"), "--show-error"])
    assert drawn.exit_code == 0, drawn.output


def test_verifying_never_imports_matplotlib(tmp_path):
    code = ("import sys, softimpact_cli as si\n"
            f"si.sweep({PLANE!r}, {str(tmp_path / 'm.h5')!r}, workers=1)\n"
            "assert 'matplotlib' not in sys.modules\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr


def test_a_redo_that_does_not_halve_the_disagreements_ends_the_ladder():
    """Near a fractal boundary tightening does not help: stop after one redo, say why."""
    from types import SimpleNamespace

    scene = si.load_scene(PLANE + "[integrator]\ncell_size = 0.5\ncell_hits = 2\n")
    calls, outcomes = [], iter([(12, 400), (9, 400), (1, 400)])

    def fake_check(sc, ds, n, seed, executor):
        k, sample = next(outcomes)
        a = attempt(k, sample)
        return dataclasses.replace(a, alone_disagreements=0)

    def redo(sc, rung):
        calls.append(rung)
        return SimpleNamespace(attrs={"n": 1000})

    original = v.check_result
    v.check_result = fake_check
    try:
        ds = v.verify_sweep(scene, SimpleNamespace(attrs={"n": 1000, "pilot_status": "x"}),
                            redo, sample=400)
    finally:
        v.check_result = original
    assert calls == [1]  # 12 -> 9 did not halve: no second rung
    assert ds.attrs["pilot_status"] == "x"  # the redone result keeps the pilot's record
    assert ds.attrs["verify_status"] == v.OVER and ds.attrs["verify_rungs"] == 1
    assert "did not halve the disagreements (12 -> 9 of 400)" in ds.attrs["verify_message"]
    assert v.stalled([attempt(12, 400), attempt(6, 400)]) is False  # halved: go on
    assert v.stalled([attempt(12, 400)]) is False
