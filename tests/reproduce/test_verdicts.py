"""Verdict rules on synthetic values: agreement within the study's precision, and an
explanation counted only when its own run agrees."""

from softimpact_cli.reproduce.statements import load
from softimpact_cli.reproduce.verdicts import (
    EXPLAINED,
    REPRODUCED,
    UNEXPLAINED,
    Measure,
    agrees,
    verdict,
)


def test_value_rule_uses_the_study_precision_plus_our_tolerance():
    assert agrees("value", 7.44466, 5e-6, Measure(7.444664, ""))
    assert not agrees("value", 7.44466, 5e-6, Measure(7.29852, ""))
    assert agrees("value", 16.5, 0.005, Measure(16.549, "", tolerance=0.05))


def test_count_names_and_holds():
    assert agrees("count", 3, 0, Measure(3, ""))
    assert not agrees("count", 3, 0, Measure(4, ""))
    assert agrees("names", ["b", "a"], 0, Measure(["a", "b"], ""))
    assert not agrees("names", ["a"], 0, Measure(["a", "b"], ""))
    assert agrees("holds", None, 0, Measure(True, "")) and not agrees(
        "holds", None, 0, Measure(False, ""))


def test_share_rule_needs_every_share_inside_its_interval_widened_by_precision():
    m = Measure([0.60, 0.15], "", ci=[(0.57, 0.63), (0.13, 0.17)])
    assert agrees("share", [0.62, 0.16], 0.0, m)
    assert not agrees("share", [0.65, 0.16], 0.0, m)
    assert agrees("share", [0.65, 0.16], 0.02, m)
    assert not agrees("share", [0.62], 0.0, m)  # a missing share never agrees
    assert not agrees("share", 0.6, 0.0, Measure(0.6, ""))  # no interval, no agreement


def test_verdicts_reproduced_explained_unexplained():
    st = {"rule": "value", "study": 10.0, "precision": 0.05}
    assert verdict(st, Measure(10.02, "10.02"))[0] == REPRODUCED
    near = Measure(10.2, "10.2", alternatives=[
        Measure(11.0, "11.0", runs=("a",), label="t0 = T/4"),
        Measure(10.01, "10.01", runs=("b",), label="t0 = T/2")])
    v, why = verdict(st, near)
    assert v == EXPLAINED and "t0 = T/2: 10.01 (agrees; run b)" in why
    assert "t0 = T/4: 11.0 (does not agree; run a)" in why
    far = Measure(10.2, "10.2", alternatives=[Measure(11.0, "11", runs=("a",), label="x")])
    assert verdict(st, far)[0] == UNEXPLAINED


def test_a_difference_with_an_explanation_not_run_yet_is_not_checked_yet():
    st = {"rule": "value", "study": 10.0, "precision": 0.05}
    m = Measure(10.2, "10.2", pending=["fig07_basins_t0half"])
    v, _ = verdict(st, m)
    assert v.startswith("not checked yet: differs") and "fig07_basins_t0half" in v
    assert verdict(st, Measure(10.0, "10.0", pending=["x"]))[0] == REPRODUCED


def test_an_explanation_with_a_caveat_is_reported_but_not_counted():
    st = {"rule": "count", "study": 3}
    alt = Measure(3, "3", runs=("r",), label="sign flipped", caveat="contradicts figure 7")
    v, why = verdict(st, Measure(2, "2", alternatives=[alt]))
    assert v == UNEXPLAINED and "agrees, not counted: contradicts figure 7" in why


def test_a_statements_reading_comes_first_in_the_explanation():
    """The reading of a statement's loose words lives in statements.toml (key
    ``reading``), not in its check: every verdict's explanation starts with it."""
    st = {"rule": "holds", "reading": "'around d = 10' read as within 20%"}
    assert verdict(st, Measure(True, "yes", note="mirrored")) == (
        REPRODUCED, "'around d = 10' read as within 20%; mirrored")
    assert verdict(st, Measure(False, "no"))[1] == "'around d = 10' read as within 20%"
    assert verdict({"rule": "holds"}, Measure(True, "yes"))[1] == ""


def test_the_moved_readings_are_in_the_statements():
    readings = {s["check"]: s["reading"] for s in load() if "reading" in s}
    assert readings["dcrit_mixed_mirrored"].startswith("'around d = 10' read as")
    assert readings["fig09_velocity_rows"].startswith("'no qualitative change' read as")
