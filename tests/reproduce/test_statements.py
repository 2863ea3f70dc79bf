"""The statements file: every one of the study's 89 statements exactly once, each with a
rule the verdicts know and a check that exists (or why none can)."""

import pytest

from softimpact_cli.reproduce.checks import CHECKS
from softimpact_cli.reproduce.statements import RULES, load, select


def test_all_89_statements_present_once_in_order():
    ids = [s["id"] for s in load()]
    assert ids == [f"S{k}" for k in range(1, 90)]


def test_every_statement_has_a_check_or_says_why_not():
    for s in load():
        assert s["rule"] in RULES
        if s["rule"] == "none":
            assert len(s["why"]) > 20
        else:
            assert s["check"] in CHECKS, s["id"]


def test_the_study_numbers_are_the_statement_numbers():
    by_id = {s["id"]: s for s in load()}
    assert by_id["S9"]["study"] == 7.44466 and by_id["S9"]["precision"] == 5e-6
    assert by_id["S81"]["study"] == [0.654, 0.176, 0.115, 0.055]
    assert "7.44466" in by_id["S9"]["text"]


def test_a_duplicate_or_malformed_entry_is_refused():
    entry = ('[[statement]]\nid = "S1"\nwhere = "x"\ntext = "t"\nrule = "holds"\n'
             'check = "rk4_available"\n')
    assert len(load(entry)) == 1
    with pytest.raises(ValueError, match="twice"):
        load(entry * 2)
    with pytest.raises(ValueError, match="rule"):
        load(entry.replace('"holds"', '"close"'))
    with pytest.raises(ValueError, match="not in checks.py"):
        load(entry.replace("rk4_available", "no_such_check"))
    with pytest.raises(ValueError, match="needs the study's value"):
        load(entry.replace('"holds"', '"value"'))
    with pytest.raises(ValueError, match="needs why"):
        load(entry.replace('"holds"', '"none"'))
    with pytest.raises(ValueError, match="S1: reading must be a text"):
        load(entry + "reading = 3\n")


def test_select_reads_lists_and_ranges_and_refuses_unknown_ids():
    statements = load()
    assert [s["id"] for s in select(statements, "S9-S11,S1")] == ["S1", "S9", "S10", "S11"]
    assert select(statements, None) == statements
    with pytest.raises(ValueError, match="no statement S90"):
        select(statements, "S90")
    with pytest.raises(ValueError, match="cannot read"):
        select(statements, "9")
