"""Chunk files carry their identity and a checksum: every kind of damage or foreign
part is named, deleted and never used (issue 20, item 9)."""

import shutil

import numpy as np
import pytest

from softimpact_cli.store.sweep_store import PART, DamagedPart, RunIdentity, SweepStore
from softimpact_cli.sweep.chunks import RESULT_FIELDS

ID = RunIdentity("a" * 64, chunk_size=5, n_total=12)  # chunks [0,5) [5,10) [10,12)


def chunk_result(start, stop, seed=0):
    rng = np.random.default_rng([start, seed])
    out = {k: rng.integers(0, 5, stop - start).astype(t) for k, t in RESULT_FIELDS.items()}
    out["orbits"] = {(0, 1): (start, rng.normal(size=(3, 4))),
                     (1, 2): (start + 1, rng.normal(size=(1, 4)))}
    return out


@pytest.fixture
def store(tmp_path):
    s = SweepStore(tmp_path / "r.h5")
    s.ensure_parts()
    for i in range(ID.n_chunks):
        s.write_chunk(i, chunk_result(*ID.chunk(i)), ID, session_started=100.0)
    return s


def test_round_trip_with_orbits_as_plain_arrays(store):
    arrays, meta = store.read_chunk(1, ID)
    expected = chunk_result(5, 10)
    for key in RESULT_FIELDS:
        assert np.array_equal(arrays[key], expected[key])
        assert arrays[key].dtype == expected[key].dtype
    assert arrays["orbits"].keys() == expected["orbits"].keys()
    for key, (flat, pts) in expected["orbits"].items():
        assert arrays["orbits"][key][0] == flat and np.array_equal(arrays["orbits"][key][1], pts)
    assert (meta["chunk"], meta["start"], meta["stop"]) == (1, 5, 10)
    assert meta["scene_sha256"] == ID.scene_sha256 and meta["session_started"] == 100.0
    # no pickle anywhere: numpy refuses object arrays with allow_pickle=False
    with np.load(store.parts / PART.format(1), allow_pickle=False) as data:
        assert all(data[k].dtype != object for k in data.files)


def _flip(path, at):
    raw = bytearray(path.read_bytes())
    raw[at] ^= 0x40
    path.write_bytes(bytes(raw))


def damage(store, kind, tmp_path):
    path = store.parts / PART.format(1)
    if kind == "truncated":
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    elif kind == "zero-length":
        path.write_bytes(b"")
    elif kind == "flipped data byte":
        # a byte inside the label array (stored uncompressed: find its bytes)
        raw = path.read_bytes()
        label = chunk_result(5, 10)["label"].tobytes()
        _flip(path, raw.index(label) + 2)
    elif kind == "flipped meta byte":
        raw = path.read_bytes()
        _flip(path, raw.index(b'"session_started"') + 20)
    elif kind == "array edited, zip rewritten":  # the zip's CRCs are fine: only ours catch it
        with np.load(path) as data:
            arrays = {k: data[k] for k in data.files}
        arrays["label"][0] += 1
        np.savez(path, **arrays)
    elif kind == "not a zip":
        path.write_bytes(b"\x00" * 500)
    elif kind == "another chunk's data":
        shutil.copy(store.parts / PART.format(0), path)
    elif kind == "another scene":
        other = SweepStore(tmp_path / "other.h5")
        other.ensure_parts()
        other_id = RunIdentity("b" * 64, ID.chunk_size, ID.n_total)
        other.write_chunk(1, chunk_result(5, 10, seed=1), other_id, 1.0)
        shutil.copy(other.parts / PART.format(1), path)
    elif kind == "another chunk size":
        other = SweepStore(tmp_path / "other.h5")
        other.ensure_parts()
        other_id = RunIdentity(ID.scene_sha256, 4, ID.n_total)
        other.write_chunk(1, chunk_result(4, 8), other_id, 1.0)
        shutil.copy(other.parts / PART.format(1), path)


REASONS = {
    "truncated": "unreadable",
    "zero-length": "empty file",
    "flipped data byte": "checksum",
    "flipped meta byte": "checksum",
    "not a zip": "unreadable",
    "array edited, zip rewritten": "checksum",
    "another chunk's data": "holds chunk 0's data",
    "another scene": "from another scene",
    "another chunk size": "another chunk size",
}


@pytest.mark.parametrize("kind", sorted(REASONS))
def test_every_damage_is_named_and_the_part_deleted(store, kind, tmp_path):
    damage(store, kind, tmp_path)
    with pytest.raises(DamagedPart, match=REASONS[kind]):
        store.read_chunk(1, ID)
    good, bad = store.verify(ID)
    assert set(good) == {0, 2} and list(bad) == [1] and REASONS[kind] in bad[1]
    assert store.done() == {0, 2}  # the bad one is gone, the good ones stay


def test_parts_beyond_the_plan_and_leftover_temporaries_are_removed(store):
    shutil.copy(store.parts / PART.format(2), store.parts / PART.format(9))
    (store.parts / (PART.format(0) + ".tmp")).write_bytes(b"half")
    good, bad = store.verify(ID)
    assert set(good) == {0, 1, 2} and "beyond" in bad[9]
    assert sorted(p.name for p in store.parts.iterdir()) == [PART.format(i) for i in range(3)]


def test_write_chunk_recreates_a_deleted_parts_folder(store):
    shutil.rmtree(store.parts)
    store.write_chunk(2, chunk_result(10, 12), ID, 5.0)
    assert store.done() == {2}
