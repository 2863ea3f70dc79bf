"""Workers end with their parent: PR_SET_PDEATHSIG on Linux, a thread polling the parent's
pid elsewhere (forced here by pretending to be another platform)."""

import subprocess
import sys
import textwrap
import time

import pytest

psutil = pytest.importorskip("psutil")

SCRIPT = textwrap.dedent("""
    import os, sys, time
    from softimpact_cli.sweep import executors
    executors.WATCH_PARENT_S = 0.05
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:
        sys.platform = {platform!r}
        executors.end_with_parent(parent)
        time.sleep(60)
        os._exit(0)
    print(pid, flush=True)
    time.sleep(0.3)
    os._exit(0)  # the parent dies without a word to its child
""")


@pytest.mark.parametrize("platform", ["linux", "darwin"])
def test_a_worker_ends_when_its_parent_dies(platform):
    if platform == "linux" and not sys.platform.startswith("linux"):
        pytest.skip("PR_SET_PDEATHSIG is Linux only")
    proc = subprocess.run([sys.executable, "-c", SCRIPT.format(platform=platform)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    child = psutil.Process(int(proc.stdout.split()[0])) if psutil.pid_exists(
        int(proc.stdout.split()[0])) else None
    deadline = time.time() + 5
    while child is not None and time.time() < deadline:
        try:
            if child.status() == psutil.STATUS_ZOMBIE:
                break
        except psutil.NoSuchProcess:
            break
        time.sleep(0.05)
    else:
        if child is not None:
            child.kill()
            pytest.fail("the worker outlived its parent")
