"""A rigid-stop result's own report: its labels' impacts per period and the counters'
names (the sweep's variables ``rigid_<name>``, ``sweep.chunks.RIGID_FIELDS``)."""

from __future__ import annotations

import numpy as np

# a rigid result's per-trajectory counters, variables ``rigid_<name>`` (sweep.chunks)
RIGID_COUNTERS = ("impacts", "chatter_sequences", "sticking_phases")


def impacts_per_period(label: np.ndarray, period: np.ndarray, contacts: np.ndarray,
                       table: dict[int, str]) -> dict[str, list[float]]:
    """{label name: its impacts per forcing period} of the trajectories on an impacting
    periodic orbit (period > 0, contacts > 0), from their final orbit's count (``contacts``)
    over its period; the distinct values, ascending (one unless a name covers several
    orbits). Arrays: one value per trajectory, same shape."""
    keep = (period > 0) & (contacts > 0)
    out = {}
    for code in np.unique(label[keep]):
        chosen = keep & (label == code)
        ratios = np.unique(contacts[chosen] / period[chosen].astype(float))
        out[table[int(code)]] = [float(v) for v in ratios]
    return out


def per_period_text(per_label: dict[str, list[float]]) -> str:
    """A rigid result's impacts per period, "impacting P1 1, impacting P2 1.5" (several
    values of one name joined by "or")."""
    return ", ".join(f"{name} {' or '.join(f'{v:g}' for v in values)}"
                     for name, values in per_label.items())
