"""The interruption mechanism in-process: a signal raises Interrupted at a safe point,
never inside a frame whose caller would swallow it, and any exception that follows a
signal is recognised as the interruption."""

import os
import signal
import time

import pytest

from softimpact_cli.sweep import interrupt


def _busy(seconds: float) -> None:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        pass


def test_a_signal_raises_interrupted_with_the_shell_status():
    with pytest.raises(interrupt.Interrupted) as caught:
        with interrupt.raising_on_signals():
            os.kill(os.getpid(), signal.SIGTERM)
            _busy(5)
    assert caught.value.status == 143 and caught.value.signum == signal.SIGTERM
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL  # restored afterwards


def test_inside_an_unsafe_frame_the_interruption_waits_until_it_returns():
    # a function that counts as llvmlite code (a ctypes callback there swallows exceptions)
    code = ("def callback(busy):\n"
            "    import os, signal\n"
            "    os.kill(os.getpid(), signal.SIGINT)\n"
            "    busy(0.3)\n"
            "    return 'finished'\n")
    namespace = {"__name__": "llvmlite.binding.fake"}
    exec(code, namespace)
    results = []
    with pytest.raises(interrupt.Interrupted) as caught:
        with interrupt.raising_on_signals():
            results.append(namespace["callback"](_busy))
            _busy(5)
    assert results == ["finished"] and caught.value.status == 130


def test_errors_after_a_signal_are_the_interruption():
    with interrupt.raising_on_signals():
        try:
            try:
                os.kill(os.getpid(), signal.SIGINT)
                _busy(5)
            except interrupt.Interrupted:
                raise SystemError("returned a result with an exception set") from None
        except SystemError as exc:
            stop = interrupt.interruption(exc)
    assert stop is not None and stop.status == 130


def test_ordinary_errors_are_not_interruptions():
    with interrupt.raising_on_signals():
        assert interrupt.interruption(ValueError("x")) is None
        assert interrupt.interruption(SystemExit(2)) is None
        assert interrupt.interruption(KeyboardInterrupt()).status == 130
        wrapped = SystemError("numba")
        wrapped.__context__ = interrupt.Interrupted(signal.SIGTERM)
        assert interrupt.interruption(wrapped).status == 143


def test_a_sweep_interrupted_before_its_header_kept_nothing(tmp_path):
    out = tmp_path / "r.h5"
    assert interrupt.sweep_kept(out, "s.toml") == f"nothing written to {out}"


def test_within_deferred_the_interruption_waits_for_the_block_to_end():
    # a Dask cluster's start (sweep/executors.py): cut in half it would leave workers
    finished = []
    with pytest.raises(interrupt.Interrupted) as caught:
        with interrupt.raising_on_signals():
            with interrupt.deferred():
                os.kill(os.getpid(), signal.SIGINT)
                _busy(0.3)
                finished.append(True)
            _busy(5)
    assert finished == [True] and caught.value.status == 130
    assert interrupt.received() is None  # the next block starts uninterrupted
    with interrupt.deferred():  # outside a block: nothing to raise
        pass
