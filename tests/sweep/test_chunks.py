"""Recurrence cells (on by default) must not make a result depend on how the run is cut:
tables start at every CELL_BLOCK flat indices and at every grid point, and chunk sizes are
rounded up to whole blocks, so one worker, two workers and any --chunk-size agree."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.chunks import CELL_BLOCK
from softimpact_cli.sweep.in_memory import sweep_in_memory
from softimpact_cli.sweep.plan import chunk_size_for, default_chunk_size

from .test_sweep import DATA_VARS

SCENE = """
[system]
model = "duffing"
[coupling]
d = 6.0
[analysis]
kind = "basins"
[grid]
phi = [0.0, "pi"]
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [25, 25]
[catalogue]
grid = 6
random = 30
seed = 2
"""


def test_cells_are_on_by_default_with_whole_block_chunks():
    scene = parse_scene(SCENE, "cells.toml")
    assert scene.integrator.cell_size == IntegratorSettings().cell_size > 0.0
    for given_size in (None, 1, 7, CELL_BLOCK, CELL_BLOCK + 1):
        for workers in (1, 2, 64):
            assert chunk_size_for(scene, given_size, workers) % CELL_BLOCK == 0


def test_labels_do_not_depend_on_workers_or_chunk_size():
    """625 trajectories per grid point: blocks cut inside a point and across points."""
    scene = parse_scene(SCENE, "cells.toml")
    one = sweep_in_memory(scene, workers=1)
    two = sweep_in_memory(scene, workers=2, chunk_size=600)  # rounded up to 3 blocks
    assert int(one.attrs["chunk_size"]) != int(two.attrs["chunk_size"])
    for v in DATA_VARS + ("captured",):
        assert np.array_equal(one[v].values, two[v].values), v
    assert (one["captured"].values == 2).any()  # cells did label some trajectories


@given(n_total=st.integers(1, 10**7), workers=st.integers(1, 512),
       block=st.sampled_from([1, 16, CELL_BLOCK]))
def test_default_chunk_size_is_whole_blocks(n_total, workers, block):
    size = default_chunk_size(n_total, workers, block)
    assert size % block == 0
    assert 16 <= size < 2000 + block


def test_resume_accepts_the_chunk_size_it_was_given(tmp_path, monkeypatch):
    """--chunk-size 5 with cells runs in chunks of 256; resuming with --chunk-size 5 again
    is the same size, not a refused change."""
    import pytest

    from softimpact_cli.store.sweep_store import SweepStore
    from softimpact_cli.sweep import run_sweep

    class Killed(Exception):
        pass

    def killed(self, result):
        raise Killed

    out = tmp_path / "r.h5"
    scene = parse_scene(SCENE.replace("[25, 25]", "[12, 12]"), "r.toml")
    with monkeypatch.context() as m:
        m.setattr(SweepStore, "finish", killed)
        with pytest.raises(Killed):
            run_sweep(scene, out, workers=1, chunk_size=5)
    again = run_sweep(scene, out, workers=1, chunk_size=5, resume=True)
    assert int(again.attrs["chunk_size"]) == CELL_BLOCK and int(again.attrs["resumed"]) == 1
