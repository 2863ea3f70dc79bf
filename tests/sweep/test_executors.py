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


def test_a_cluster_that_loses_all_its_workers_keeps_the_chunks(tmp_path, monkeypatch):
    """Every worker gone mid-run (and the scattered context with them): ClusterLost, one
    line naming the cluster, the chunks written kept, and a resume ends in the result of
    an uninterrupted run (issue 31, item 8; on eab4deb: AttributeError on the cancelled
    future's exception)."""
    distributed = pytest.importorskip("dask.distributed")
    from softimpact_cli.kinds.scene import parse_scene
    from softimpact_cli.store.sweep_store import SweepStore
    from softimpact_cli.sweep import run_sweep
    from softimpact_cli.sweep.executors import ClusterLost

    from .test_sweep import equal_results, scene_text

    def scene(out):
        return parse_scene(scene_text(out, 8), "s.toml")  # 16 chunks: many left when it scales to 0

    reference = run_sweep(scene(tmp_path / "ref.h5"), tmp_path / "ref.h5", workers=1,
                          chunk_size=4)
    out = tmp_path / "r.h5"
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                       dashboard_address=None)
    write = SweepStore.write_chunk

    def write_then_lose_the_workers(self, index, *args):
        write(self, index, *args)
        if len(self.done()) == 2:
            cluster.scale(0)

    monkeypatch.setattr(SweepStore, "write_chunk", write_then_lose_the_workers)
    try:
        with pytest.raises(ClusterLost, match=rf"^the Dask cluster {cluster.scheduler_address} "
                                              r"stopped running chunk \d+ \(.*\): it was "
                                              r"closed, or lost its workers or scheduler$"):
            run_sweep(scene(out), out, scheduler=cluster.scheduler_address, chunk_size=4)
    finally:
        cluster.close()
    assert len(SweepStore(out).done()) >= 2
    monkeypatch.undo()
    resumed = run_sweep(scene(out), out, workers=1, resume=True)
    assert resumed.attrs["resumed"] == 1
    equal_results(reference, resumed)
