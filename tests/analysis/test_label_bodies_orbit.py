"""label_orbit on n bodies (issue 32 items 4 and 6): a joint orbit of up to eight bodies
(2n = 16 state variables) is named by each body's attractor and the canonical shifts,
and its code is its place among the catalogue's names. Synthetic attractors: the system
of eight bodies does not need to exist for its names."""

from itertools import product
from math import lcm

import numpy as np
import pytest

from softimpact_cli.analysis.catalogue import (
    Attractor,
    Catalogue,
    combination_names,
    combinations,
    label_orbit,
)
from softimpact_cli.analysis.labels import (
    BodyToken,
    bodies_label,
    catalogue_code,
    code_of,
    name_of,
    parse_label,
    shifts,
)
from softimpact_cli.kernels import codes


def attractor(number: int, period: int, centre: float) -> Attractor:
    """A fake attractor: p section points on a small circle about (centre, 0), point 0
    the one of largest x (canonical order)."""
    angles = 2 * np.pi * np.arange(period) / period
    points = np.column_stack([centre + 0.3 * np.cos(angles), 0.3 * np.sin(angles)])
    return Attractor(number, period, points, abs(centre) + 0.3, np.zeros(2), 0.0, 0.0)


BODY = (attractor(1, 1, -2.0), attractor(2, 2, 2.0), attractor(3, 3, 6.0))


def catalogue(n: int) -> Catalogue:
    per_body = [BODY] * n
    right = per_body[1] if n > 1 else ()
    combos = tuple(combinations(list(BODY), list(BODY))) if n == 2 else ()
    return Catalogue("synthetic", {}, BODY, right, combos, {}, 0, more=tuple(per_body[2:]))


def joint_orbit(chosen, indices) -> np.ndarray:
    """(lcm, 2n) time-ordered section points of bodies on ``chosen`` attractors starting
    at ``indices``."""
    q = lcm(*(a.period for a in chosen))
    return np.array([np.concatenate([a.points[(j + t) % a.period]
                                     for a, j in zip(chosen, indices, strict=True)])
                     for t in range(q)])


@pytest.mark.parametrize("n", [1, 2, 3, 5, 8])
def test_a_joint_orbit_is_named_by_its_bodies(n):
    rng = np.random.default_rng(n)
    cat = catalogue(n)
    names = cat.names
    index = {name: i for i, name in enumerate(names)}
    assert len(index) == len(names)  # every combination named once
    for _ in range(20):
        chosen = [BODY[k] for k in rng.integers(0, 3, n)]
        start = [int(rng.integers(0, a.period)) for a in chosen]
        orbit = joint_orbit(chosen, start)
        assert orbit.shape[1] == 2 * n
        label = label_orbit(cat, orbit, impacting=False)
        periods = [a.period for a in chosen]
        # the shifts of the last section point (the one label_orbit reads)
        last = [(j + orbit.shape[0] - 1) % a.period for a, j in zip(chosen, start, strict=True)]
        expected = bodies_label([BodyToken(a.period, a.number, s) for a, s in
                                 zip(chosen, shifts(last, periods), strict=True)])
        assert label == expected and parse_label(label.name) == label
        # the same orbit seen from any of its section times has the same name
        rolled = np.roll(orbit, 1, axis=0)
        assert label_orbit(cat, rolled, impacting=False) == label
        code = code_of(label, index)
        assert code == catalogue_code(index[label.name])
        assert name_of(code, names) == label.name
    assert label_orbit(cat, orbit, impacting=True).name == f"impacting P{orbit.shape[0]}"


def test_eight_bodies_have_more_names_than_the_first_code_range():
    """3 attractors (periods 1, 2, 3) per body, 8 bodies: sum over choices of the number
    of combinations, well past CATALOGUE_WIDTH, every code distinct."""
    names = catalogue(8).names
    expected = 0
    for chosen in product(BODY, repeat=8):
        periods = [a.period for a in chosen]
        expected += int(np.prod(periods)) // lcm(*periods)
    assert len(names) == expected > codes.CATALOGUE_WIDTH
    all_codes = {catalogue_code(i) for i in range(len(names))}
    assert len(all_codes) == len(names) and max(all_codes) < 2**31


def test_pair_names_follow_the_combinations():
    cat = catalogue(2)
    assert cat.names == combination_names(cat.per_body)
    assert cat.names[:3] == ("L1^1 R1-0^1", "L1^1 R2-0^2", "L1^1 R3-0^3")


def test_unmatched_and_wrong_width():
    cat = catalogue(3)
    orbit = joint_orbit([BODY[0], BODY[1], BODY[2]], [0, 0, 0])
    off = orbit.copy()
    off[:, 4] += 50.0  # body 3 on no attractor
    assert label_orbit(cat, off, impacting=False).name == "unmatched P6"
    short = orbit[:3]  # a period that is not the lcm of the bodies'
    assert label_orbit(cat, short, impacting=False).kind == "unmatched"
    with pytest.raises(ValueError, match="an orbit of 4 state variables, a catalogue of 3"):
        label_orbit(cat, orbit[:, :4], impacting=False)


@pytest.mark.parametrize("n", [2, 3, 4])
def test_every_combination_orbit_is_named_by_its_own_name(n):
    """joint_orbit of each (attractors, canonical shifts) is labelled with exactly the name
    combination_names lists for it, in the same order: names and orbits agree."""
    from softimpact_cli.analysis.catalogue import joint_orbit
    from softimpact_cli.analysis.labels import all_shifts

    cat = catalogue(n)
    named = []
    for chosen in product(BODY, repeat=n):
        for s in all_shifts([a.period for a in chosen]):
            named.append(label_orbit(cat, joint_orbit(chosen, s), impacting=False).name)
    assert tuple(named) == cat.names
    if n == 2:
        pair = [c.orbit for c in combinations(list(BODY), list(BODY))]
        ours = [joint_orbit((c.left, c.right), (0, c.shift))
                for c in combinations(list(BODY), list(BODY))]
        assert all(np.array_equal(a, b) for a, b in zip(pair, ours, strict=True))
