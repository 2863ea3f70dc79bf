"""The study's names for solutions (SPEC.md section 3), their parser, and the shift rule.

ASCII names:

- ``L{p}^{n}``: one body on its attractor number n of period p (one-body scenes);
- ``L{pl}^{nl} R{pr}-{s}^{nr}``: the pair, left body on attractor nl (period pl), right body
  on attractor nr (period pr), relative shift s;
- ``impacting P{p}``: a periodic solution with contact in the steady state, period p;
- ``unresolved``, ``diverged``: outcomes that are not periodic orbits;
- ``unmatched P{p}``: a non-impacting periodic orbit that matches no catalogue attractor;
- ``chaotic A{n}``, ``quasi-periodic A{n}`` and their ``impacting`` forms: attractor
  number n that is not periodic (found by the second stage, :mod:`.nonperiodic`).

**The shift s.** Each body's attractor has its p section points ordered canonically:
point 0 is the one with the largest displacement x, point i+1 is the stroboscopic map's
image of point i. At a section time, if the left body sits at index j and the right body
at index k, then ``s = (k - j) mod gcd(pl, pr)``. Both indices advance by one per forcing
period, so s is the same at every section time of the orbit, and there are exactly
``gcd(pl, pr)`` distinct combinations of two attractors.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from math import gcd

from ..kernels.codes import (
    BASE_WIDTH,
    DIVERGED_LABEL,
    IMPACTING_BASE,
    NONPERIODIC_BASES,
    PENDING,
    UNMATCHED_BASE,
    UNRESOLVED_LABEL,
)

UNRESOLVED = "unresolved"
DIVERGED = "diverged"


@dataclass(frozen=True)
class Label:
    """A parsed name. ``kind``: 'body', 'pair', 'impacting', 'unmatched', 'unresolved',
    'diverged', or one of ``NONPERIODIC_KINDS`` ('chaotic', 'impacting chaotic',
    'quasi-periodic', 'impacting quasi-periodic': attractor number ``left``)."""

    kind: str
    period: int = 0
    left: int = 0
    right_period: int = 0
    shift: int = 0
    right: int = 0

    @property
    def name(self) -> str:
        if self.kind == "pair":
            return (f"L{self.period}^{self.left} "
                    f"R{self.right_period}-{self.shift}^{self.right}")
        if self.kind == "body":
            return f"L{self.period}^{self.left}"
        if self.kind in ("impacting", "unmatched"):
            return f"{self.kind} P{self.period}"
        if self.kind in NONPERIODIC_KINDS:
            return f"{self.kind} A{self.left}"
        return self.kind

    @property
    def latex(self) -> str:
        if self.kind == "pair":
            return (f"$L^{{{self.left}}}_{{{self.period}}}"
                    f"R^{{{self.right}}}_{{{self.right_period}-{self.shift}}}$")
        if self.kind == "body":
            return f"$L^{{{self.left}}}_{{{self.period}}}$"
        if self.kind in ("impacting", "unmatched"):
            return f"{self.kind} $P_{{{self.period}}}$"
        if self.kind in NONPERIODIC_KINDS:
            return f"{self.kind} $A_{{{self.left}}}$"
        return self.kind


NONPERIODIC_KINDS = tuple(NONPERIODIC_BASES)
_PAIR = re.compile(r"^L(\d+)\^(\d+) R(\d+)-(\d+)\^(\d+)$")
_BODY = re.compile(r"^L(\d+)\^(\d+)$")
_PERIODIC = re.compile(r"^(impacting|unmatched) P(\d+)$")
_NONPERIODIC = re.compile(r"^((?:impacting )?(?:chaotic|quasi-periodic)) A(\d+)$")


def parse_label(name: str) -> Label:
    """Parse an ASCII name; ValueError names the allowed forms."""
    if m := _PAIR.match(name):
        pl, nl, pr, s, nr = map(int, m.groups())
        if min(pl, nl, pr, nr) < 1 or s >= gcd(pl, pr):
            raise ValueError(f"{name!r}: periods and numbers start at 1 and the shift must "
                             f"be < gcd({pl}, {pr}) = {gcd(pl, pr)}")
        return Label("pair", pl, nl, pr, s, nr)
    if m := _BODY.match(name):
        p, n = map(int, m.groups())
        if min(p, n) < 1:
            raise ValueError(f"{name!r}: period and number start at 1")
        return Label("body", p, n)
    if m := _PERIODIC.match(name):
        if int(m.group(2)) < 1:
            raise ValueError(f"{name!r}: the period starts at 1")
        return Label(m.group(1), int(m.group(2)))
    if m := _NONPERIODIC.match(name):
        if not 1 <= int(m.group(2)) < BASE_WIDTH:
            raise ValueError(f"{name!r}: attractor numbers run from 1 to {BASE_WIDTH - 1}")
        return Label(m.group(1), left=int(m.group(2)))
    if name in (UNRESOLVED, DIVERGED):
        return Label(name)
    raise ValueError(
        f"cannot read label {name!r}: use 'L1^1 R1-0^2' (pair), 'L2^1' (one body), "
        "'impacting P3', 'unmatched P3', 'chaotic A1', 'impacting quasi-periodic A2', "
        "'unresolved' or 'diverged'"
    )


def n_shifts(left_period: int, right_period: int) -> int:
    """Number of distinct relative shifts of two periodic orbits: gcd(pl, pr)."""
    return gcd(left_period, right_period)


def shift(left_index: int, right_index: int, left_period: int, right_period: int) -> int:
    """The shift s = (k - j) mod gcd(pl, pr) of bodies at canonical indices j (left), k."""
    return (right_index - left_index) % gcd(left_period, right_period)


def code_of(label: Label, catalogue_names: tuple[str, ...]) -> int:
    """Integer code of a label (``kernels.codes``, section 2), given the catalogue's names
    in code order."""
    if label.kind in ("pair", "body"):
        name = label.name
        if name in catalogue_names:
            return catalogue_names.index(name)
        return UNMATCHED_BASE + label.period  # a catalogue from other parameters
    if label.kind == "impacting":
        return IMPACTING_BASE + label.period
    if label.kind == "unmatched":
        return UNMATCHED_BASE + label.period
    if label.kind in NONPERIODIC_KINDS:
        return NONPERIODIC_BASES[label.kind] + label.left
    return UNRESOLVED_LABEL if label.kind == UNRESOLVED else DIVERGED_LABEL


def name_of(code: int, catalogue_names: tuple[str, ...]) -> str:
    """The ASCII name of an integer code."""
    code = int(code)
    if 0 <= code < len(catalogue_names):
        return catalogue_names[code]
    if code == UNRESOLVED_LABEL:
        return UNRESOLVED
    if code == DIVERGED_LABEL:
        return DIVERGED
    if code == PENDING:
        return "pending"
    if UNMATCHED_BASE < code < UNMATCHED_BASE + 1000:
        return f"unmatched P{code - UNMATCHED_BASE}"
    if IMPACTING_BASE < code < IMPACTING_BASE + 1000:
        return f"impacting P{code - IMPACTING_BASE}"
    for kind, base in NONPERIODIC_BASES.items():
        if base < code < base + BASE_WIDTH:
            return f"{kind} A{code - base}"
    raise ValueError(f"unknown label code {code}")


def latex_of(name: str) -> str:
    """LaTeX form of a name (the name itself when it does not parse)."""
    try:
        return parse_label(name).latex
    except ValueError:
        return name
