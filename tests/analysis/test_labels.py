from math import gcd

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.analysis.labels import Label, latex_of, n_shifts, parse_label, shift

periods = st.integers(1, 40)


@given(periods, periods)
def test_distinct_shifts_equal_gcd(pl, pr):
    # enumerate all index pairs (j, k) reachable on the joint orbit from every start and
    # count the distinct invariant shifts: must be gcd(pl, pr)
    shifts = {shift(j, k, pl, pr) for j in range(pl) for k in range(pr)}
    assert len(shifts) == n_shifts(pl, pr) == gcd(pl, pr)


@given(periods, periods, st.integers(0, 200), st.integers(0, 200), st.integers(0, 500))
def test_shift_invariant_along_orbit(pl, pr, j, k, n):
    s0 = shift(j % pl, k % pr, pl, pr)
    assert shift((j + n) % pl, (k + n) % pr, pl, pr) == s0


@given(periods, st.integers(1, 9), periods, st.integers(1, 9), st.data())
def test_pair_label_round_trip(pl, nl, pr, nr, data):
    s = data.draw(st.integers(0, gcd(pl, pr) - 1))
    label = Label("pair", pl, nl, pr, s, nr)
    assert parse_label(label.name) == label
    assert label.name == f"L{pl}^{nl} R{pr}-{s}^{nr}"


@given(st.sampled_from(["impacting", "unmatched"]), periods)
def test_periodic_label_round_trip(kind, p):
    assert parse_label(f"{kind} P{p}") == Label(kind, p)


@pytest.mark.parametrize("name", ["unresolved", "diverged", "L2^1", "L1^1 R1-0^2", "L5^2 R5-3^2"])
def test_named_examples(name):
    assert parse_label(name).name == name


def test_latex():
    assert latex_of("L1^1 R1-0^2") == "$L^{1}_{1}R^{2}_{1-0}$"
    assert latex_of("L5^2 R5-3^2") == "$L^{2}_{5}R^{2}_{5-3}$"


@pytest.mark.parametrize("bad", ["L1^1 R1-1^2", "L0^1", "L1^1R1-0^2", "impacting", "P3",
                                 "L2^1 R4-2^1", "chaos", "chaotic A0", "chaotic",
                                 "impacting chaotic A1000", "quasi periodic A1"])
def test_bad_labels(bad):
    with pytest.raises(ValueError):
        parse_label(bad)


@given(st.sampled_from(["impacting", "unmatched"]), st.integers(1, 999))
def test_codes_round_trip(kind, p):
    from softimpact_cli.analysis.labels import code_of, name_of

    names = ("L1^1 R1-0^1", "L1^1 R1-0^2")
    label = Label(kind, p)
    assert name_of(code_of(label, names), names) == label.name


def test_catalogue_codes_follow_catalogue_order():
    from softimpact_cli.analysis.labels import code_of, name_of

    names = ("L2^1 R2-0^1", "L2^1 R2-1^1", "L2^1 R5-0^2")
    for i, n in enumerate(names):
        assert code_of(parse_label(n), names) == i and name_of(i, names) == n
    for special in ("unresolved", "diverged"):
        assert name_of(code_of(parse_label(special), names), names) == special
