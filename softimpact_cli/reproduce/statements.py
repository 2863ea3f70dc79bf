"""The study's statements (statements.toml, shipped as package data): read and checked."""

from __future__ import annotations

import re
import tomllib
from importlib import resources

from .checks import CHECKS

RULES = ("value", "count", "names", "share", "holds", "none")
ID = re.compile(r"^S([1-9][0-9]*)$")


def load(text: str | None = None) -> list[dict]:
    """Every statement, in id order; ValueError names the first bad entry."""
    if text is None:
        text = resources.files(__package__).joinpath("statements.toml").read_text()
    entries = tomllib.loads(text).get("statement", [])

    seen = set()
    for e in entries:
        sid = e.get("id", "?")
        if not ID.match(str(sid)):
            raise ValueError(f"statement {sid!r}: id must be S<number>")
        if sid in seen:
            raise ValueError(f"statement {sid}: id given twice")
        seen.add(sid)
        for key in ("where", "text", "rule"):
            if not isinstance(e.get(key), str) or not e[key]:
                raise ValueError(f"statement {sid}: {key} is required (text)")
        if e["rule"] not in RULES:
            raise ValueError(f"statement {sid}: rule {e['rule']!r}; one of {', '.join(RULES)}")
        if e["rule"] == "none":
            if not e.get("why"):
                raise ValueError(f"statement {sid}: rule 'none' needs why")
        elif e.get("check") not in CHECKS:
            raise ValueError(f"statement {sid}: check {e.get('check')!r} is not in checks.py")
        if "reading" in e and (not isinstance(e["reading"], str) or not e["reading"]):
            raise ValueError(f"statement {sid}: reading must be a text")
        if e["rule"] in ("value", "count", "names", "share") and "study" not in e:
            raise ValueError(f"statement {sid}: rule {e['rule']!r} needs the study's value")
    return sorted(entries, key=lambda e: int(e["id"][1:]))


def select(statements: list[dict], only: str | None) -> list[dict]:
    """The statements named in ``only`` ("S9,S10" or "S9-S11"), all when None."""
    if not only:
        return statements
    wanted = set()
    for part in only.replace(" ", "").split(","):
        if "-" in part:
            a, b = part.split("-", 1)
            if not (ID.match(a) and ID.match(b)):
                raise ValueError(f"--only: cannot read {part!r}; use S9, S9-S11 or S9,S12")
            wanted |= {f"S{k}" for k in range(int(a[1:]), int(b[1:]) + 1)}
        elif ID.match(part):
            wanted.add(part)
        else:
            raise ValueError(f"--only: cannot read {part!r}; use S9, S9-S11 or S9,S12")
    known = {s["id"] for s in statements}
    if wanted - known:
        raise ValueError(f"--only: no statement {sorted(wanted - known)[0]} "
                         f"(S1..S{len(statements)})")
    return [s for s in statements if s["id"] in wanted]
