"""Recurrence cells: the labels earlier trajectories gave to boxes of the section.

A cell is a box of side ``cell_size`` in the state space of the stroboscopic section (the
idea of Attractors.jl's recurrences method). Every section point a classified trajectory
visited marks its cell with that trajectory's label code; a cell that two trajectories
with different labels visited is marked ``MIXED_CELL`` and never used again. A later
trajectory whose section points land in cells of one label for ``cell_hits``
consecutive periods takes that label without integrating further. Cells are only valid
for one parameter point: the caller starts a new table for each.

**Keys.** A cell is its integer coordinates ``floor(y_i / cell_size)``, each within
``[-2**14, 2**14)`` (beyond: ``NO_CELL``), 15 bits each. Up to ``PACKED_DIM`` = 4
coordinates (one body or a pair) pack exactly into one int64 >= 0: the key is the packing,
as before. From 5 to ``MAX_CELL_DIM`` = 16 coordinates (eight bodies) the coordinates pack
exactly into four int64 words, and the key is a slot number >= 0 found by hashing the
words with linear probing *in the table itself*: slot k's words are kept under the
negative keys ``-2 - 4k - i`` (i = 0..3; -1 is NO_CELL), so a slot is a cell's only when
its four stored words are the cell's (the collision check), and a cell met again finds
its slot again. Keys of labels (>= 0) and of words (<= -2) never meet, and the kernels
keep one table argument (``classify_near`` passes its table; a second typed dict would
cost an argument, a tuple of two ~40 us per call).
"""

import numpy as np
from numba import njit, types
from numba.typed import Dict

from .codes import MIXED_CELL

NO_CELL = -1  # key of a point outside the representable range
_BITS = 15  # bits per coordinate of a key
_OFFSET = 1 << (_BITS - 1)
PACKED_DIM = 63 // _BITS  # coordinates one int64 holds exactly (4: one body or a pair)
WORDS = 4  # int64 words of a wide cell's coordinates
MAX_CELL_DIM = WORDS * PACKED_DIM  # 16 state variables: eight bodies; the scene reader
# refuses cells for larger states, and cell_key raises for them
_SLOT_MASK = (1 << 60) - 1  # slots 0 .. 2**60 - 1: their word keys -2 - 4 k - i fit int64
_MIX = 1000003  # odd multiplier of the words' hash (linear probing settles collisions)


@njit(cache=True)
def new_cells():
    """An empty table {cell key: label code} (and, for wide states, {-2 - 4k - i: word i
    of slot k's cell})."""
    return Dict.empty(key_type=types.int64, value_type=types.int64)


@njit(cache=True)
def _packed_word(y, first, stop, cell_size):
    """Coordinates ``first .. stop - 1`` of y's cell packed into one int64 >= 0 (15 bits
    each), or NO_CELL when one is beyond range (or not finite)."""
    word = 0
    for i in range(first, stop):
        k = np.floor(y[i] / cell_size)
        if not (-_OFFSET <= k < _OFFSET):
            return NO_CELL
        word |= (int(k) + _OFFSET) << (_BITS * (i - first))
    return word


@njit(cache=True)
def _word_key(slot, i):
    return -2 - WORDS * slot - i


@njit(cache=True)
def cell_key(y, cell_size, table):
    """Integer key (>= 0) of the cell holding y, or NO_CELL when a coordinate is beyond
    range. Up to PACKED_DIM coordinates the key is the packing itself (``table`` unused);
    up to MAX_CELL_DIM it is the slot of ``table`` (from ``new_cells``) that holds the
    cell's packed words, claimed for a cell not met before. A state of more than
    MAX_CELL_DIM coordinates has no key: a ValueError, never a silent switch-off."""
    dim = y.shape[0]
    if dim <= PACKED_DIM:
        return _packed_word(y, 0, dim, cell_size)
    if dim > MAX_CELL_DIM:
        raise ValueError("recurrence cells hold at most 16 state variables (kernels/cells.py)")
    words = np.zeros(WORDS, dtype=np.int64)
    h = 0
    for j in range(WORDS):
        first = j * PACKED_DIM
        if first < dim:
            words[j] = _packed_word(y, first, min(dim, first + PACKED_DIM), cell_size)
            if words[j] == NO_CELL:
                return NO_CELL
        h = ((h ^ words[j]) * _MIX) & _SLOT_MASK
    slot = h
    while True:
        if _word_key(slot, 0) not in table:  # a free slot: the cell's from now on
            for j in range(WORDS):
                table[_word_key(slot, j)] = words[j]
            return slot
        same = True
        for j in range(WORDS):
            if table[_word_key(slot, j)] != words[j]:
                same = False
                break
        if same:
            return slot
        slot = (slot + 1) & _SLOT_MASK  # another cell's slot: the next one


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
