"""One function per kind of statement: it reads the runs it needs (``runs(name)`` returns
a result dataset) and returns softimpact's :class:`~.verdicts.Measure`, with the
candidate explanations it tried as alternatives. The study's numbers come from the
statement (``st``), softimpact's from the runs; nothing here is typed in from either."""

from __future__ import annotations

import math

from ..verdicts import Measure

CHECKS = {}
PI = math.pi


def check(name: str):
    def register(fn):
        CHECKS[name] = fn
        return fn
    return register


def _names(names) -> str:
    return ", ".join(names) if names else "none"


def _counted(names: list[str], what: str, run: str) -> Measure:
    """How many ``names`` there are, shown as "N what: a, b, c", read from ``run``."""
    return Measure(len(names), f"{len(names)} {what}: {_names(names)}", (run,))


def _pct(x: float) -> str:
    return f"{100 * x:.1f}%"


def _share_text(values, cis, n) -> str:
    return " / ".join(f"{_pct(v)} [{_pct(lo)}, {_pct(hi)}]" for v, (lo, hi)
                      in zip(values, cis, strict=True)) + f" (95% Wilson, n = {n})"




from . import basins, catalogues, distances, stability  # noqa: E402, F401  (they register)
