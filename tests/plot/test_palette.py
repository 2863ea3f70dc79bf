"""Colours: distinct within a catalogue, the same for a name in every result of a system."""

from softimpact_cli.analysis.labels import Label
from softimpact_cli.plot.palette import DISTINCT, IMPACTING, SPECIAL, colour_of


def bilinear_w0928_names():
    """The 28 states of figure 13's catalogue: periods 1, 3, 3, 5 (numbers 1..4)."""
    periods = {1: 1, 2: 3, 3: 3, 4: 5}
    from math import gcd

    return [Label("pair", periods[a], a, periods[b], s, b).name
            for a in periods for b in periods for s in range(gcd(periods[a], periods[b]))]


def test_every_solution_of_a_catalogue_gets_its_own_colour():
    names = bilinear_w0928_names()
    assert len(names) == 28 <= len(DISTINCT)
    colours = [colour_of(n, names) for n in names]
    assert len(set(colours)) == len(names)
    assert IMPACTING not in colours and not set(SPECIAL.values()) & set(colours)


def test_a_name_keeps_its_colour_whatever_else_a_figure_shows():
    names = bilinear_w0928_names()
    for name in names:
        assert colour_of(name, names) == colour_of(name, tuple(names))
    # the Duffing pair's four states keep the study's gallery colours in catalogue order
    duffing = ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1", "L1^2 R1-0^2"]
    assert [colour_of(n, duffing) for n in duffing] == DISTINCT[:4]


def test_outcomes_and_unknown_names_have_stable_colours():
    assert colour_of("impacting P3", ["L1^1"]) == IMPACTING
    assert colour_of("unresolved") == SPECIAL["unresolved"]
    assert colour_of("unmatched P7") == colour_of("unmatched P7", ["L1^1"])


def test_attractors_that_are_not_periodic_take_their_own_colours():
    from softimpact_cli.plot.palette import NOT_PERIODIC

    names = ["chaotic A1", "impacting quasi-periodic A2", "impacting chaotic A3"]
    colours = [colour_of(n, ["L1^1"]) for n in names]
    assert colours == NOT_PERIODIC[:3]  # by number, impacting or not: never brown
    assert not set(colours) & (set(DISTINCT) | {IMPACTING, *SPECIAL.values()})
