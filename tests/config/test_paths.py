"""Output paths and path arguments (issue 20, items 2 and 20): every bad path is found
before any computation and reported in one line, exit status 2, nothing written."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from softimpact_cli.config import ConfigError, check_writable

ROOT = Path(__file__).parents[2]
TRAJECTORY = ROOT / "configs" / "trajectory_duffing.toml"
SCENE = """
[system]
model = "duffing"
[analysis]
kind = "trajectory"
state = [3.0, 0.0, -3.0, 0.0]
periods = 2
samples_per_period = 8
[output]
path = {path}
"""


def run_cli(*args, cwd=None):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "softimpact_cli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, env=env)


def assert_one_line_error(proc, *words):
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("softimpact: error: "), proc.stderr
    for word in words:
        assert word in lines[0], lines[0]
    assert proc.stdout == ""  # nothing computed, nothing reported as written


# ---------------------------------------------------------------- the probe itself


def test_probe_reports_the_true_reason_and_leaves_nothing(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ConfigError, match=f"cannot write {blocker}/sub/x.h5: {blocker} is "
                                          "not a directory"):
        check_writable(blocker / "sub" / "x.h5", "s.toml")
    check_writable(tmp_path / "a" / "b" / "x.h5", "s.toml")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]  # probe removed a/b


def test_probe_keeps_an_existing_file(tmp_path):
    existing = tmp_path / "r.h5"
    existing.write_bytes(b"data")
    check_writable(existing, "s.toml")
    assert existing.read_bytes() == b"data"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.h5"]


@pytest.mark.parametrize("name, reason", [
    ("a\0b.h5", "NUL character"), ("x" * 300 + ".h5", "303 bytes; at most 224"),
    ("newdir/", "ends with '/'"), ("", "is empty"), (".", "is a directory")])
def test_bad_names(tmp_path, name, reason):
    with pytest.raises(ConfigError, match="s.toml: key: .*" + reason):
        check_writable(os.path.join(tmp_path, name) if name else name, "s.toml", "key")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not Path("/proc/self").exists(), reason="needs Linux /proc")
def test_proc_is_refused_with_the_real_reason():
    # as root os.access says /proc is writable; the probe finds out it is not
    with pytest.raises(ConfigError, match="cannot create directory /proc/forbidden: No such "
                                          "file or directory"):
        check_writable("/proc/forbidden/x.h5", "command line", "-o/--output")


# ---------------------------------------------------------------- the command line


@pytest.mark.skipif(not Path("/proc/self").exists(), reason="needs Linux /proc")
def test_bad_output_found_before_computing():
    proc = run_cli("sweep", TRAJECTORY, "-o", "/proc/forbidden/x.h5")
    assert_one_line_error(proc, "-o/--output", "cannot create directory /proc/forbidden: No "
                                               "such file or directory")


def test_directories_as_paths(tmp_path):
    folder = tmp_path / "folder"
    folder.mkdir()
    assert_one_line_error(run_cli("sweep", folder), "is a directory")
    assert_one_line_error(run_cli("sweep", TRAJECTORY, "-o", folder), "is a directory")
    assert_one_line_error(run_cli("info", folder), "is a directory")
    assert_one_line_error(run_cli("plot", "trajectory", folder, "-o", tmp_path / "f.png"),
                          "is a directory")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folder"]


def test_info_refuses_other_hdf5_files(tmp_path):
    h5py = pytest.importorskip("h5py")
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["x"] = [1.0, 2.0]
    assert_one_line_error(run_cli("info", other), "not a softimpact result")


@pytest.mark.parametrize("path, words", [
    ('"a\\u0000b.h5"', ("[output] path", "NUL")),
    ('"' + "y" * 260 + '.h5"', ("[output] path", "at most 224"))])
def test_bad_output_names_write_nothing(tmp_path, path, words):
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.format(path=path))
    assert_one_line_error(run_cli("sweep", scene, cwd=tmp_path), *words)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_trailing_slash_writes_into_the_directory_and_plot_checks_first(tmp_path):
    scene = tmp_path / "run.toml"
    scene.write_text(SCENE.format(path='"out/"'))
    proc = run_cli("sweep", scene, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    result = tmp_path / "out" / "run.h5"
    assert result.is_file()
    proc = run_cli("sweep", scene, "-o", "other/", cwd=tmp_path)
    assert proc.returncode == 0 and (tmp_path / "other" / "run.h5").is_file(), proc.stderr
    # plot: a bad figure path is refused before drawing, in one line
    assert_one_line_error(run_cli("plot", "trajectory", result, "-o", "figs/"), "ends with")
    blocker = tmp_path / "blocker"
    blocker.write_text("")
    assert_one_line_error(run_cli("plot", "trajectory", result, "-o", blocker / "f.png"),
                          f"cannot write {blocker / 'f.png'}: {blocker} is not a directory")
