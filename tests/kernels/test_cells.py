"""Recurrence cells: keys identify boxes of the section exactly, conflicting labels mark a
cell MIXED_CELL, and a sweep with cells labels as a sweep without them."""

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softimpact_cli.kernels.cells import (
    MAX_CELL_DIM,
    NO_CELL,
    PACKED_DIM,
    WORDS,
    new_cells,
    remember_cells,
)
from softimpact_cli.kernels.cells import cell_key as kernel_cell_key
from softimpact_cli.kernels.codes import BY_CELLS, MIXED_CELL


def cell_key(y, size, table=None):
    """The kernel's key, in a fresh table unless one is given."""
    return kernel_cell_key(y, size, new_cells() if table is None else table)

coordinate = st.integers(min_value=-5000, max_value=5000)
offset = st.floats(min_value=0.01, max_value=0.99)  # clear of rounding at cell edges


@settings(max_examples=200, deadline=None)
@given(st.lists(coordinate, min_size=4, max_size=4), st.lists(offset, min_size=4, max_size=4),
       st.lists(offset, min_size=4, max_size=4), st.sampled_from([0.05, 0.1, 0.37]))
def test_points_share_a_key_exactly_when_they_share_a_cell(cell, a, b, size):
    base = np.array(cell, dtype=float)
    ya = (base + np.array(a)) * size
    yb = (base + np.array(b)) * size
    same = np.array_equal(np.floor(ya / size), np.floor(yb / size))
    assert (cell_key(ya, size) == cell_key(yb, size)) == same
    neighbour = yb.copy()
    neighbour[int(np.argmax(b))] += size  # one cell over along one axis
    assert cell_key(neighbour, size) != cell_key(ya, size) or not same


def test_far_points_have_no_cell():
    assert cell_key(np.array([1e9, 0.0, 0.0, 0.0]), 0.1) == NO_CELL
    assert cell_key(np.array([np.nan, 0.0]), 0.1) == NO_CELL
    assert cell_key(np.array([-0.05, 0.05]), 0.1) != cell_key(np.array([0.05, 0.05]), 0.1)


@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=PACKED_DIM + 1, max_value=MAX_CELL_DIM), st.data(),
       st.sampled_from([0.05, 0.1, 0.37]))
def test_wide_states_share_a_key_exactly_when_they_share_a_cell(dim, data, size):
    """From 5 to 16 coordinates (eight bodies) the key is the slot of the table that holds
    the cell's words: the same cell finds it again, another cell gets another."""
    vector = st.lists(coordinate, min_size=dim, max_size=dim)
    offsets = st.lists(offset, min_size=dim, max_size=dim)
    base = np.array(data.draw(vector), dtype=float)
    ya = (base + np.array(data.draw(offsets))) * size
    yb = (base + np.array(data.draw(offsets))) * size
    axis = data.draw(st.integers(0, dim - 1))
    neighbour = yb.copy()
    neighbour[axis] += size  # one cell over along one axis
    table = new_cells()
    key_a = cell_key(ya, size, table)
    assert key_a >= 0 and cell_key(yb, size, table) == key_a
    key_n = cell_key(neighbour, size, table)
    assert key_n >= 0 and key_n != key_a
    assert cell_key(ya, size, table) == key_a and len(table) == 2 * WORDS  # words only
    far = ya.copy()
    far[axis] = 1e9
    assert cell_key(far, size, table) == NO_CELL and len(table) == 2 * WORDS
    remember_cells(table, np.array([key_a, key_n]), 2, 5)
    assert table[key_a] == table[key_n] == 5


def test_a_wide_cell_whose_slot_is_taken_gets_the_next_one():
    """The collision check: a slot holding another cell's words is passed over."""
    y = np.linspace(-1.0, 1.0, 16)
    slot = cell_key(y, 0.1)
    table = new_cells()
    for i in range(WORDS):  # another cell's words in that slot
        table[-2 - WORDS * slot - i] = 12345 + i
    assert cell_key(y, 0.1, table) == slot + 1
    assert cell_key(y, 0.1, table) == slot + 1  # found again past the taken slot
    assert cell_key(y + 0.1, 0.1, table) not in (slot, slot + 1)


