"""A reader that goes away (``softimpact sweep S -o R.h5 2>&1 | head -n 2``) costs the
output, never the result (issue 31, item 6): the sweep writes its whole result and exits
with its usual status."""

import os
import subprocess
import sys

import pytest
import xarray as xr

from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.report.streams import ReaderSafeStream
from softimpact_cli.sweep import run_sweep

from ..sweep.test_sweep import equal_results, scene_text


def test_a_closed_pipe_drops_the_writes_and_raises_nothing():
    read, write = os.pipe()
    stream = ReaderSafeStream(os.fdopen(write, "w"))
    stream.write("first line\n")
    stream.flush()
    assert os.read(read, 100) == b"first line\n"
    os.close(read)  # the reader goes away
    stream.write("progress: 1/2\n" * 10_000)  # more than a pipe buffers
    stream.flush()
    assert stream.gone
    assert stream.write("the last line\n") == len("the last line\n")
    stream.flush()
    with pytest.raises(TypeError):  # still a text stream (click probes it with bytes)
        stream.write(b"")
    stream.stream.close()  # the buffered bytes went to /dev/null: closing flushes nothing


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("reference") / "reference.h5"
    return run_sweep(parse_scene(scene_text(out, 6), "reference.toml"), out, workers=1,
                     chunk_size=8)


@pytest.mark.parametrize("streams", ["2>&1", "2>"], ids=["stdout-and-stderr", "stderr"])
def test_a_sweep_piped_into_head_writes_its_whole_result(tmp_path, reference, streams):
    out = tmp_path / "run.h5"
    scene = tmp_path / "run.toml"
    scene.write_text(scene_text(out, 6))
    # progress lines every 0.05 s: many are written after the pipe is closed, the last
    # one (72/72) from the sweep's own thread, between its last chunk and the result
    env = {**os.environ, "SOFTIMPACT_PROGRESS_INTERVAL": "0.05"}
    command = [sys.executable, "-m", "softimpact_cli", "sweep", str(scene), "--workers", "1",
               "--chunk-size", "8", "--no-verify"]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, env=env,
                            stderr=subprocess.STDOUT if streams == "2>&1" else subprocess.PIPE)
    pipe = proc.stdout if streams == "2>&1" else proc.stderr
    lines = [pipe.readline() for _ in range(2)]  # head -n 2
    pipe.close()
    if streams == "2>":
        stdout = proc.stdout.read()  # stdout stays open: its last line is printed
    status = proc.wait(timeout=600)
    assert all(lines), lines
    assert status == 0
    if streams == "2>":
        assert f"-> {out}" in stdout.decode()
    with xr.open_dataset(out) as back:
        assert back.attrs["complete"] == 1
        equal_results(reference, back.load())
    assert not (tmp_path / "run.h5.parts").exists()
