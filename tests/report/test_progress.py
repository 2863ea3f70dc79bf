"""Progress lines for logs: counts, rate, ETA, unresolved share; a last line at the end."""

import time

import numpy as np

from softimpact_cli.kernels.codes import DIVERGED_LABEL, UNRESOLVED_LABEL
from softimpact_cli.report.progress import ProgressLines, duration, interval_s


def test_lines_count_unresolved_and_end_with_the_total():
    lines = []
    p = ProgressLines(8, initial=2, interval=0.02, write=lines.append)
    p(np.array([0, UNRESOLVED_LABEL, 1]))
    deadline = time.monotonic() + 5
    while not lines and time.monotonic() < deadline:
        time.sleep(0.01)
    assert lines and lines[0].startswith("progress: 5/8 trajectories (62.5%), ")
    assert "ETA " in lines[0] and "unresolved 1 (33.33%)" in lines[0]
    p(np.array([DIVERGED_LABEL, 0, 0]))
    assert lines[-1].startswith("progress: 8/8 trajectories (100.0%), ")
    assert "unresolved 1 (16.67%)" in lines[-1] and "diverged 1 (16.67%)" in lines[-1]
    n = len(lines)
    time.sleep(0.1)
    assert len(lines) == n  # the timer stopped with the total


def test_counts_without_labels_say_nothing_about_unresolved():
    lines = []
    p = ProgressLines(3, unit="phases", interval=60, write=lines.append)
    p(1)
    p(2)
    assert lines == [lines[-1]] and lines[-1].startswith("progress: 3/3 phases (100.0%)")
    assert "unresolved" not in lines[-1]


def test_durations_and_interval(monkeypatch):
    assert [duration(s) for s in (5, 460, 7500)] == ["5s", "7m40s", "2h05m"]
    monkeypatch.setenv("SOFTIMPACT_PROGRESS_INTERVAL", "0.5")
    assert interval_s() == 0.5
    monkeypatch.setenv("SOFTIMPACT_PROGRESS_INTERVAL", "soon")
    assert interval_s() == 30.0


def test_close_returns_only_when_the_timer_thread_has_ended():
    # close() that only set the event left the thread alive for a moment: a CLI command
    # that had returned still had a timer running (it failed a CI run's thread check)
    for _ in range(20):
        p = ProgressLines(10, interval=60, write=lambda line: None)
        p.close()
        assert not p._thread.is_alive()
    finished = ProgressLines(2, interval=60, write=lambda line: None)
    finished(2)  # reaching the total closes it
    assert not finished._thread.is_alive()


def test_recurrent_trajectories_are_not_counted_unresolved():
    """The second stage's recurrent trajectories keep UNRESOLVED_LABEL in their chunk until
    the parent names them (chaotic A1...): the line counts them apart (issue 31, item 3)."""
    from softimpact_cli.sweep.second_stage import progress_codes

    result = {"label": np.array([0, UNRESOLVED_LABEL, UNRESOLVED_LABEL, UNRESOLVED_LABEL]),
              "section_flat": np.array([101, 103])}  # flat indices; the chunk starts at 100
    codes = progress_codes(result, 100)
    assert result["label"][1] == UNRESOLVED_LABEL  # the chunk's own codes untouched
    lines = []
    ProgressLines(4, interval=60, write=lines.append)(codes)
    assert "unresolved 1 (25.00%)" in lines[-1]
    assert "on a recurrent set 2 (50.00%, named at the end)" in lines[-1]
