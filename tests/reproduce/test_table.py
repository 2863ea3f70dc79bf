"""The table writer: a summary by verdict, then one row per statement."""

from softimpact_cli.reproduce.table import summary, write_table


def _row(sid, verdict):
    return {"id": sid, "where": "Fig 5", "text": "a | b", "value": "7.3", "command": "fig05",
            "verdict": verdict, "explanation": "tried t0"}


def test_summary_counts_verdicts_by_their_head():
    rows = [_row("S1", "reproduced"), _row("S2", "not checked yet: needs run fig06"),
            _row("S3", "not checked yet: needs run fig12"), _row("S4", "differs, explained")]
    counts = summary(rows)
    assert counts["reproduced"] == 1 and counts["not checked yet"] == 2
    assert counts["differs, explained"] == 1 and counts["differs, unexplained"] == 0


def test_table_has_the_header_summary_and_one_escaped_row_per_statement():
    rows = [_row("S1", "reproduced"), _row("S2", "differs, unexplained")]
    text = write_table(rows, "# title")
    lines = text.splitlines()
    assert lines[0] == "# title"
    assert "| reproduced | 1 |" in lines and "| differs, unexplained | 1 |" in lines
    body = [line for line in lines if line.startswith("| S")]
    assert len(body) == 2 and "a \\| b" in body[0]  # a pipe in a cell is escaped
    assert all(line.count(" | ") == 6 for line in body)  # 7 columns
