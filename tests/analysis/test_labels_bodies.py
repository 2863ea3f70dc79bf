"""Names of n bodies (issue 32 item 4): one token per body with its period and shift,
today's one-body and pair names unchanged, parser and printer round trip, the shift rule
and the number of combinations checked by brute force, and codes for every name."""

from itertools import product
from math import gcd, lcm, prod

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softimpact_cli.analysis.labels import (
    MAX_NAMED_BODIES,
    BodyToken,
    Label,
    all_shifts,
    bodies_label,
    catalogue_code,
    code_of,
    impacting_code,
    n_combinations,
    name_of,
    parse_label,
    shift,
    shifts,
)
from softimpact_cli.kernels import codes

small_periods = st.lists(st.integers(1, 6), min_size=1, max_size=4)


def orbits_by_brute_force(periods):
    """Every index tuple, grouped into the orbits of the common advance (+1, ..., +1)."""
    q = lcm(*periods)
    seen, orbits = set(), []
    for start in product(*(range(p) for p in periods)):
        if start in seen:
            continue
        orbit = {tuple((j + t) % p for j, p in zip(start, periods, strict=True))
                 for t in range(q)}
        seen |= orbit
        orbits.append(orbit)
    return orbits


def lexicographic_least(indices, periods):
    """The definition of the shifts, by brute force over every advance."""
    q = lcm(*periods)
    return min(tuple((j + t) % p for j, p in zip(indices, periods, strict=True))
               for t in range(q) if (indices[0] + t) % periods[0] == 0)


@settings(max_examples=150, deadline=None)
@given(small_periods)
def test_combinations_counted_and_named_by_brute_force(periods):
    """n_combinations = p1 ... pk / lcm is the number of orbits of index tuples; the
    shifts are constant on each orbit, distinct between orbits, the lexicographic least
    tuple with body 1 at 0, and all_shifts lists exactly them."""
    orbits = orbits_by_brute_force(periods)
    assert len(orbits) == n_combinations(periods) == prod(periods) // lcm(*periods)
    names = []
    for orbit in orbits:
        found = {shifts(indices, periods) for indices in orbit}
        assert len(found) == 1
        (s,) = found
        assert s == lexicographic_least(next(iter(orbit)), periods) and s in orbit
        names.append(s)
    assert sorted(names) == all_shifts(periods)


@given(st.integers(1, 40), st.integers(1, 40), st.integers(0, 200), st.integers(0, 200))
def test_two_bodies_keep_the_pairs_shift(pl, pr, j, k):
    assert shifts((j % pl, k % pr), (pl, pr)) == (0, shift(j % pl, k % pr, pl, pr))
    assert n_combinations((pl, pr)) == gcd(pl, pr)


token_parts = st.tuples(st.integers(1, 12), st.integers(1, 12))


@st.composite
def body_labels(draw, min_bodies=1, max_bodies=MAX_NAMED_BODIES):
    """A valid label of 1 .. 8 bodies, shifts drawn among the canonical ones."""
    parts = draw(st.lists(token_parts, min_size=min_bodies, max_size=max_bodies))
    periods = [p for p, _ in parts]
    s = shifts([draw(st.integers(0, p - 1)) for p in periods], periods)
    return bodies_label([BodyToken(p, n, k) for (p, n), k in zip(parts, s, strict=True)])


@settings(max_examples=300, deadline=None)
@given(body_labels())
def test_body_names_round_trip(label):
    assert parse_label(label.name) == label
    assert len(label.body_tokens) == {"body": 1, "pair": 2}.get(label.kind,
                                                                 len(label.tokens))
    assert label.latex.startswith("$") and label.latex.endswith("$")


def test_one_body_and_pair_names_are_todays():
    assert bodies_label([BodyToken(2, 1)]).name == "L2^1"
    assert bodies_label([BodyToken(2, 1), BodyToken(4, 3, 1)]) == Label("pair", 2, 1, 4, 1, 3)
    assert bodies_label([BodyToken(2, 1), BodyToken(4, 3, 1)]).name == "L2^1 R4-1^3"


