"""The one code space of outcomes: statuses, label codes and classification methods."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.analysis.labels import code_of, name_of, parse_label
from softimpact_cli.kernels import codes

STATUSES = (codes.CONVERGED, codes.UNRESOLVED, codes.DIVERGED, codes.STEP_BUDGET,
            codes.TOO_MANY_SWITCHES, codes.STEP_UNDERFLOW)
SPECIAL_LABELS = (codes.UNRESOLVED_LABEL, codes.DIVERGED_LABEL, codes.MIXED_CELL,
                  codes.PENDING)


def test_every_status_has_an_outcome_and_a_message():
    assert set(codes.STATUS_TABLE) == set(STATUSES)
    assert {codes.outcome(s) for s in STATUSES} == set(codes.OUTCOMES)
    assert all(codes.message(s) for s in STATUSES)


@pytest.mark.parametrize("status", STATUSES[1:])
def test_a_failed_status_maps_to_the_label_of_its_outcome(status):
    label = codes.label_code_of_status(status)
    expected = {"unresolved": codes.UNRESOLVED_LABEL, "diverged": codes.DIVERGED_LABEL}
    assert label == expected[codes.outcome(status)]
    assert name_of(label, ()) == codes.outcome(status)


def test_budget_and_chatter_are_unresolved_underflow_is_diverged():
    # the mapping the sweep and the bifurcation analysis used to write separately
    assert codes.label_code_of_status(codes.STEP_BUDGET) == codes.UNRESOLVED_LABEL
    assert codes.label_code_of_status(codes.TOO_MANY_SWITCHES) == codes.UNRESOLVED_LABEL
    assert codes.label_code_of_status(codes.STEP_UNDERFLOW) == codes.DIVERGED_LABEL
    with pytest.raises(ValueError, match="labelled by its orbit"):
        codes.label_code_of_status(codes.CONVERGED)


def test_special_label_codes_are_distinct_negative_and_not_an_orbit_index():
    assert len(set(SPECIAL_LABELS)) == len(SPECIAL_LABELS)
    assert all(c < 0 for c in SPECIAL_LABELS)
    # -1 is the "no orbit" index of a capture, so no label code may be -1
    assert codes.NO_ORBIT == -1 and codes.NO_ORBIT not in SPECIAL_LABELS
    assert codes.UNMATCHED_BASE - codes.IMPACTING_BASE >= 1000


def test_classification_methods_have_names():
    assert set(codes.CLASSIFIED_BY) == {codes.BY_OWN_REPEAT, codes.BY_KNOWN_ORBIT,
                                        codes.BY_CELLS, codes.BY_SECTION}
    assert len(set(codes.CLASSIFIED_BY.values())) == 4


@given(st.sampled_from(["impacting", "unmatched"]), st.integers(1, 999))
def test_periodic_label_codes_round_trip(kind, period):
    label = parse_label(f"{kind} P{period}")
    code = code_of(label, ("L1^1",))
    assert code not in SPECIAL_LABELS and code >= codes.IMPACTING_BASE
    assert name_of(code, ("L1^1",)) == label.name


@given(st.lists(st.sampled_from(["L1^1", "L2^1", "L2^2", "L3^1", "L1^2"]), min_size=1,
                unique=True))
def test_catalogue_codes_are_positions_and_names_round_trip(names):
    names = tuple(names)
    for i, name in enumerate(names):
        assert code_of(parse_label(name), names) == i
        assert name_of(i, names) == name


def test_label_code_ranges_never_overlap():
    # impacting, unmatched and the four kinds of attractor that is not periodic: each a
    # disjoint range of BASE_WIDTH codes above every catalogue index and special code
    bases = sorted([codes.IMPACTING_BASE, codes.UNMATCHED_BASE,
                    *codes.NONPERIODIC_BASES.values()])
    assert len(set(bases)) == len(bases)
    assert all(b - a >= codes.BASE_WIDTH for a, b in zip(bases, bases[1:], strict=False))
    assert codes.IMPACTING_BASE >= codes.BASE_WIDTH


@given(st.sampled_from(sorted(codes.NONPERIODIC_BASES)), st.integers(1, 999))
def test_nonperiodic_label_codes_round_trip(kind, number):
    label = parse_label(f"{kind} A{number}")
    code = code_of(label, ("L1^1",))
    assert code == codes.NONPERIODIC_BASES[kind] + number
    assert name_of(code, ("L1^1",)) == label.name == f"{kind} A{number}"
    assert label.latex == f"{kind} $A_{{{number}}}$"
