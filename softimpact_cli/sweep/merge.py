"""The parent's side of a sweep's chunks: their arrays into the result's flat arrays, their
representative orbits kept per (grid point, code), their impacting orbits renumbered over
the result (``analysis.impacting``). No I/O."""

from __future__ import annotations

from ..analysis.engine import Problem
from ..analysis.impacting import ImpactingOrbits
from .chunks import SweepContext


def keep_first_orbits(orbits: dict, found: dict) -> None:
    """Merge a chunk's representative orbits into ``orbits``: per (grid point, code) the
    one of the lowest flat index, whatever order the chunks finished in."""
    for key, (flat, pts) in found.items():
        if key not in orbits or flat < orbits[key][0]:
            orbits[key] = (flat, pts)


def impacting_numbering(context: SweepContext) -> ImpactingOrbits:
    """The result's numbering of impacting orbits (``analysis.impacting``): give it the
    chunks in flat order (``merge_chunk``)."""
    system = context.system()
    return ImpactingOrbits(
        lambda point: Problem(system, context.point_values(point)[0], context.integrator),
        context.label_tol)


def merge_chunk(arrays: dict, orbits: dict, numbering: ImpactingOrbits, context: SweepContext,
                start: int, stop: int, chunk: dict) -> None:
    """A chunk's arrays into the result's flat ``arrays`` and its orbits into ``orbits``,
    its impacting orbits renumbered over the result. Chunks in flat order. ``arrays``
    holds the fields of the sweep's system (``chunks.result_fields``)."""
    for key in arrays:
        arrays[key][start:stop] = chunk[key]
    found = numbering.merge_chunk(arrays["label"][start:stop], start,
                                  context.states.shape[0], chunk["orbits"])
    keep_first_orbits(orbits, found)
