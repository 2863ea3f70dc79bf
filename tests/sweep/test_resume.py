"""--resume repairs what a kill, a disk or a user left behind (issue 20, items 9, 13, 17,
20): damaged or foreign chunk files, a missing parts folder (after a kill or during the
run), a damaged header, a stale parts folder next to a complete result, nothing at all.
Each case says what it does, ends in the uninterrupted result, and never in a traceback."""

import shutil

import numpy as np
import pytest

from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store import open_result
from softimpact_cli.store.sweep_store import PART, SweepStore
from softimpact_cli.sweep import run_sweep

from .test_sweep import equal_results, scene_text

CHUNK = 4  # 2 phi x 4 x 4 = 32 trajectories: 8 chunks


class Killed(Exception):
    """Stands in for a kill between the last chunk and the assembly."""


def scene_at(out, seed=2):
    return parse_scene(scene_text(out, res=4).replace("seed = 2", f"seed = {seed}"),
                       str(out) + ".toml")


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "ref.h5"
    return run_sweep(scene_at(out), out, workers=1, chunk_size=CHUNK)


def interrupted(out, monkeypatch, seed=2):
    """A run killed after writing every chunk and before assembling them."""
    def killed(self, result):
        raise Killed

    with monkeypatch.context() as m:
        m.setattr(SweepStore, "finish", killed)
        with pytest.raises(Killed):
            run_sweep(scene_at(out, seed), out, workers=1, chunk_size=CHUNK)
    return SweepStore(out)


def resume(out, chunk_size=None):
    said = []
    ds = run_sweep(scene_at(out), out, workers=1, resume=True, chunk_size=chunk_size,
                   echo=said.append)
    return ds, "\n".join(said)


def assert_resumed(reference, ds, said: str, done: int, out, store) -> None:
    """A resume that found ``done`` of the 8 chunks kept and finished the sweep: the
    dataset it returned and the file it wrote equal the reference, its chunks are gone."""
    assert f"resuming: {done} of 8 chunks already done" in said
    equal_results(reference, ds)
    equal_results(reference, open_result(out))
    assert not store.parts.exists()


