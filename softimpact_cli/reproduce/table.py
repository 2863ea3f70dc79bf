"""The reproduction table (results/reproduce.md): one row per statement, a summary of
the verdicts first."""

from __future__ import annotations

from collections import Counter

from .verdicts import VERDICTS


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def summary(rows: list[dict]) -> dict[str, int]:
    """{verdict: number of rows}, in VERDICTS order (a verdict is the text before ':')."""
    counts = Counter(r["verdict"].split(":")[0] for r in rows)
    return {v: counts.get(v, 0) for v in VERDICTS}


def write_table(rows: list[dict], header: str) -> str:
    """The markdown of the table. ``rows``: id, where, text, study_value, value, command,
    verdict, explanation."""
    counts = summary(rows)
    lines = [header, "", "| verdict | statements |", "| --- | --- |"]
    lines += [f"| {v} | {n} |" for v, n in counts.items()]
    lines += ["", "| id | where | the study says | softimpact | command (runs) | verdict | "
              "why / what was tried |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        lines.append("| " + " | ".join(_cell(r[k]) for k in (
            "id", "where", "text", "value", "command", "verdict", "explanation")) + " |")
    return "\n".join(lines) + "\n"
