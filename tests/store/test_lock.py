"""One writer per output (issue 20, item 10): a second run is refused naming the holder's
pid; the lock goes with its process, so a killed run's lock file never blocks."""

import os
import signal
import subprocess
import sys

import pytest

from softimpact_cli.config import ConfigError
from softimpact_cli.store.lock import acquire, held, lock_path, output_lock, release

HOLD = """
import sys, time
from softimpact_cli.store.lock import acquire
acquire(sys.argv[1], "softimpact sweep holder.toml")
print("locked", flush=True)
time.sleep(120)
"""


@pytest.fixture
def holder(tmp_path):
    """Another process holding the lock on tmp_path/r.h5."""
    out = tmp_path / "r.h5"
    proc = subprocess.Popen([sys.executable, "-c", HOLD, str(out)], stdout=subprocess.PIPE,
                            text=True, env={**os.environ, "PYTHONPATH": os.getcwd()})
    assert proc.stdout.readline().strip() == "locked"
    yield out, proc
    proc.kill()
    proc.wait()


def test_second_writer_is_refused_naming_the_pid(holder):
    out, proc = holder
    with pytest.raises(ConfigError) as exc:
        acquire(out, "softimpact sweep second.toml --overwrite")
    message = str(exc.value)
    assert f"in use by process {proc.pid} (softimpact sweep holder.toml)" in message
    assert "\n" not in message and not held(out)


def test_lock_of_a_killed_run_does_not_block(holder):
    out, proc = holder
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert lock_path(out).exists()  # the stale file stays, with the dead pid in it
    with output_lock(out, "softimpact sweep again.toml"):
        assert held(out)
        assert lock_path(out).read_text().startswith(f"{os.getpid()} softimpact sweep again")
    assert not held(out) and not lock_path(out).exists()


def test_lock_is_released_when_the_block_raises(tmp_path):
    out = tmp_path / "r.h5"
    with pytest.raises(RuntimeError), output_lock(out, "x"):
        with output_lock(out, "nested: the same process may re-enter"):
            pass
        assert held(out)
        raise RuntimeError
    assert not held(out)
    acquire(out, "y")  # free again
    release(out)


@pytest.mark.slow
def test_second_sweep_on_the_same_output_is_refused_by_the_cli(holder, tmp_path):
    out, proc = holder
    scene = tmp_path / "s.toml"
    scene.write_text(f"[system]\nmodel='duffing'\n[analysis]\nkind='basins'\n"
                     f"[initial_conditions]\nkind='plane'\naxes=['x1','x2']\n"
                     f"ranges=[[-1,1],[-1,1]]\nresolution=[2,2]\n[output]\npath='{out}'\n")
    for flags in ([], ["--overwrite"], ["--resume"]):
        res = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene),
                              "-q", *flags], capture_output=True, text=True)
        assert res.returncode == 2, res.stderr
        assert res.stderr.strip().splitlines() == [
            f"softimpact: error: {out}: in use by process {proc.pid} (softimpact sweep "
            "holder.toml); wait for it to end (or stop it) and run again"]
    assert not out.exists()


def test_lock_in_a_folder_that_does_not_exist_yet(tmp_path):
    out = tmp_path / "new" / "deeper" / "r.h5"
    with output_lock(out, "x"):
        assert held(out)
    assert out.parent.is_dir() and not lock_path(out).exists()


def test_lock_where_nothing_can_be_created_is_one_clean_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(ConfigError, match="cannot create the lock file"):
        acquire(blocker / "r.h5", "x")