def test_wider_states_are_refused_not_silently_uncelled():
    """A key holds MAX_CELL_DIM = 16 coordinates (eight bodies); a 17th is an error, in the
    kernel and (for its message) in the scene."""
    assert MAX_CELL_DIM == 16
    cell_key(np.zeros(16), 0.1)
    with pytest.raises(ValueError, match="at most 16 state variables"):
        cell_key(np.zeros(17), 0.1)


def test_cells_label_a_five_variable_state_like_no_cells():
    """The energy test's 5-state system (beyond one packed word): cells now serve it, and
    a trajectory the cells name takes the label its full integration gives. On dopri5,
    the method of the energy test's own classification: that test's compiled kernel
    serves this one (the default "auto" compiled another, 40 s of CPU, for a system no
    run uses; what cells do does not depend on the method)."""
    from softimpact_cli.analysis.engine import Problem, RecurrenceCells, classify_state
    from tests.kernels.test_energy import FREE, WORK_PAIR

    problem = Problem(WORK_PAIR, dict(FREE, d=50.0)).with_integrator(method="dopri5",
                                                                     max_periods=400)
    state = [3.0, 0.0, -3.0, 0.0, 0.0]
    plain = classify_state(problem, state)
    cells = RecurrenceCells(0.5, 2, 400)
    first = classify_state(problem, state, recurrence=cells)
    assert first.period == plain.period and first.cell_code == MIXED_CELL
    cells.remember(first, 7)
    assert min(cells.table) <= -2  # the wide states' cells keep their words in the table
    again = classify_state(problem, state, recurrence=cells)
    assert again.cell_code == 7
    assert again.periods_used < plain.periods_used


def test_scene_refuses_cells_for_a_wider_state(monkeypatch):
    import softimpact_cli.config.scene as scene_module  # its reader of [system]
    from softimpact_cli.config import ConfigError
    from softimpact_cli.kinds.scene import parse_scene
    from tests.kernels.test_energy import WORK_PAIR

    monkeypatch.setattr(scene_module, "get_system", lambda model, bodies: WORK_PAIR)
    text = ("[system]\nmodel='duffing'\n[integrator]\ncell_size={}\n[analysis]\n"
            "state=[1.0, 0.0, 0.0, 0.0, 0.0]\n")
    assert parse_scene(text.format(0.5)).system.dim == 5  # 5 variables: cells allowed now
    monkeypatch.setattr(scene_module, "MAX_CELL_DIM", 4)  # the message, at a smaller bound
    assert parse_scene(text.format(0.0)).system.dim == 5
    with pytest.raises(ConfigError, match=r"\[integrator\] cell_size: recurrence cells hold "
                                          r"states of at most 4 variables, this system has 5"):
        parse_scene(text.format(0.5))


def test_cells_visited_on_the_way_to_two_labels_become_mixed():
    cells = new_cells()
    remember_cells(cells, np.array([10, 11, NO_CELL, 12]), 4, 3)
    assert dict(cells) == {10: 3, 11: 3, 12: 3}
    remember_cells(cells, np.array([12, 13, 99]), 2, 1000)  # only the first two count
    assert dict(cells) == {10: 3, 11: 3, 12: MIXED_CELL, 13: 1000}
    remember_cells(cells, np.array([12]), 1, 3)
    assert cells[12] == MIXED_CELL  # once mixed, always mixed


def test_a_sweep_with_cells_labels_like_one_without():
    from softimpact_cli.sweep.chunks import run_chunk
    from tests.sweep.test_capture import context

    ctx, _ = context(res=24)  # figure 6(d) plane, 576 initial conditions, one chunk
    n = ctx.states.shape[0]
    plain = run_chunk(ctx, 0, n)
    cells = replace(ctx, integrator=replace(ctx.integrator, cell_size=0.05, cell_hits=5))
    fast = run_chunk(cells, 0, n)
    assert np.array_equal(fast["label"], plain["label"])
    by_cells = fast["captured"] == BY_CELLS
    assert by_cells.mean() > 0.3
    assert fast["periods_used"][by_cells].mean() < plain["periods_used"][by_cells].mean()
    # a cell-labelled trajectory reports its label's orbit period and penetration
    assert np.array_equal(fast["period"], plain["period"])
    assert np.allclose(fast["max_penetration"], plain["max_penetration"])
    # the same chunk gives the same result (cells start empty at every run and point)
    again = run_chunk(cells, 0, n)
    for key in ("label", "periods_used", "captured"):
        assert np.array_equal(again[key], fast[key])
