"""The check that only formerly unresolved entries of a reference changed."""

import numpy as np

from softimpact_cli.kernels.codes import CHAOTIC_BASE, UNRESOLVED_LABEL
from tests.regression.changed import formerly_unresolved_only


def sweep(labels, names):
    codes = sorted(set(labels))
    return {"label": np.array(labels), "periods_used": np.array([10] * len(labels)),
            "label_code": np.array(codes), "label_name": np.array([names[c] for c in codes]),
            "attractor_points": np.arange(2.0 * len(codes)).reshape(len(codes), 2, 1)}


NAMES = {0: "L1^1", UNRESOLVED_LABEL: "unresolved", CHAOTIC_BASE + 1: "chaotic A1"}


def test_an_unresolved_label_may_become_an_attractor():
    stored = sweep([0, UNRESOLVED_LABEL, 0], NAMES)
    now = sweep([0, CHAOTIC_BASE + 1, 0], NAMES)
    now["periods_used"][1] = 99
    # L1^1 as stored, padded with NaN: the attractor's cloud is longer than any orbit
    now["attractor_points"] = np.array([[[2.0], [3.0], [np.nan]], [[7.0], [7.0], [7.0]]])
    assert formerly_unresolved_only(stored, now) == []


def test_a_periodic_label_may_not_change():
    stored = sweep([0, UNRESOLVED_LABEL, 0], NAMES)
    now = sweep([0, UNRESOLVED_LABEL, CHAOTIC_BASE + 1], NAMES)
    assert formerly_unresolved_only(stored, now) == [
        "label: 1 values changed where the label was not unresolved"]


def test_a_design_may_only_move_unresolved_counts_to_new_groups():
    stored = {"group": np.array(["L1^1", "unresolved"]), "count": np.array([[5, 2], [7, 0]])}
    now = {"group": np.array(["L1^1", "chaotic A1"]), "count": np.array([[5, 2], [7, 0]])}
    assert formerly_unresolved_only(stored, now) == []
    now["count"] = np.array([[4, 3], [7, 0]])
    assert formerly_unresolved_only(stored, now) == [
        "group L1^1: counts changed", "the new groups' counts are not the unresolved ones lost"]


def test_the_sums_of_a_design_gain_what_their_new_members_gained():
    stored = {"group": np.array(["L1^1", "impacting (all)", "unresolved"]),
              "count": np.array([[5, 1, 2]])}
    now = {"group": np.array(["L1^1", "impacting (all)", "impacting chaotic A1"]),
           "count": np.array([[5, 3, 2]])}
    assert formerly_unresolved_only(stored, now) == []
    now["count"] = np.array([[5, 2, 2]])
    assert formerly_unresolved_only(stored, now) == ["group impacting (all): counts changed"]
