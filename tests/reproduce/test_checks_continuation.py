"""The continuation as a candidate explanation of figure 7's impacting ranges (S28, S32,
S34): the fold ending the stable impacting branch is compared with the study's value, and
the row says whether the study's value can be that end (the orbit is stable there)."""

from softimpact_cli.reproduce.checks.distances import CONTINUED, _continuation_end
from softimpact_cli.reproduce.verdicts import UNEXPLAINED, Measure, agrees, verdict

from .test_measures import EVENTS, IMPACTING, LAM, MODULUS, STABLE, continuation_result


def runs(name):
    assert name == "fig07_continuation"
    return continuation_result(LAM, STABLE, IMPACTING, MODULUS, EVENTS)


def test_a_study_value_inside_the_stable_range_cannot_be_its_end():
    st = {"rule": "value", "study": 15.96, "precision": 0.005}
    m = _continuation_end(st, runs, "A")
    assert m.value == 15.49 and m.label == CONTINUED and m.runs == ("fig07_continuation",)
    assert not agrees("value", 15.96, 0.005, m)
    assert "grazing at 16.550000" in m.shown and "fold, multiplier +1" in m.shown
    assert "at the study's d = 15.96 the impacting orbit is stable (largest |mu| 0.907)" \
        in m.shown  # 0.9 at d = 16.0, 0.97 at 15.6: interpolated
    v, why = verdict(st, Measure(15.5, "15.5", alternatives=[m]))
    assert v == UNEXPLAINED and f"{CONTINUED}: 15.4900" in why and "does not agree" in why


def test_a_study_value_at_the_fold_within_its_precision_agrees():
    st = {"rule": "value", "study": 15.5, "precision": 0.05}
    m = _continuation_end(st, runs, "A")
    assert agrees("value", 15.5, 0.05, m) and "is that end within its precision" in m.shown
    below = _continuation_end({"rule": "value", "study": 15.0, "precision": 0.005}, runs,
                              "A")
    assert "outside the stable impacting range 15.4900-16.5000" in below.shown


def test_without_the_continuation_run_a_difference_waits_for_it(monkeypatch):
    """--cached-only with fig07_continuation not made: a differing impacting end is 'not
    checked yet' naming the run; the grazing cross-check is left out."""
    from softimpact_cli.reproduce.checks import distances
    from softimpact_cli.reproduce.runs import MissingRun

    def no_continuation(name):
        raise MissingRun(name)

    monkeypatch.setattr(distances, "_grid_reading", lambda runs, name, what: [])
    monkeypatch.setattr(distances, "_branch", lambda runs, name, run="fig07": {
        "impacting_range": [15.5, 16.5], "falls_to": "B", "destroyed_at": 16.549})
    st = {"rule": "value", "study": 15.96, "precision": 0.005}
    m = distances._impacting_end(st, no_continuation, "A")
    assert m.pending == ["fig07_continuation"]
    assert verdict(st, m)[0].startswith("not checked yet: differs")
    d = distances._destroyed({"rule": "value", "study": 16.5}, no_continuation, "A")
    assert d.runs == ("fig07",) and "continuation" not in d.note
