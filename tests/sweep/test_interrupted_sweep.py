"""Ctrl-C and SIGTERM during a sweep: one line saying what was kept, exit 130 / 143, no
worker process left behind, and a resume that ends with the uninterrupted result; a
killed parent takes its workers along."""

import os
import shlex
import signal
import subprocess
import sys
import time

import pytest
import xarray as xr

from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep import run_sweep

from .test_sweep import equal_results, scene_text

psutil = pytest.importorskip("psutil")

RES = 16  # 2 x 256 trajectories: a few seconds of chunks on two workers
CHUNK = 8


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("reference") / "reference.h5"
    ds = run_sweep(parse_scene(scene_text(out, RES), "reference.toml"), out, workers=1,
                   chunk_size=CHUNK)
    return ds


class Sweep:
    """A ``softimpact sweep`` in its own session (as a shell job), stderr in a file."""

    def __init__(self, tmp_path, *options, env=None, res=RES):
        self.out = tmp_path / "run.h5"
        self.scene = tmp_path / "run.toml"
        self.scene.write_text(scene_text(self.out, res))
        self.err = tmp_path / "stderr.txt"
        self.parts = tmp_path / "run.h5.parts"
        with open(self.err, "w") as err:
            self.proc = subprocess.Popen(
                [sys.executable, "-m", "softimpact_cli", "sweep", str(self.scene),
                 "--chunk-size", str(CHUNK), *options], stdout=subprocess.DEVNULL,
                stderr=err, start_new_session=True, env={**os.environ, **(env or {})})

    def stderr(self) -> str:
        return self.err.read_text()

    def wait_for(self, ready, what: str, timeout: float = 240) -> list:
        """Wait until ``ready()``; return the run's descendant processes then."""
        deadline = time.time() + timeout
        while time.time() < deadline:
            if ready():
                return psutil.Process(self.proc.pid).children(recursive=True)
            if self.proc.poll() is not None:
                pytest.fail(f"the sweep ended before {what}: {self.stderr()}")
            time.sleep(0.02)
        self.proc.kill()
        pytest.fail(f"no {what} within {timeout} s")

    def chunks_written(self, n: int):
        return lambda: self.parts.is_dir() and len(list(self.parts.glob("chunk-*.npz"))) >= n

    def in_catalogue(self):
        return lambda: "executor:" in self.stderr()

    def send(self, signum: int, group: bool = False) -> int:
        os.killpg(self.proc.pid, signum) if group else os.kill(self.proc.pid, signum)
        return self.proc.wait(timeout=120)


def survivors(processes: list, timeout: float = 10.0) -> list:
    """The processes still alive (zombies count as ended) after up to ``timeout`` s;
    these are then killed."""
    deadline = time.time() + timeout
    while True:
        alive = []
        for p in processes:
            try:
                if p.is_running() and p.status() != psutil.STATUS_ZOMBIE:
                    alive.append(p)
            except psutil.NoSuchProcess:
                pass
        if not alive or time.time() > deadline:
            break
        time.sleep(0.1)
    for p in alive:  # leave nothing behind when the test fails
        p.kill()
    return alive


def resume_as_printed(stderr: str) -> subprocess.CompletedProcess:
    """Run the resume command the interruption line gives."""
    line = stderr.strip().splitlines()[-1]
    command = shlex.split(line.split("resume with: ", 1)[1])
    assert command[:2] == ["softimpact", "sweep"] and command[-1] == "--resume"
    return subprocess.run([sys.executable, "-m", "softimpact_cli", *command[1:], "-q"],
                          capture_output=True, text=True)


def check_one_line(stderr: str, name: str) -> str:
    assert "Traceback" not in stderr and "Aborted" not in stderr, stderr
    lines = [s for s in stderr.splitlines() if s.startswith("softimpact: interrupted")]
    assert len(lines) == 1 and stderr.strip().endswith(lines[0]), stderr
    assert lines[0].startswith(f"softimpact: interrupted ({name}): "), lines[0]
    return lines[0]


def test_sigint_during_the_catalogue_keeps_nothing(tmp_path):
    # --no-cache: an earlier test's catalogue of this scene would end the search at once
    run = Sweep(tmp_path, "--workers", "2", "--no-cache")
    run.wait_for(run.in_catalogue(), "the catalogue")
    time.sleep(0.5)  # inside the catalogue search (numba compiling or running)
    assert run.send(signal.SIGINT) == 130
    line = check_one_line(run.stderr(), "SIGINT")
    assert line.endswith(f"nothing written to {run.out}")
    assert not run.out.exists() and not run.parts.exists()


@pytest.mark.slow
@pytest.mark.parametrize("signum, status, group", [(signal.SIGTERM, 143, False),
                                                    (signal.SIGINT, 130, True)],
                         ids=["sigterm-to-parent", "ctrl-c-to-group"])
def test_interrupted_pool_ends_its_workers_and_resumes(tmp_path, reference, signum, status,
                                                       group):
    run = Sweep(tmp_path, "--workers", "2")
    workers = run.wait_for(run.chunks_written(3), "three chunks")
    assert len(workers) >= 2
    assert run.send(signum, group) == status
    line = check_one_line(run.stderr(), signal.Signals(signum).name)
    assert f"of 64 chunks kept in {run.parts}; resume with: " in line
    assert survivors(workers) == []
    resumed = resume_as_printed(run.stderr())
    assert resumed.returncode == 0, resumed.stderr
    with xr.open_dataset(run.out) as back:
        assert back.attrs["complete"] == 1 and back.attrs["resumed"] == 1
        equal_results(reference, back.load())


