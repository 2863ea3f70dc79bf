"""One colour per solution, the same in every panel and every figure of a system.

A system's catalogue numbers its solutions in a fixed order (attractors by period and
amplitude, combinations by left attractor, right attractor and shift), and that order is
the same in every result of the system, whatever d, phi, k_c or c_c. Solutions take
colours from DISTINCT in that order, so no two solutions of one catalogue share a colour
(up to len(DISTINCT)); impacting solutions share one extra colour (brown), except the
second, third... impacting orbit of one period at one point (``impacting P1^2``,
``analysis.impacting``), which take their own (IMPACTING_NUMBERED); unresolved and
diverged outcomes have their own; chaotic and quasi-periodic attractors take one each.
Without the catalogue order (a bare name), a name falls back to a stable hash of itself.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence

from ..analysis.attributes import attribute_list

IMPACTING = "#8c564b"  # every impacting solution shares one extra colour, but:
# impacting P{p}^2, ^3, ...: another impacting orbit of the same period (tab20's light
# brown, then tones none of the lists here uses), so two impacting basins are drawn apart
IMPACTING_NUMBERED = ["#c49c94", "#4e2a1e", "#d4a017", "#5f9ea0", "#b05f3c", "#2f4f4f"]
SPECIAL = {"unresolved": "#7f7f7f", "diverged": "#000000"}
# 30 colours, the most distinct first (tab10 without brown and grey, then tab20's light
# partners, then darker tab20b/tab20c tones); brown and grey stay reserved above.
DISTINCT = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#e377c2", "#bcbd22", "#17becf",
    "#393b79", "#637939", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#f7b6d2",
    "#dbdb8d", "#9edae5", "#8c6d31", "#843c39", "#7b4173", "#3182bd", "#e6550d", "#31a354",
    "#756bb1", "#fd8d3c", "#74c476", "#9e9ac8", "#6baed6", "#e7969c",
]

# chaotic and quasi-periodic attractors A1, A2, ...: deep tones none of the above uses
NOT_PERIODIC = ["#d81b60", "#00897b", "#1a237e", "#827717", "#6a1b9a", "#e65100"]


def solution_order(ds) -> list[str]:
    """The catalogue's solution names in catalogue order (pairs: combinations; one body:
    attractors), from any result that carries the catalogue or its ``catalogue_names``
    attribute; [] if it does not."""
    for var in ("combination_name", "attractor_name"):
        if var in ds:
            return [str(n) for n in ds[var].values]
    # results without the catalogue's arrays (continuation)
    return [str(n) for n in attribute_list(ds.attrs, "catalogue_names")]


def colour_of(name: str, order: Sequence[str] = ()) -> str:
    """Colour of a solution name; ``order`` is ``solution_order`` of the result drawn.
    Attractors that are not periodic ("impacting chaotic A1", ...) each take their own
    colour (by hash), impacting or not: they are few and must be told apart."""
    if " A" in name and ("chaotic" in name or "quasi-periodic" in name):
        number = name.rsplit(" A", 1)[1]
        if number.isdigit():
            return NOT_PERIODIC[(int(number) - 1) % len(NOT_PERIODIC)]
    if name.startswith("impacting"):
        number = name.rsplit("^", 1)[1] if "^" in name else ""
        if number.isdigit() and int(number) >= 2:
            return IMPACTING_NUMBERED[(int(number) - 2) % len(IMPACTING_NUMBERED)]
        return IMPACTING
    if name in SPECIAL:
        return SPECIAL[name]
    if name in order:
        return DISTINCT[list(order).index(name) % len(DISTINCT)]
    digest = int(hashlib.sha256(name.encode()).hexdigest(), 16)
    return DISTINCT[digest % len(DISTINCT)]
