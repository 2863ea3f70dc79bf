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


def test_an_impacting_label_may_split_into_numbered_orbits_only():
    from softimpact_cli.analysis.labels import impacting_code
    from tests.regression.changed import impacting_split_only

    names = {0: "L1^1", 1001: "impacting P1", impacting_code(1, 2): "impacting P1^2",
             1002: "impacting P2", impacting_code(2, 2): "impacting P2^2"}
    stored = sweep([0, 1001, 1001, 1002], names)
    now = sweep([0, 1001, impacting_code(1, 2), 1002], names)
    # codes in order 0, 1001, 1002, 1002001: the split-off orbit has its own points
    now["attractor_points"] = np.array([[[0.0], [1.0]], [[2.0], [3.0]], [[4.0], [5.0]],
                                        [[6.0], [7.0]]])
    now["periods_used"][2] = 99  # where the stored label was impacting: allowed
    stored["attractor_points"] = now["attractor_points"][:3]
    assert impacting_split_only(stored, now) == []
    now["label"][3] = impacting_code(1, 2)  # impacting P2 -> impacting P1^2: not a split
    now["periods_used"][0] = 7  # a non-impacting trajectory changed
    assert impacting_split_only(stored, now) == [
        "label: a change that is not impacting P{p} -> impacting P{p}^m",
        "periods_used: 1 values changed where the label was not impacting"]


def test_a_design_group_may_split_off_an_impacting_orbit_only():
    from tests.regression.changed import impacting_split_only

    stored = {"group": np.array(["L1^1", "impacting (all)", "impacting P1"]),
              "count": np.array([[5, 4, 4]])}
    now = {"group": np.array(["L1^1", "impacting (all)", "impacting P1", "impacting P1^2"]),
           "count": np.array([[5, 4, 1, 3]])}
    assert impacting_split_only(stored, now) == []
    now["count"] = np.array([[4, 4, 1, 4]])
    assert impacting_split_only(stored, now) == ["group L1^1: counts changed",
                                                 "group impacting P1: counts changed"]
