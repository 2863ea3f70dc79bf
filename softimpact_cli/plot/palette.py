"""One colour per label name, the same in every panel and every figure."""

from __future__ import annotations

import hashlib

# Fixed colours for the names that recur across the study's figures; others are derived
# from a stable hash of the name so that they never change between runs.
FIXED = {
    "L1^1": "#1f77b4", "L1^2": "#d62728", "L2^1": "#1f77b4", "L5^2": "#2ca02c",
    "L1^1 R1-0^1": "#1f77b4", "L1^1 R1-0^2": "#ff7f0e", "L1^2 R1-0^1": "#2ca02c",
    "L1^2 R1-0^2": "#d62728",
    "unresolved": "#7f7f7f", "diverged": "#000000",
}
IMPACTING = "#8c564b"  # every impacting solution shares one extra colour
CYCLE = ["#9467bd", "#e377c2", "#bcbd22", "#17becf", "#aec7e8", "#ffbb78", "#98df8a",
         "#ff9896", "#c5b0d5", "#c49c94", "#f7b6d2", "#dbdb8d", "#9edae5", "#393b79",
         "#637939", "#8c6d31", "#843c39", "#7b4173", "#3182bd", "#e6550d"]


def colour_of(name: str) -> str:
    if name in FIXED:
        return FIXED[name]
    if name.startswith("impacting"):
        return IMPACTING
    digest = int(hashlib.sha256(name.encode()).hexdigest(), 16)
    return CYCLE[digest % len(CYCLE)]
