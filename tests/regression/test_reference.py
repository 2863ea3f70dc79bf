"""Every example scene reproduces the results stored from main before the architecture
change (``tests/data/reference``, written by ``python -m tests.regression.reference write``
at commit b0c8a8d): labels, statuses, periods and counters identical, floats to 1e-9."""

import numpy as np
import pytest

from tests.regression.reference import (
    SCENES,
    STORE,
    arrays_of,
    differences,
    load_stored,
    run_scene,
)


@pytest.mark.slow
@pytest.mark.parametrize("name,scene,options", SCENES, ids=[s[0] for s in SCENES])
def test_scene_reproduces_stored_result(name, scene, options, tmp_path):
    stored = load_stored(name)
    now = arrays_of(run_scene(scene, options, tmp_path / f"{name}.h5"))
    assert differences(stored, now) == []


def test_differences_catches_a_changed_label_and_a_moved_float():
    stored = {"label": np.array([0, 1, 2]), "x": np.array([1.0, 2.0])}
    assert differences(stored, {k: v.copy() for k, v in stored.items()}) == []
    assert differences(stored, {"label": np.array([0, 2, 2]), "x": stored["x"]}) == [
        "label: 1 of 3 values differ"]
    assert differences(stored, {"label": stored["label"], "x": np.array([1.0, 2.0 + 1e-6])}) \
        == ["x: 1 of 2 values differ beyond 1e-09"]
    assert differences(stored, {"label": stored["label"]}) == ["x: only in stored result"]


def test_every_figure_scene_and_the_60_by_60_plane_have_a_reference():
    names = {s[0] for s in SCENES}
    assert "fig06d_plane_60" in names and len(names) >= 24
    assert all((STORE / f"{n}.npz").exists() for n in names)
