"""What the checks read from results: the boundary dimension tells a smooth boundary from
a ragged one; shares carry Wilson intervals; survivors follow d_crit."""

import numpy as np
import xarray as xr

from softimpact_cli.reproduce import measures as M


def test_boundary_dimension_is_one_for_a_straight_or_curved_boundary():
    y, x = np.mgrid[0:256, 0:256]
    assert abs(M.boundary_dimension((x > 100).astype(int)) - 1.0) < 0.05
    disc = ((x - 128) ** 2 + (y - 128) ** 2 < 80 ** 2).astype(int)
    assert abs(M.boundary_dimension(disc) - 1.0) < 0.1


def test_boundary_dimension_is_near_two_for_interleaved_basins():
    rng = np.random.default_rng(0)
    assert M.boundary_dimension(rng.integers(0, 2, (256, 256))) > 1.8


def test_share_groups_and_wilson_interval():
    point = {"counts": {"L1^1 R1-0^1": 900, "impacting P1": 60, "impacting P3": 40},
             "n": 1000}
    s, (lo, hi) = M.share(point, "impacting (all)")
    assert s == 0.1 and lo < 0.1 < hi and hi - lo < 0.04
    assert M.share(point, "non-impacting (sum)")[0] == 0.9
    assert M.found(point) == (["L1^1 R1-0^1"], ["impacting P1", "impacting P3"])


def test_survivors_are_the_combinations_below_d():
    ds = xr.Dataset({"d_crit": (("combination", "phi"), [[1.0, 3.0], [2.0, 0.5]]),
                     "combination_label": (("combination",), ["A", "B"])},
                    coords={"phi": [0.0, 1.0]})
    assert M.survivors(ds, 1.5, 0.0) == ["A"]
    assert M.survivors(ds, 1.5, 1.0) == ["B"]
    assert M.dcrit_at(ds, "A", 1.0) == 3.0


def continuation_result(lam, stable, impacting, modulus, events, start=0,
                        ends=("parameter bound 22.5", "parameter bound 2")) -> xr.Dataset:
    """A one-branch continuation result "A" (points in order of arclength, ``ends``: why
    it ends at its first and at its last point) with ``events`` [(kind, parameter)]."""
    n = len(lam)
    return xr.Dataset({
        "parameter": (("point",), np.asarray(lam, float)),
        "stable": (("point",), np.asarray(stable, np.int8)),
        "impacting": (("point",), np.asarray(impacting, np.int8)),
        "multiplier_re": (("point", "multiplier"), np.c_[modulus, np.full(n, 0.1)]),
        "multiplier_im": (("point", "multiplier"), np.zeros((n, 2))),
        "branch_name": (("branch",), ["A"]), "branch_first": (("branch",), [0]),
        "branch_size": (("branch",), [n]), "branch_start": (("branch",), [start]),
        "branch_end_low": (("branch",), [ends[0]]),
        "branch_end_high": (("branch",), [ends[1]]),
        "event_kind": (("event",), [k for k, _ in events]),
        "event_branch": (("event",), [0] * len(events)),
        "event_parameter": (("event",), [p for _, p in events])})


# d falling from the start at 22.5: flat and stable, grazing at 16.55, stable impacting
# down to a fold at 15.49, back up unstable (and a grazing of that unstable leg at 18.1)
LAM = [22.5, 20.0, 17.0, 16.5, 16.0, 15.6, 15.5, 15.6, 16.5, 18.0]
STABLE = [1, 1, 1, 1, 1, 1, 1, 0, 0, 0]
IMPACTING = [0, 0, 0, 1, 1, 1, 1, 1, 1, 1]
MODULUS = [0.7, 0.7, 0.7, 0.8, 0.9, 0.97, 0.99, 1.01, 1.2, 1.5]
EVENTS = [("grazing", 16.55), ("fold", 15.49), ("grazing", 18.1)]


def test_stable_impacting_leg_runs_from_the_grazing_to_the_fold():
    leg = M.stable_impacting_leg(continuation_result(LAM, STABLE, IMPACTING, MODULUS,
                                                     EVENTS), "A")
    assert (leg["grazing"], leg["fold"], leg["end"]) == (16.55, 15.49, "fold")
    assert (leg["low"], leg["high"]) == (15.5, 16.5)
    assert list(leg["parameter"]) == [15.5, 15.6, 16.0, 16.5]
    assert list(leg["modulus"]) == [0.99, 0.97, 0.9, 0.8]


def test_stable_impacting_leg_follows_falling_d_whichever_way_the_points_run():
    """The same branch stored the other way round (start last), and one that stays
    stable to the parameter bound (no fold: the branch's end is said)."""
    back = continuation_result(LAM[::-1], STABLE[::-1], IMPACTING[::-1], MODULUS[::-1],
                               EVENTS, start=len(LAM) - 1)
    leg = M.stable_impacting_leg(back, "A")
    assert (leg["low"], leg["high"], leg["fold"]) == (15.5, 16.5, 15.49)
    bound = continuation_result([22.5, 10.0, 3.0, 2.5, 2.0], [1] * 5, [0, 0, 0, 1, 1],
                                [0.7] * 5, [("grazing", 2.6)])
    leg = M.stable_impacting_leg(bound, "A")
    assert np.isnan(leg["fold"]) and leg["end"] == "parameter bound 2"
    assert (leg["grazing"], leg["low"]) == (2.6, 2.0)
    never = continuation_result([22.5, 20.0], [1, 1], [0, 0], [0.7, 0.7], [])
    assert M.stable_impacting_leg(never, "A")["end"] == "no run"