def test_three_body_name_reads_as_documented():
    label = parse_label("B1:P2^1 B2:P1-0^2 B3:P2-1^1")
    assert label.kind == "bodies" and label.period == 2
    assert label.tokens == (BodyToken(2, 1), BodyToken(1, 2), BodyToken(2, 1, 1))
    assert label.latex == "$B_{1}{:}P^{1}_{2}\\,B_{2}{:}P^{2}_{1-0}\\,B_{3}{:}P^{1}_{2-1}$"


@pytest.mark.parametrize("bad", [
    "B1:P1^1 B2:P1-0^2",  # two bodies are named L R
    "B1:P1^1 B3:P1-0^2 B2:P1-0^1",  # bodies out of order
    "B1:P2-0^1 B2:P1-0^2 B3:P1-0^1",  # the first body has no shift
    "B1:P2^1 B2:P2^2 B3:P1-0^1",  # the others have one
    "B1:P2^1 B2:P4-2^1 B3:P1-0^1",  # shift 2 >= gcd(2, 4)
    "B1:P2^1 B2:P3-0^1 B3:P6-6^1",  # body 3's shift < gcd(lcm(2, 3), 6) = 6
    "B1:P0^1 B2:P1-0^1 B3:P1-0^1",
    "impacting P1^1", "impacting P1^0", "impacting P1^1000",
])
def test_bad_body_names(bad):
    with pytest.raises(ValueError):
        parse_label(bad)


def test_impacting_orbits_are_numbered_from_the_second():
    first, second = parse_label("impacting P1"), parse_label("impacting P1^2")
    assert first.name == "impacting P1" and second.name == "impacting P1^2"
    assert second.latex == "impacting $P_{1}^{2}$"
    assert code_of(first, ()) == codes.IMPACTING_BASE + 1 == impacting_code(1)
    assert code_of(second, ()) == impacting_code(1, 2) != impacting_code(2, 2)
    for p, m in [(1, 2), (7, 3), (999, 999), (12, 999)]:
        label = parse_label(f"impacting P{p}^{m}")
        code = code_of(label, ())
        assert name_of(code, ()) == label.name and 0 < code < 2**31
        assert not codes.IMPACTING_BASE <= code < codes.NONPERIODIC_BASES["chaotic"] + 1000


@settings(max_examples=50, deadline=None)
@given(st.lists(body_labels(3, MAX_NAMED_BODIES), min_size=1, max_size=30, unique=True),
       st.integers(0, 3000))
def test_codes_hold_many_bodies_names(labels, offset):
    """A catalogue of more than CATALOGUE_WIDTH solutions: the ones past it take
    EXTENDED_CATALOGUE_BASE + index, distinct from every other code, and round trip."""
    names = tuple(f"filler {i}" for i in range(offset)) + tuple(lb.name for lb in labels)
    index = {n: i for i, n in enumerate(names)}
    for i, label in enumerate(labels):
        code = code_of(label, index)
        assert code == code_of(label, names) == catalogue_code(offset + i)
        assert name_of(code, names) == label.name and 0 <= code < 2**31
        special = code >= codes.CATALOGUE_WIDTH
        assert special == (offset + i >= codes.CATALOGUE_WIDTH)
        assert not codes.IMPACTING_BASE <= code < codes.NUMBERED_IMPACTING_BASE + 10**6
    assert np.int32(catalogue_code(2**31 - 1 - codes.EXTENDED_CATALOGUE_BASE)) > 0


def test_basin_stability_sums_count_many_bodies_and_numbered_impacting_orbits():
    from softimpact_cli.analysis.stability import groups

    names = ["B1:P1^1 B2:P1-0^1 B3:P1-0^2", "impacting P1", "impacting P1^2", "unresolved"]
    out = groups(names)
    assert out["non-impacting (sum)"] == [0]
    assert out["impacting (all)"] == [1, 2]
    assert out["impacting P1^2"] == [2]
