"""Tipping probabilities (basin overlap): known matrices, invariants of any pair of label
arrays, and the destinations of solutions in order."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.analysis.labels import DIVERGED, UNRESOLVED, UNRESOLVED_LABEL
from softimpact_cli.analysis.tipping import attractor_destinations, tipping_probabilities

NAMES = ("A", "B", "C")


def test_a_known_overlap():
    # basin A before: 4 starts, 3 stay A, 1 goes to B; basin B: 2 starts, both to B
    before = np.array([0, 0, 0, 0, 1, 1])
    after = np.array([0, 0, 0, 1, 1, 1])
    ds = tipping_probabilities(before, after, NAMES)
    assert list(ds["tip_from"].values) == ["A", "B"]
    assert list(ds["tip_to"].values) == ["A", "B"]
    np.testing.assert_array_equal(ds["tip_count"].values, [[3, 1], [0, 2]])
    np.testing.assert_allclose(ds["tip_probability"].values, [[0.75, 0.25], [0.0, 1.0]])
    np.testing.assert_allclose(ds["tip_from_share"].values, [4 / 6, 2 / 6])
    # Wilson 95% for 3 of 4: [0.3006, 0.9544]
    assert ds["tip_ci95_low"].values[0, 0] == pytest.approx(0.300642, abs=1e-5)
    assert ds["tip_ci95_high"].values[0, 0] == pytest.approx(0.954413, abs=1e-5)


def test_unresolved_starts_are_a_label_not_dropped():
    before = np.array([0, UNRESOLVED_LABEL, 0])
    after = np.array([UNRESOLVED_LABEL, 1, 0])
    ds = tipping_probabilities(before, after, NAMES)
    assert UNRESOLVED in ds["tip_from"].values and UNRESOLVED in ds["tip_to"].values
    assert int(ds["tip_count"].sum()) == 3
    assert DIVERGED not in ds["tip_from"].values


def test_a_code_table_names_as_a_result_does():
    ds = tipping_probabilities(np.array([5, 7]), np.array([7, 7]), {5: "x", 7: "y"})
    assert list(ds["tip_from"].values) == ["x", "y"]
    np.testing.assert_allclose(ds["tip_probability"].values, [[1.0], [1.0]])


def test_sizes_must_match():
    with pytest.raises(ValueError, match="differ in size: 3 and 2"):
        tipping_probabilities(np.zeros(3, int), np.zeros(2, int), NAMES)


labels = st.lists(st.tuples(st.integers(0, 2), st.integers(0, 2)), min_size=1, max_size=200)


@given(pairs=labels)
def test_rows_are_probabilities_and_counts_add_up(pairs):
    before, after = (np.array(x) for x in zip(*pairs, strict=True))
    ds = tipping_probabilities(before, after, NAMES)
    p = ds["tip_probability"].values
    np.testing.assert_allclose(p.sum(axis=1), 1.0)
    assert int(ds["tip_count"].sum()) == before.size
    assert np.all(ds["tip_ci95_low"].values <= p + 1e-12)
    assert np.all(p <= ds["tip_ci95_high"].values + 1e-12)
    np.testing.assert_allclose(ds["tip_from_share"].sum(), 1.0)


@given(pairs=labels, perm=st.permutations([0, 1, 2]))
def test_renaming_the_labels_permutes_the_matrix(pairs, perm):
    before, after = (np.array(x) for x in zip(*pairs, strict=True))
    ds = tipping_probabilities(before, after, NAMES)
    renamed = tuple(NAMES[perm.index(k)] for k in range(3))  # code perm[k] is named NAMES[k]
    other = tipping_probabilities(np.array(perm)[before], np.array(perm)[after], renamed)
    for i in ds["tip_from"].values:
        for j in ds["tip_to"].values:
            assert (float(ds["tip_probability"].sel(tip_from=i, tip_to=j))
                    == float(other["tip_probability"].sel(tip_from=i, tip_to=j)))


@given(codes=st.lists(st.integers(0, 2), min_size=1, max_size=100))
def test_no_change_is_the_identity(codes):
    ds = tipping_probabilities(np.array(codes), np.array(codes), NAMES)
    np.testing.assert_array_equal(ds["tip_probability"].values,
                                  np.eye(len(set(codes))))


def test_destinations_keep_each_solutions_points_in_order():
    orbits = {"P1": np.zeros((1, 4)), "P2": np.ones((2, 4)), "P3": 2 * np.ones((3, 4))}
    seen = []

    def label(states):
        seen.append(states.copy())
        return [f"s{int(s[0])}-{k}" for k, s in enumerate(states)]

    out = attractor_destinations(orbits, label)
    assert out == {"P1": ["s0-0"], "P2": ["s1-1", "s1-2"], "P3": ["s2-3", "s2-4", "s2-5"]}
    assert len(seen) == 1 and seen[0].shape == (6, 4)  # one labelling call for all
    assert attractor_destinations({}, label) == {}
