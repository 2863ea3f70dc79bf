"""Run what the selected statements need and build the reproduction table."""

from __future__ import annotations

import datetime as _dt
import traceback
from pathlib import Path

from .. import __version__
from .checks import CHECKS
from .runs import CACHE, QUICK_PLANE, QUICK_SAMPLES, ROOT, RUNS, MissingRun, cache_path, execute
from .statements import load, select
from .table import write_table
from .verdicts import NOT_CHECKED, NOT_COMPUTABLE, verdict


def _value_text(m) -> str:
    return m.shown


def reproduce(quick: bool = False, only: str | None = None, workers: int | None = None,
              cached_only: bool = False, cache: Path = CACHE, echo=lambda s: None
              ) -> tuple[list[dict], str]:
    """(rows, markdown) of the statements selected by ``only`` (all when None).

    Each run a check asks for is executed once (or read from ``cache``); ``quick`` runs
    every scene at reduced size (planes at most 24 x 24, 100 random samples, the kinds'
    own --quick reductions) and the table says so; ``cached_only`` computes nothing and
    marks statements whose runs are not cached as not checked yet.
    """
    statements = select(load(), only)
    done: dict[str, object] = {}
    used: list[str] = []

    stood: dict[str, str] = {}  # run -> the stand-in used for it (--cached-only)
    row_stand_ins: set[str] = set()

    def runs(name: str):
        if name not in done:
            try:
                done[name] = execute(RUNS[name], quick, workers, cache, echo, cached_only)
            except MissingRun as missing:
                done[name] = missing
                stand_in = RUNS[name].stand_in
                if stand_in:
                    try:
                        done[name] = execute(RUNS[stand_in], quick, workers, cache, echo,
                                             cached_only)
                        stood[name] = stand_in
                    except MissingRun:
                        pass
        if isinstance(done[name], Exception):
            raise done[name]
        actual = stood.get(name, name)
        if actual not in used:
            used.append(actual)
        if name in stood:
            row_stand_ins.add(name)
        return done[name]

    rows = []
    for st in statements:
        row = {k: st[k] for k in ("id", "where", "text")}
        row.update(value="", command="", explanation="")
        row_stand_ins.clear()
        if st["rule"] == "none":
            row["verdict"] = f"{NOT_COMPUTABLE}: {st['why']}"
        else:
            try:
                m = CHECKS[st["check"]](st, runs)
                row["verdict"], row["explanation"] = verdict(st, m)
                row["value"] = _value_text(m)
                names = list(dict.fromkeys([*m.runs, *(r for a in m.alternatives
                                                       for r in a.runs)]))
                row["command"] = ", ".join(stood.get(n, n) for n in names)
                if row_stand_ins:
                    said = ", ".join(f"{stood[n]} for {n}" for n in sorted(row_stand_ins))
                    row["explanation"] = "; ".join(filter(None, [
                        f"measured on the lower-resolution stand-in ({said}): the full "
                        "run is not made yet", row["explanation"]]))
            except MissingRun as missing:
                row["verdict"] = (f"{NOT_CHECKED}: needs run {missing.name} "
                                  f"({RUNS[missing.name].command()})")
            except Exception as exc:  # noqa: BLE001 - a broken check is reported, not hidden
                echo(traceback.format_exc())
                row["verdict"] = (f"{NOT_CHECKED}: the check {st['check']} failed "
                                  f"({exc.__class__.__name__}: {exc})")
        rows.append(row)
        echo(f"{row['id']}: {row['verdict']}")
    header = _header(quick, only, cached_only)
    if stood:
        header += ("\n\n**Stand-ins:** the full runs " + ", ".join(sorted(stood)) + " were not "
                   "made when this table was written (`--cached-only`); their rows are "
                   "measured on the 50 x 50 stand-ins " + ", ".join(sorted(stood.values()))
                   + " and say so.")
    return rows, write_table(rows, header) + _runs_section(used, quick, cache)


def _header(quick: bool, only: str | None, cached_only: bool) -> str:
    now = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    size = (f"**QUICK run (reduced sizes): basin planes at most {QUICK_PLANE} x "
            f"{QUICK_PLANE}, at most {QUICK_SAMPLES} random samples per point (grids, "
            "catalogues, critical distances and bifurcation diagrams stay at full size); "
            "shares are not at the study's resolution.**"
            if quick else
            "Full resolution: every scene of configs/figures/ as stated there (pair basins "
            "200 x 200 per panel, one body 300 x 300, N = 1000 per basin-stability point).")
    return "\n".join([
        "# Reproducing the study, statement by statement",
        "",
        f"Made by `softimpact reproduce{' --quick' if quick else ''}"
        f"{' --cached-only' if cached_only else ''}{f' --only {only}' if only else ''}` "
        f"(softimpact {__version__}, {now}). "
        "Every softimpact number below was produced by the runs named in its row (listed "
        "at the end with the command that remakes each); the study's values are its own.",
        "",
        size,
        "",
        "Conventions: softimpact starts every trajectory at t0 = 0 (the study does not "
        "state its start phase); plane shares carry a 95% Wilson interval over the plane's "
        "cells, basin stability over its N samples; 'reproduced' means the study's value "
        "lies within softimpact's interval or tolerance widened by the study's stated "
        "precision (half its last digit). 'differs, explained' names the run of the "
        "explanation that agrees; 'differs, unexplained' lists what was tried.",
    ])


def _runs_section(used: list[str], quick: bool, cache: Path) -> str:
    lines = ["", "## Runs", "", "| run | what | command | result file |",
             "| --- | --- | --- | --- |"]
    for name in used:
        run = RUNS[name]
        path = cache_path(run.scene(quick), name, cache)
        try:
            shown = path.relative_to(ROOT)
        except ValueError:
            shown = path
        lines.append(f"| {name} | {run.note or 'the figure scene as it is'} | "
                     f"`{run.command()}{' --quick' if quick else ''}` | {shown} |")
    return "\n".join(lines) + "\n"
