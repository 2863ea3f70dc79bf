"""The second stage's pure parts: the long-period test and the recurrence rule."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from softimpact_cli.analysis.section_follow import Recurrences, cell_indices, repeat_period


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 120), st.integers(0, 50))
def test_a_periodic_sequence_has_its_period_and_no_other(q, lead):
    rng = np.random.default_rng(q)
    orbit = rng.uniform(-5, 5, size=(q, 4))
    points = np.concatenate([rng.uniform(-5, 5, size=(lead, 4)),
                             np.tile(orbit, (3, 1))])
    assert repeat_period(points, 200, 1e-6) == q
    assert repeat_period(points, q - 1, 1e-6) == 0 if q > 1 else True


def test_a_spiral_into_a_fixed_point_is_not_a_period():
    # y_n = r^n (cos n a, sin n a): y_n - y_{n-q} is small for q a multiple of 2 pi / a,
    # but the divisor 1 nearly repeats too: still converging, not a period-q orbit
    n = np.arange(400)
    r = 0.999
    points = np.stack([r ** n * np.cos(2 * np.pi * n / 7), r ** n * np.sin(2 * np.pi * n / 7)],
                      axis=1) * 1e-5
    assert repeat_period(points, 200, 1e-6) == 0


def test_recurrences_fire_after_the_needed_revisits_only():
    cells = cell_indices(np.array([[0.1], [1.1], [2.1], [0.2], [1.2], [2.2], [0.3]]), 1.0)
    rule = Recurrences(3)
    assert rule.feed(cells[:5]) == -1  # two revisits so far
    assert Recurrences(3).feed(cells) == 5  # the third consecutive revisit, row 5
    assert Recurrences(3).feed(cell_indices(np.arange(50.0)[:, None], 1.0)) == -1  # drifting


def test_known_sets_stop_on_the_first_set_reaching_the_run():
    from softimpact_cli.analysis.section_follow import KnownSets, SectionFollow

    def found(cells, known_set=-1):
        cells = np.array(cells, dtype=np.int64)
        return SectionFollow("recurrent", 0, 0, np.zeros((0, 1)), cells, np.zeros((0, 1)), 0,
                             -np.inf, np.zeros(1), 0.0, known_set)

    sets = KnownSets()
    sets.learn(found([[0], [1]]))
    sets.learn(found([[5], [6]]))
    sets.learn(found([[2]], known_set=0))  # a trajectory found on set 0 widens it
    assert sets.cells == [{(0,), (1,), (2,)}, {(5,), (6,)}] and len(sets) == 2
    runs = []
    assert sets.landed(np.array([[0], [2], [9], [5]]), runs, 3) == (-1, -1)
    assert runs == [0, 1]  # the 9 broke set 0's run; set 1's has begun
    assert sets.landed(np.array([[6], [5], [1]]), runs, 3) == (1, 1)  # 5, 6, 5: set 1