@pytest.mark.slow
def test_ctrl_c_on_a_dask_local_cluster(tmp_path, reference):
    pytest.importorskip("dask.distributed")
    run = Sweep(tmp_path, "--scheduler", "local:2")
    workers = run.wait_for(run.chunks_written(2), "two chunks")
    assert run.send(signal.SIGINT, group=True) == 130
    line = check_one_line(run.stderr(), "SIGINT")
    assert "chunks kept in" in line
    assert survivors(workers, timeout=20) == []
    resumed = resume_as_printed(run.stderr())
    assert resumed.returncode == 0, resumed.stderr
    with xr.open_dataset(run.out) as back:
        equal_results(reference, back.load())


def test_workers_end_when_the_parent_is_killed(tmp_path):
    run = Sweep(tmp_path, "--workers", "2")
    workers = run.wait_for(run.chunks_written(1), "a chunk")
    assert len(workers) >= 2
    os.kill(run.proc.pid, signal.SIGKILL)
    run.proc.wait()
    assert survivors(workers, timeout=5) == []


def test_progress_lines_when_stderr_is_not_a_terminal(tmp_path):
    run = Sweep(tmp_path, "--workers", "1", env={"SOFTIMPACT_PROGRESS_INTERVAL": "0.05"},
                res=6)
    assert run.proc.wait(timeout=240) == 0, run.stderr()
    lines = [s for s in run.stderr().splitlines() if s.startswith("progress: ")]
    assert len(lines) >= 2, run.stderr()  # at least one on the interval, and the last
    assert lines[-1].startswith("progress: 72/72 trajectories (100.0%), ")
    assert "unresolved 0 (0.00%)" in lines[-1]


# ---------------------------------------------------------------- Dask (issue 31, item 8)
SMALL = 6  # 2 x 36 trajectories: 9 chunks of 8


@pytest.fixture(scope="module")
def small_reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("small") / "reference.h5"
    return run_sweep(parse_scene(scene_text(out, SMALL), "reference.toml"), out, workers=1,
                     chunk_size=CHUNK)


def spawned_workers(run: Sweep, before: set[int] = frozenset()):
    """Whether a Dask worker process (multiprocessing's spawn) other than ``before`` has
    started: it is then importing, where a Ctrl-C printed a KeyboardInterrupt traceback."""
    def ready():
        try:
            children = psutil.Process(run.proc.pid).children(recursive=True)
            return any(p.pid not in before and "spawn_main" in " ".join(p.cmdline())
                       for p in children)
        except psutil.NoSuchProcess:
            return False
    return ready


@pytest.mark.slow
@pytest.mark.parametrize("phase", ["sweep", "verification"])
def test_ctrl_c_while_a_dask_local_cluster_starts(tmp_path, small_reference, phase):
    pytest.importorskip("dask.distributed")
    # the verification of a sweep starts a cluster of its own (after the sweep's closed)
    run = Sweep(tmp_path, "--scheduler", "local:1", *(("--check", "8") * (phase ==
                                                                        "verification")),
                *(("--no-verify",) * (phase == "sweep")), res=SMALL)
    if phase == "verification":
        # any worker alive once the line is out is the verification's: its cluster starts
        # after the line (the sweep's is closed before it); leaving out the processes alive
        # at the line, as this test did, left out that worker when it spawned first, and
        # the run ended before another (a CI run failed so, and 1 in 3 runs here)
        run.wait_for(lambda: "verification: rerunning" in run.stderr(), "the verification")
    workers = run.wait_for(spawned_workers(run), "a worker process starting")
    assert run.send(signal.SIGINT, group=True) == 130
    line = check_one_line(run.stderr(), "SIGINT")  # on eab4deb: a traceback per worker
    assert survivors(workers, timeout=20) == []
    if phase == "sweep":
        assert "chunks kept in" in line or line.endswith(f"nothing written to {run.out}")
        if "resume with: " not in line:
            return
    else:
        assert line.endswith("is complete but not verified; verify with: softimpact sweep "
                             f"{run.scene} -o {run.out} --resume"), line
    resumed = resume_as_printed(run.stderr().replace("verify with: ", "resume with: "))
    assert resumed.returncode == 0, resumed.stderr
    with xr.open_dataset(run.out) as back:
        equal_results(small_reference, back.load())


def test_a_dask_cluster_closed_mid_run(tmp_path, small_reference):
    """A cluster closed (or left without workers) while the sweep runs: one line with the
    resume command, exit 2, the chunks written kept; the resume ends in the same result
    (on eab4deb: AttributeError: 'FutureCancelledError' object has no attribute 'items')."""
    distributed = pytest.importorskip("dask.distributed")
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                       protocol="tcp", dashboard_address=None)
    try:
        run = Sweep(tmp_path, "--scheduler", cluster.scheduler_address, "--no-verify",
                    res=SMALL)
        run.wait_for(run.chunks_written(2), "two chunks")
    finally:
        cluster.close()
    assert run.proc.wait(timeout=120) == 2
    stderr = run.stderr()
    assert "Traceback" not in stderr and "AttributeError" not in stderr, stderr
    last = stderr.strip().splitlines()[-1]
    assert last.startswith(f"softimpact: error: the Dask cluster {cluster.scheduler_address} "
                           "stopped running chunk "), stderr
    assert f"of 9 chunks kept in {run.parts}; resume with: " in last, last
    resumed = resume_as_printed(stderr)
    assert resumed.returncode == 0, resumed.stderr
    with xr.open_dataset(run.out) as back:
        assert back.attrs["resumed"] == 1
        equal_results(small_reference, back.load())
