"""Verdict rules: does softimpact's measured value agree with the study's statement?

A check returns a :class:`Measure` (the value at softimpact's defaults) with the
:class:`Measure` of every candidate explanation it tried (another start phase, the
study's integrator, a typo read the other way, ...). The verdict is

- ``reproduced``: the default value agrees within the study's stated precision;
- ``differs, explained``: it does not, but an explanation's run does (named in the row);
- ``differs, unexplained``: neither the value nor any explanation tried agrees;
- ``not computable``: no run can check the statement (the row says why);
- ``not checked yet``: the run it needs was not made (the row names it), or the value
  differs and a candidate explanation's run was not made.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

REPRODUCED = "reproduced"
EXPLAINED = "differs, explained"
UNEXPLAINED = "differs, unexplained"
NOT_COMPUTABLE = "not computable"
NOT_CHECKED = "not checked yet"
VERDICTS = (REPRODUCED, EXPLAINED, UNEXPLAINED, NOT_COMPUTABLE, NOT_CHECKED)


@dataclass
class Measure:
    """What a run gave. ``value``: a number, an integer count, a list of names, a list of
    shares (with ``ci``: their 95% Wilson intervals, one (low, high) each) or a bool (rule
    "holds"). ``shown``: the value as the table prints it, with interval or tolerance.
    ``label``: for an explanation, what was changed (e.g. "t0 = T/2")."""

    value: Any
    shown: str
    runs: tuple[str, ...] = ()
    ci: list[tuple[float, float]] | None = None
    tolerance: float = 0.0
    label: str = ""
    alternatives: list[Measure] = field(default_factory=list)
    note: str = ""
    pending: list[str] = field(default_factory=list)  # explanation runs not made yet
    caveat: str = ""  # an explanation that agrees but contradicts another run: not counted


def agrees(rule: str, study: Any, precision: float, m: Measure) -> bool:
    """Whether measure ``m`` agrees with the study's value under ``rule``."""
    if rule == "holds":
        return bool(m.value)
    if rule == "count":
        return int(m.value) == int(study)
    if rule == "names":
        return sorted(m.value) == sorted(study)
    if rule == "value":
        return abs(float(m.value) - float(study)) <= precision + m.tolerance
    if rule == "share":
        studied = study if isinstance(study, list) else [study]
        values = m.value if isinstance(m.value, list) else [m.value]
        if len(values) != len(studied) or m.ci is None:
            return False
        return all(lo - precision <= s <= hi + precision
                   for s, (lo, hi) in zip(studied, m.ci, strict=True))
    raise ValueError(f"unknown rule {rule!r}")


def verdict(statement: dict, m: Measure) -> tuple[str, str]:
    """(verdict, explanation text) of a statement given softimpact's measure."""
    rule, study = statement["rule"], statement.get("study")
    precision = float(statement.get("precision", 0.0))
    note = "; ".join(filter(None, [statement.get("reading", ""), m.note]))
    if agrees(rule, study, precision, m):
        return REPRODUCED, note
    tried = []
    explaining = []
    for alt in m.alternatives:
        ok = agrees(rule, study, precision, alt)
        said = "does not agree" if not ok else (
            f"agrees, not counted: {alt.caveat}" if alt.caveat else "agrees")
        tried.append(f"{alt.label}: {alt.shown} ({said}; run {', '.join(alt.runs)})")
        if ok and not alt.caveat:
            explaining.append(alt)
    text = "; ".join(filter(None, [note, *tried]))
    if explaining:
        return EXPLAINED, text
    if m.pending:
        return (f"{NOT_CHECKED}: differs; the explanation needs run "
                f"{', '.join(m.pending)}", text)
    return UNEXPLAINED, text or "no explanation tried"
