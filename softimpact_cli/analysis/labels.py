"""The study's names for solutions (SPEC.md section 3), their parser, and the shift rule.

ASCII names:

- ``L{p}^{n}``: one body on its attractor number n of period p (one-body scenes);
- ``L{pl}^{nl} R{pr}-{s}^{nr}``: the pair, left body on attractor nl (period pl), right body
  on attractor nr (period pr), relative shift s;
- ``B1:P{p1}^{n1} B2:P{p2}-{s2}^{n2} ... Bk:P{pk}-{sk}^{nk}``: k >= 3 bodies, one token per
  body in body order: body i on its attractor number ni of period pi, shifted by si (the
  first body's shift is 0 and not written; see **Shifts** below);
- ``impacting P{p}``, ``impacting P{p}^{m}``: a periodic solution with contact in the
  steady state, period p; m >= 2 numbers the distinct impacting orbits of period p met at
  one parameter point (``impacting P{p}`` is number 1, the first met; see
  :mod:`.impacting`);
- ``unresolved``, ``diverged``: outcomes that are not periodic orbits;
- ``unmatched P{p}``: a non-impacting periodic orbit that matches no catalogue attractor;
- ``chaotic A{n}``, ``quasi-periodic A{n}`` and their ``impacting`` forms: attractor
  number n that is not periodic (found by the second stage, :mod:`.nonperiodic`).

**Shifts.** Each body's attractor has its p section points ordered canonically: point 0
is the one with the largest displacement x, point i+1 is the stroboscopic map's image of
point i. At a section time the bodies sit at indices (j1, ..., jk) of their attractors;
one forcing period later at (j1 + 1, ..., jk + 1). A combination of attractors is
therefore an orbit of index tuples under that common advance: there are
``p1 p2 ... pk / lcm(p1, ..., pk)`` of them (:func:`n_combinations`). Its shifts are the
index tuple at the section time where body 1 sits at index 0 whose remaining indices
(s2, ..., sk) come first in lexicographic order (:func:`shifts`). For two bodies this is
``s = (k - j) mod gcd(pl, pr)``, the pair's rule: s is the same at every section time of
the orbit, and there are exactly ``gcd(pl, pr)`` distinct combinations of two attractors.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from itertools import product
from math import gcd, lcm, prod

from ..kernels.codes import (
    BASE_WIDTH,
    CATALOGUE_WIDTH,
    DIVERGED_LABEL,
    EXTENDED_CATALOGUE_BASE,
    IMPACTING_BASE,
    NONPERIODIC_BASES,
    NUMBERED_IMPACTING_BASE,
    PENDING,
    UNMATCHED_BASE,
    UNRESOLVED_LABEL,
)

UNRESOLVED = "unresolved"
DIVERGED = "diverged"
MAX_NAMED_BODIES = 8  # bodies a name (and a label code) holds; tested at this size


@dataclass(frozen=True)
class BodyToken:
    """One body's part of a non-impacting name: its attractor's period and number, and
    its shift (0 for the first body)."""

    period: int
    number: int
    shift: int = 0


@dataclass(frozen=True)
class Label:
    """A parsed name. ``kind``: 'body', 'pair', 'bodies' (three or more, ``tokens``),
    'impacting' (period ``period``, number ``left``: 0 for the first, 2, 3, ... for the
    others met at one parameter point), 'unmatched',
    'unresolved', 'diverged', or one of ``NONPERIODIC_KINDS`` ('chaotic', 'impacting
    chaotic', 'quasi-periodic', 'impacting quasi-periodic': attractor number ``left``).
    Build a non-impacting one from its body tokens with :func:`bodies_label`."""

    kind: str
    period: int = 0
    left: int = 0
    right_period: int = 0
    shift: int = 0
    right: int = 0
    tokens: tuple[BodyToken, ...] = ()

    @property
    def body_tokens(self) -> tuple[BodyToken, ...]:
        """One token per body (one body, a pair, or more); empty for the other kinds."""
        if self.kind == "body":
            return (BodyToken(self.period, self.left),)
        if self.kind == "pair":
            return (BodyToken(self.period, self.left),
                    BodyToken(self.right_period, self.right, self.shift))
        return self.tokens

    @property
    def name(self) -> str:
        return self._written(PLAIN)

    @property
    def latex(self) -> str:
        return self._written(LATEX)

    def _written(self, notation: int) -> str:
        """The name (``PLAIN``) or its matplotlib mathtext (``LATEX``), from the kind's
        formats in ``_NOTATION``; a kind without formats is written as itself."""
        if self.kind == "bodies":
            token, separator, whole = _BODIES_NOTATION
            return whole[notation].format(separator[notation].join(
                token[notation].format(body=i + 1, period=t.period, number=t.number,
                                       shift=f"-{t.shift}" if i else "")
                for i, t in enumerate(self.tokens)))
        formats = _NOTATION.get(self.kind)
        if formats is None:
            return self.kind
        number = (("^{}", "^{{{}}}")[notation].format(self.left)
                  if self.left > 1 else "")  # of an impacting orbit past the first
        return formats[notation].format(**vars(self), number=number)


def bodies_label(tokens) -> Label:
    """The label of bodies on the attractors ``tokens`` (a BodyToken per body, shifts
    canonical): 'body' for one, 'pair' for two (the L/R names), 'bodies' for more."""
    tokens = tuple(tokens)
    if len(tokens) == 1:
        return Label("body", tokens[0].period, tokens[0].number)
    if len(tokens) == 2:
        a, b = tokens
        return Label("pair", a.period, a.number, b.period, b.shift, b.number)
    return Label("bodies", lcm(*(t.period for t in tokens)), tokens=tokens)


def n_combinations(periods) -> int:
    """Number of distinct combinations of attractors of these periods (one per body):
    p1 p2 ... pk / lcm(p1, ..., pk) (gcd(pl, pr) for a pair, 1 for one body)."""
    periods = tuple(periods)
    return prod(periods) // lcm(*periods)


def shift_bounds(periods) -> tuple[int, ...]:
    """(1, g2, ..., gk): body i's shift runs over 0 .. gi - 1, gi = gcd(lcm(p1, ..., p(i-1)),
    pi) (the first body's is always 0). Their product is ``n_combinations(periods)``."""
    bounds, common = [1], periods[0]
    for p in periods[1:]:
        bounds.append(gcd(common, p))
        common = lcm(common, p)
    return tuple(bounds)


def shifts(indices, periods) -> tuple[int, ...]:
    """The canonical shifts (0, s2, ..., sk) of bodies at indices (j1, ..., jk) of
    attractors of periods (p1, ..., pk): of the section times where body 1 sits at index
    0, the one whose remaining indices come first in lexicographic order. Every section
    time of one combination gives the same shifts.

    Greedy: the advances t that bring body 1 to 0 are t0 + p1 Z; the least index body 2
    reaches over them is (j2 + t0) mod gcd(p1, p2), reached on t1 + lcm(p1, p2) Z; and so
    on, body i's shift being below gcd(lcm(p1 .. p(i-1)), pi) (:func:`shift_bounds`)."""
    periods = tuple(periods)
    t, step = -indices[0] % periods[0], periods[0]
    out = [0]
    for j, p in zip(indices[1:], periods[1:], strict=True):
        g = gcd(step, p)
        s = (j + t) % g
        # the advance t + step * m (m < p / g) that puts this body at index s exactly
        t += step * next(m for m in range(p // g) if (j + t + step * m) % p == s)
        step = lcm(step, p)
        out.append(s)
    return tuple(out)


def shift(left_index: int, right_index: int, left_period: int, right_period: int) -> int:
    """The shift s = (k - j) mod gcd(pl, pr) of bodies at canonical indices j (left), k."""
    return (right_index - left_index) % gcd(left_period, right_period)


def n_shifts(left_period: int, right_period: int) -> int:
    """Number of distinct relative shifts of two periodic orbits: gcd(pl, pr)."""
    return gcd(left_period, right_period)


def all_shifts(periods) -> list[tuple[int, ...]]:
    """Every canonical shift tuple of attractors of these periods, in lexicographic
    order (``n_combinations(periods)`` of them)."""
    return [(0, *rest) for rest in product(*(range(g) for g in shift_bounds(periods)[1:]))]


NONPERIODIC_KINDS = tuple(NONPERIODIC_BASES)
PLAIN, LATEX = 0, 1  # the two notations of a label: its name, its mathtext
# per kind: (name, mathtext) formats of the Label's fields (``number``: "^n" of the n-th
# impacting orbit of a period met at one point, n > 1, else empty)
_NOTATION = {
    "pair": ("L{period}^{left} R{right_period}-{shift}^{right}",
             "$L^{{{left}}}_{{{period}}}R^{{{right}}}_{{{right_period}-{shift}}}$"),
    "body": ("L{period}^{left}", "$L^{{{left}}}_{{{period}}}$"),
    "impacting": ("impacting P{period}{number}", "impacting $P_{{{period}}}{number}$"),
    "unmatched": ("{kind} P{period}", "{kind} $P_{{{period}}}$"),
    **{kind: ("{kind} A{left}", "{kind} $A_{{{left}}}$") for kind in NONPERIODIC_KINDS},
}
# three or more bodies: (per body token, separator, whole) formats in each notation
_BODIES_NOTATION = (("B{body}:P{period}{shift}^{number}",
                     "B_{{{body}}}{{:}}P^{{{number}}}_{{{period}{shift}}}"),
                    (" ", r"\,"), ("{}", "${}$"))

_PAIR = re.compile(r"^L(\d+)\^(\d+) R(\d+)-(\d+)\^(\d+)$")
_BODY = re.compile(r"^L(\d+)\^(\d+)$")
_TOKEN = re.compile(r"^B(\d+):P(\d+)(?:-(\d+))?\^(\d+)$")
_IMPACTING = re.compile(r"^impacting P(\d+)(?:\^(\d+))?$")
_UNMATCHED = re.compile(r"^unmatched P(\d+)$")
_NONPERIODIC = re.compile(r"^((?:impacting )?(?:chaotic|quasi-periodic)) A(\d+)$")


def _parse_bodies(name: str) -> Label | None:
    """A name of three or more body tokens, checked; None when it is not of that form."""
    parts = name.split(" ")
    matches = [_TOKEN.match(p) for p in parts]
    if len(parts) < 3 or not all(matches):
        return None
    tokens = []
    for i, m in enumerate(matches):
        body, period, number = int(m.group(1)), int(m.group(2)), int(m.group(4))
        if body != i + 1 or (m.group(3) is None) != (i == 0):
            raise ValueError(f"{name!r}: tokens name bodies B1, B2, ... in order, every one "
                             "but the first with its shift ('B2:P1-0^2')")
        if min(period, number) < 1:
            raise ValueError(f"{name!r}: periods and numbers start at 1")
        tokens.append(BodyToken(period, number, int(m.group(3) or 0)))
    periods = tuple(t.period for t in tokens)
    bounds = shift_bounds(periods)
    for i, (t, g) in enumerate(zip(tokens, bounds, strict=True)):
        if t.shift >= g:
            raise ValueError(f"{name!r}: body {i + 1}'s shift must be < {g} (gcd of "
                             f"lcm{periods[:i]} and {t.period})")
    return bodies_label(tokens)


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
    if (label := _parse_bodies(name)) is not None:
        return label
    if m := _IMPACTING.match(name):
        p, number = int(m.group(1)), int(m.group(2) or 0)
        if p < 1 or m.group(2) is not None and not 2 <= number < BASE_WIDTH:
            raise ValueError(f"{name!r}: the period starts at 1; the first impacting orbit "
                             f"of a period has no number, the others 2 to {BASE_WIDTH - 1}")
        return Label("impacting", p, number)
    if m := _UNMATCHED.match(name):
        if int(m.group(1)) < 1:
            raise ValueError(f"{name!r}: the period starts at 1")
        return Label("unmatched", int(m.group(1)))
    if m := _NONPERIODIC.match(name):
        if not 1 <= int(m.group(2)) < BASE_WIDTH:
            raise ValueError(f"{name!r}: attractor numbers run from 1 to {BASE_WIDTH - 1}")
        return Label(m.group(1), left=int(m.group(2)))
    if name in (UNRESOLVED, DIVERGED):
        return Label(name)
    raise ValueError(
        f"cannot read label {name!r}: use 'L1^1 R1-0^2' (pair), 'L2^1' (one body), "
        "'B1:P2^1 B2:P1-0^2 B3:P2-1^1' (three or more bodies), 'impacting P3', "
        "'impacting P1^2', 'unmatched P3', 'chaotic A1', 'impacting quasi-periodic A2', "
        "'unresolved' or 'diverged'"
    )


def catalogue_code(index: int) -> int:
    """Label code of the catalogue's solution number ``index`` (0-based, code order):
    the index itself below CATALOGUE_WIDTH, EXTENDED_CATALOGUE_BASE + index beyond (the
    combinations of many bodies)."""
    return index if index < CATALOGUE_WIDTH else EXTENDED_CATALOGUE_BASE + index


def catalogue_index(code: int) -> int:
    """The catalogue index of a code (inverse of :func:`catalogue_code`), or -1."""
    if 0 <= code < CATALOGUE_WIDTH:
        return code
    if code >= EXTENDED_CATALOGUE_BASE + CATALOGUE_WIDTH:
        return code - EXTENDED_CATALOGUE_BASE
    return -1


def impacting_code(period: int, number: int = 1) -> int:
    """Label code of impacting orbit ``number`` of period p: IMPACTING_BASE + p for the
    first (the code of every impacting P{p} before orbits were numbered),
    NUMBERED_IMPACTING_BASE + BASE_WIDTH * number + p for the others."""
    if number <= 1:
        return IMPACTING_BASE + period
    return NUMBERED_IMPACTING_BASE + BASE_WIDTH * number + period


def code_of(label: Label, catalogue_names) -> int:
    """Integer code of a label (``kernels.codes``, section 2), given the catalogue's names
    in code order (a tuple, or a {name: index} dict for many)."""
    if label.kind in ("pair", "body", "bodies"):
        index = _index(catalogue_names, label.name)
        if index >= 0:
            return catalogue_code(index)
        return UNMATCHED_BASE + label.period  # a catalogue from other parameters
    if label.kind == "impacting":
        return impacting_code(label.period, label.left)
    if label.kind == "unmatched":
        return UNMATCHED_BASE + label.period
    if label.kind in NONPERIODIC_KINDS:
        return NONPERIODIC_BASES[label.kind] + label.left
    return UNRESOLVED_LABEL if label.kind == UNRESOLVED else DIVERGED_LABEL


def _index(names, name: str) -> int:
    if isinstance(names, dict):
        return names.get(name, -1)
    return names.index(name) if name in names else -1


def name_of(code: int, catalogue_names) -> str:
    """The ASCII name of an integer code."""
    code = int(code)
    index = catalogue_index(code)
    if 0 <= index < len(catalogue_names):
        return tuple(catalogue_names)[index]
    if code == UNRESOLVED_LABEL:
        return UNRESOLVED
    if code == DIVERGED_LABEL:
        return DIVERGED
    if code == PENDING:
        return "pending"
    if UNMATCHED_BASE < code < UNMATCHED_BASE + BASE_WIDTH:
        return f"unmatched P{code - UNMATCHED_BASE}"
    if IMPACTING_BASE < code < IMPACTING_BASE + BASE_WIDTH:
        return f"impacting P{code - IMPACTING_BASE}"
    number, period = divmod(code - NUMBERED_IMPACTING_BASE, BASE_WIDTH)
    if 2 <= number < BASE_WIDTH and period >= 1:
        return Label("impacting", period, number).name
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
