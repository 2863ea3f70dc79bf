"""Recurrence cells: the labels earlier trajectories gave to boxes of the section.

A cell is a box of side ``cell_size`` in the state space of the stroboscopic section (the
idea of Attractors.jl's recurrences method). Every section point a classified trajectory
visited marks its cell with that trajectory's label code; a cell that two trajectories
with different labels visited is marked ``MIXED_CELL`` and never used again. A later
trajectory whose section points land in cells of one label for ``cell_hits``
consecutive periods takes that label without integrating further. Cells are only valid
for one parameter point: the caller starts a new table for each.
"""

import numpy as np
from numba import njit, types
from numba.typed import Dict

from .codes import MIXED_CELL

NO_CELL = -1  # key of a point outside the representable range
_BITS = 15  # bits per coordinate of a key
_OFFSET = 1 << (_BITS - 1)
MAX_CELL_DIM = 63 // _BITS  # state variables a key holds (4: one body or a pair); the
# scene reader refuses cells for larger states, and cell_key raises for them


@njit(cache=True)
def new_cells():
    """An empty table {cell key: label code}."""
    return Dict.empty(key_type=types.int64, value_type=types.int64)


@njit(cache=True)
def cell_key(y, cell_size):
    """Integer key of the cell holding y, or NO_CELL when a coordinate is beyond range.
    A state of more than MAX_CELL_DIM coordinates has no key: a ValueError, never a
    silent switch-off."""
    if y.shape[0] > MAX_CELL_DIM:
        raise ValueError("recurrence cells hold at most 4 state variables (kernels/cells.py)")
    key = 0
    for i in range(y.shape[0]):
        k = np.floor(y[i] / cell_size)
        if not (-_OFFSET <= k < _OFFSET):
            return NO_CELL
        key |= (int(k) + _OFFSET) << (_BITS * i)
    return key


@njit(cache=True)
def remember_cells(cells, visited, n_visited, code):
    """Mark the cells of ``visited[:n_visited]`` with ``code`` (MIXED_CELL where they disagree)."""
    for i in range(n_visited):
        key = visited[i]
        if key == NO_CELL:
            continue
        if key in cells:
            if cells[key] != code:
                cells[key] = MIXED_CELL
        else:
            cells[key] = code