def test_damaged_and_foreign_parts_are_named_and_redone(reference, tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    store = interrupted(out, monkeypatch)
    other = interrupted(tmp_path / "other.h5", monkeypatch, seed=3)  # another scene
    part = [store.parts / PART.format(i) for i in range(8)]
    part[1].write_bytes(part[1].read_bytes()[:300])                # truncated
    raw = bytearray(part[2].read_bytes())
    raw[len(raw) // 2] ^= 0xFF                                      # flipped byte
    part[2].write_bytes(bytes(raw))
    part[3].write_bytes(b"")                                       # zero-length
    shutil.copy(part[5], part[4])                                  # another chunk's data
    shutil.copy(other.parts / PART.format(6), part[6])             # another seed/scene
    ds, said = resume(out)
    assert ("resume: 5 chunk files were damaged or foreign (chunk 1: unreadable "
            "(truncated or damaged); chunk 2: checksum; chunk 3: empty file; chunk 4: "
            "holds chunk 5's data; chunk 6: from another scene); recomputing them") in said
    assert_resumed(reference, ds, said, done=3, out=out, store=store)


def test_nothing_to_resume_starts_a_new_run(reference, tmp_path):
    out = tmp_path / "new.h5"
    ds, said = resume(out)
    assert f"nothing to resume at {out}; starting a new run" in said
    equal_results(reference, ds)
    assert ds.attrs["resumed"] == 0


def test_parts_folder_deleted_after_a_kill(reference, tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    store = interrupted(out, monkeypatch)
    shutil.rmtree(store.parts)
    ds, said = resume(out)
    assert "was missing; recomputing every chunk" in said
    equal_results(reference, ds)


def test_parts_folder_deleted_during_the_run(reference, tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    write = SweepStore.write_chunk
    calls = []

    def write_then_delete(self, index, *args):
        write(self, index, *args)
        calls.append(index)
        if len(calls) == 3:  # a user (or a cleaner) removes the folder mid-run
            shutil.rmtree(self.parts)

    monkeypatch.setattr(SweepStore, "write_chunk", write_then_delete)
    said = []
    ds = run_sweep(scene_at(out), out, workers=1, chunk_size=CHUNK, echo=said.append)
    said = "\n".join(said)
    assert "vanished during the run; recreated it" in said
    assert "3 chunk files went missing or broke during the run; recomputing them" in said
    equal_results(reference, ds)


@pytest.mark.parametrize("how", ["truncated", "garbage", "deleted"])
def test_damaged_or_missing_header(reference, tmp_path, monkeypatch, how):
    out = tmp_path / "r.h5"
    interrupted(out, monkeypatch)
    if how == "truncated":
        out.write_bytes(out.read_bytes()[:1000])
    elif how == "garbage":
        out.write_bytes(b"not hdf5 at all" * 100)
    else:
        out.unlink()
    ds, said = resume(out)
    assert f"resume: the result header {out} is " in said
    assert "rewriting it and keeping the chunk files that verify" in said
    assert "resuming: 8 of 8 chunks already done" in said
    equal_results(reference, ds)


def test_stale_parts_next_to_a_complete_result_are_cleaned(reference, tmp_path):
    out = tmp_path / "r.h5"
    run_sweep(scene_at(out), out, workers=1, chunk_size=CHUNK)
    parts = SweepStore(out).parts
    parts.mkdir()
    (parts / PART.format(0)).write_bytes(b"left by a kill during the clean-up")
    ds, said = resume(out)
    assert "is complete; removed the chunk folder" in said and not parts.exists()
    equal_results(reference, ds)
    with pytest.raises(ConfigError, match="complete already"):
        resume(out)


def test_wall_time_start_and_history_cover_every_session(reference, tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    store = interrupted(out, monkeypatch)
    header = store.header()
    first_parts = [store.read_chunk(i, _identity(header))[1] for i in range(8)]
    first_span = max(m["written"] for m in first_parts) - first_parts[0]["session_started"]
    for i in range(4, 8):  # the second session redoes half
        (store.parts / PART.format(i)).unlink()
    ds, _ = resume(out)
    assert ds.attrs["started"] == header.attrs["started"]
    assert ds.attrs["sessions"] == 2
    assert ds.attrs["wall_s"] > first_span > 0
    lines = ds.attrs["history"].splitlines()
    programs = ("softimpact", "pytest", "python")  # python -c: a pytest-xdist worker
    assert len(lines) == 2 and all(any(p in line for p in programs) for line in lines)


def _identity(header):
    from softimpact_cli.store.sweep_store import RunIdentity

    return RunIdentity(header.attrs["scene_sha256"], int(header.attrs["chunk_size"]),
                       int(header.attrs["n"]))


def test_another_chunk_size_on_resume_is_refused(tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    interrupted(out, monkeypatch)
    with pytest.raises(ConfigError, match=r"--chunk-size 5 differs from the interrupted "
                                          r"run's 4; resume without --chunk-size"):
        resume(out, chunk_size=5)
    ds, _ = resume(out, chunk_size=CHUNK)  # the same size is fine
    assert ds.attrs["complete"] == 1 and np.all(ds["status"].values == 0)


def _says_complete(out, **attrs):
    """The header of an interrupted run rewritten to say complete = 1 (issue 31, item 7):
    its chunk files are all that holds the result."""
    from softimpact_cli.store import write_result

    header = SweepStore(out).header()
    header.attrs.update({"complete": 1, **attrs})
    write_result(header, out)


@pytest.mark.parametrize("verify_status", [None, "pending"])
def test_a_header_that_says_complete_resumes_from_its_chunks(reference, tmp_path, monkeypatch,
                                                             verify_status):
    from softimpact_cli.sweep.verification import PENDING, sweep_verified

    out = tmp_path / "r.h5"
    store = interrupted(out, monkeypatch)
    _says_complete(out, **({"verify_status": PENDING} if verify_status else {}))
    said = []
    if verify_status:  # as `softimpact sweep --resume` runs it: the verification after
        ds = sweep_verified(scene_at(out), out, resume=True, echo=said.append, workers=1,
                            sample=4)
    else:
        ds = run_sweep(scene_at(out), out, workers=1, resume=True, echo=said.append)
    said = "\n".join(said)
    assert (f"resume: the result header {out} says it is complete but holds no 'label' "
            "variable; rewriting it and keeping the chunk files that verify") in said
    assert_resumed(reference, ds, said, done=8, out=out, store=store)


def test_a_header_that_says_complete_without_chunks_is_refused(tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    store = interrupted(out, monkeypatch)
    _says_complete(out)
    shutil.rmtree(store.parts)
    before = out.read_bytes()
    with pytest.raises(ConfigError, match=r"r\.h5: says it is complete but holds no 'label' "
                                          r"variable, and no chunk files are kept; pass "
                                          r"--overwrite to compute it again"):
        resume(out)
    assert out.read_bytes() == before
