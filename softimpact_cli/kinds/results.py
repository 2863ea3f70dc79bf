"""What ``info``, ``compare`` and the run warnings say about a result: the report
functions (``report``), given the result's kind from the registry.

``report`` knows no kind: each of its functions takes the kind (or its hooks) as an
argument, and these pass the one the result names in its ``analysis`` attribute.
"""

from __future__ import annotations

from ..report import compare as _compare
from ..report import info as _info
from ..report import info_text as _info_text
from ..report import outcomes as _outcomes
from . import KINDS


def kind_of_result(ds):
    """The AnalysisKind of a result (None for a kind this version does not know)."""
    return KINDS.get(str(ds.attrs.get("analysis")))


def describe(ds) -> dict:
    """Summary of a result dataset (``report.info.describe`` with its kind's part)."""
    return _info.describe(ds, kind_of_result(ds))


def format_summary(summary: dict, ds, max_points: int = 50) -> str:
    """The whole ``info`` text of a result (``summary`` from :func:`describe`)."""
    return _info_text.format_summary(summary, ds, max_points, kind_of_result(ds))


def outcome_counts(ds) -> tuple[int, int, int] | None:
    """(trajectories, unresolved, diverged) of a result as its kind counts them, or None."""
    kind = kind_of_result(ds)
    if kind is None or kind.outcome_counts is None:
        return None
    return kind.outcome_counts(ds)


def outcome_warnings(ds, max_periods: int, threshold: float = _outcomes.THRESHOLD,
                     section_periods: int = 0) -> list[str]:
    """Sentences about a result mostly unresolved or diverged, or an empty catalogue
    (``section_periods``: the second stage's budget after ``max_periods``, 0: off)."""
    return _outcomes.outcome_warnings(ds, max_periods, threshold, outcome_counts(ds),
                                      section_periods)


def comparable() -> tuple[str, ...]:
    """The kinds compare takes (those the registry gives a ``compare``)."""
    return _compare.comparable(KINDS)


def compare_results(a, b, name_a: str = "A", name_b: str = "B") -> dict:
    """The differences of result ``b`` from result ``a`` (``report.compare``)."""
    return _compare.compare_results(a, b, name_a, name_b, KINDS)


def format_comparison(report: dict, max_points: int = 20) -> str:
    """A compare report as plain text."""
    return _compare.format_comparison(report, KINDS[report["analysis"]].compare_text,
                                      max_points)
