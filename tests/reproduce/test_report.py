"""End to end: `softimpact reproduce` on a few statements writes the table with a row
each, verdicts from the checks, and the runs it used (quick sizes said so)."""

import re
import shlex
from pathlib import Path

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.reproduce.report import reproduce

ROOT = Path(__file__).parents[2]


def test_statements_without_runs_end_to_end(tmp_path):
    out = tmp_path / "table.md"
    result = CliRunner().invoke(main, ["reproduce", "--only", "S1,S4,S41", "-o", str(out),
                                       "--cache", str(tmp_path / "cache"), "--quiet"])
    assert result.exit_code == 0, result.output
    assert "3 statements (reproduced 2, not computable 1)" in result.output
    text = out.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| S")]
    assert [r.split(" | ")[0] for r in rows] == ["| S1", "| S4", "| S41"]
    assert "k2 = 0.01" in rows[0] and "| reproduced |" in rows[0]
    assert "not computable: a claim about all parameters" in rows[2]


def test_missing_runs_are_not_checked_yet_with_cached_only(tmp_path):
    rows, text = reproduce(only="S9", cached_only=True, cache=tmp_path)
    assert rows[0]["verdict"].startswith("not checked yet: needs run fig05")
    assert "softimpact sweep configs/figures/fig05_duffing_dcrit.toml" in rows[0]["verdict"]


def test_bad_only_is_one_error_line():
    result = CliRunner().invoke(main, ["reproduce", "--only", "S99", "-o", "/dev/null"])
    assert result.exit_code == 2 and "no statement S99" in result.output


def readme_reproduce_line() -> list[str]:
    """The quick line of the site's page on reproducing the study (once the README's)."""
    text = (ROOT / "docs" / "howto" / "reproduce.md").read_text()
    lines = [m.group(1) for m in re.finditer(
        r"^(?:\.venv/bin/)?(softimpact reproduce --quick[^\n]*)$", text, re.M)]
    assert lines, "docs/howto/reproduce.md shows a `softimpact reproduce --quick --only` line"
    return shlex.split(lines[0], comments=True)[1:]


@pytest.mark.slow
def test_readme_quick_reproduce_runs_and_says_quick(tmp_path, monkeypatch):
    """The docs' quick line (a catalogue and a d_crit run at --quick sizes)."""
    monkeypatch.chdir(tmp_path)
    words = readme_reproduce_line()
    result = CliRunner().invoke(main, [*words, "--cache", str(tmp_path / "cache"), "-q"])
    assert result.exit_code == 0, result.output
    out = tmp_path / words[words.index("-o") + 1]
    text = out.read_text()
    assert "QUICK run (reduced sizes)" in text
    rows = {line.split(" | ")[0][2:]: line for line in text.splitlines()
            if line.startswith("| S")}
    assert "| reproduced |" in rows["S5"]  # the four Duffing combinations at phi = 0
    assert "| reproduced |" in rows["S7"]  # d_crit = 0 in phase
    assert not any("not checked yet" in row for row in rows.values())
    assert list((tmp_path / "cache").glob("fig04-*.h5"))  # the run is cached
