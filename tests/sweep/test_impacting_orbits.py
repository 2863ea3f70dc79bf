"""Two coexisting impacting period-1 orbits are two labels (issue 32 item 4).

The Duffing pair at phi = pi (bodies forced in antiphase), d = 6, w = 1.08: between the
two symmetry-breaking pitchforks of configs/continuation/pitchfork_w.toml the two
asymmetric impacting P1 orbits, mirror images under S(x1, v1, x2, v2) = (-x2, -v2, -x1,
-v1), are both stable, and random starts reach both (tests/analysis/test_branch_point.py
traces them). Before, both were "impacting P1" and their basins merged."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from softimpact_cli.analysis.engine import Problem
from softimpact_cli.analysis.impacting import (
    ImpactingOrbits,
    cycle_distance,
    impacting_number,
    refine,
)
from softimpact_cli.analysis.labels import impacting_code
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.sweep.in_memory import sweep_in_memory
from softimpact_cli.systems import get_system

PAIR = get_system("duffing", 2)
VALUES = {**PAIR.defaults(), "phi": np.pi, "d": 6.0, "w": 1.08}
# the two orbits at t = 0, as a sweep meets them (4 decimals)
ORBIT_A = np.array([[-3.3681, -2.688, 4.5814, -2.1518]])
ORBIT_B = np.array([[-4.5814, 2.1518, 3.3681, 2.688]])

SCENE = """
[system]
model = "duffing"
w = 1.08
[coupling]
phi = "pi"
d = 6.0
[integrator]
cell_size = {cells}
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-10.0, 10.0], [-10.0, 10.0]]
resolution = [{res}, {res}]
[catalogue]
grid = 4
random = 20
[output]
path = "unused.h5"
"""


def mirror(y: np.ndarray) -> np.ndarray:
    return -np.asarray(y)[..., [2, 3, 0, 1]]


def problem_at(point: int) -> Problem:
    return Problem(PAIR, VALUES)


def test_newton_with_saltation_refines_both_orbits_apart():
    a, b = refine(problem_at(0), ORBIT_A), refine(problem_at(0), ORBIT_B)
    assert a is not None and b is not None
    assert np.max(np.abs(a - ORBIT_A)) < 1e-3 and np.max(np.abs(b - ORBIT_B)) < 1e-3
    assert np.max(np.abs(mirror(a) - b)) < 1e-8  # mirror images, to Newton's tolerance
    assert cycle_distance(a, b) > 1.0


def test_orbits_are_numbered_by_orbit_not_by_period():
    numbering = ImpactingOrbits(problem_at, 1e-3)
    assert numbering.number(0, ORBIT_A) == 1
    assert numbering.number(0, ORBIT_B) == 2  # another orbit of period 1: confirmed apart
    assert numbering.number(0, ORBIT_A + 1e-4) == 1  # as met again
    off = ORBIT_B + np.array([[0.05, -0.05, 0.05, 0.0]])  # beyond the matching tolerance,
    assert numbering.number(0, off) == 2  # but Newton lands on orbit B: not a third orbit
    assert len(numbering.orbits[(0, 1)]) == 2
    assert numbering.number(1, ORBIT_B) == 1  # numbers count per grid point
    assert numbering.label(0, ORBIT_B).name == "impacting P1^2"
    assert numbering.label(0, ORBIT_A).name == "impacting P1"


def test_chunks_are_renumbered_over_the_result_in_flat_order():
    """Chunk 1 met only B (its first orbit, code 1001); chunk 2 met A first, then B: in the
    result B (met first, flat 3) is number 1, A number 2, in chunk 2 too."""
    numbering = ImpactingOrbits(problem_at, 1e-3)
    first = np.array([2001, 1001, 1001, 1001])
    out1 = numbering.merge_chunk(first, 0, 100, {(0, 1001): (1, ORBIT_B)})
    assert first.tolist() == [2001, 1001, 1001, 1001] and set(out1) == {(0, 1001)}
    second = np.array([1001, impacting_code(1, 2), 1001, -2])
    out2 = numbering.merge_chunk(second, 4, 100, {(0, 1001): (4, ORBIT_A),
                                                 (0, impacting_code(1, 2)): (5, ORBIT_B)})
    two = impacting_code(1, 2)
    assert second.tolist() == [two, 1001, two, -2]
    assert set(out2) == {(0, two), (0, 1001)} and out2[(0, 1001)][0] == 5
    assert impacting_number(two) == (1, 2) and impacting_number(1001) == (1, 1)
    assert impacting_number(2001) is None


@pytest.fixture(scope="module")
def swept():
    scene = parse_scene(SCENE.format(cells=0.0, res=16), "impacting_pair.toml")
    return scene, sweep_in_memory(scene, workers=1)


def test_the_two_orbits_have_two_labels_and_two_basins(swept):
    scene, ds = swept
    names = dict(zip(ds["label_code"].values.tolist(), ds["label_name"].values.tolist(),
                     strict=True))
    codes, counts = np.unique(ds["label"].values, return_counts=True)
    found = {names[c]: int(n) for c, n in zip(codes.tolist(), counts.tolist(), strict=True)}
    assert found.get("impacting P1", 0) > 10 and found.get("impacting P1^2", 0) > 10, found
    position = {n: i for i, n in enumerate(ds["label_name"].values.tolist())}
    pts = ds["attractor_points"].values.reshape(len(position), -1, 4)
    one = pts[position["impacting P1"], 0]
    two = pts[position["impacting P1^2"], 0]
    assert np.max(np.abs(mirror(one) - two)) < 1e-3  # the mirror images, one each
    # the plane is symmetric under S too: (x1, x2) -> (-x2, -x1) swaps the two basins
    label = ds["label"].values.reshape(16, 16)
    a, b = 1001, impacting_code(1, 2)
    swapped = np.where(label == a, b, np.where(label == b, a, label))
    agree = (swapped[::-1, ::-1].T == label).mean()
    assert agree > 0.9


def test_numbers_do_not_depend_on_chunks_or_cells(swept):
    scene, ds = swept
    chunked = sweep_in_memory(scene, workers=1, chunk_size=7)
    assert np.array_equal(chunked["label"].values, ds["label"].values)
    cells = replace(scene, integrator=replace(scene.integrator, cell_size=0.05, cell_hits=5))
    with_cells = sweep_in_memory(cells, workers=1)
    assert np.array_equal(with_cells["label"].values, ds["label"].values)


def test_basins_drawn_apart(swept):
    from softimpact_cli.plot.basins_figure import draw_basins
    from softimpact_cli.plot.palette import IMPACTING, colour_of

    fig = draw_basins(swept[1])
    texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert any(t.startswith("impacting $P_{1}$") for t in texts)
    assert any(t.startswith("impacting $P_{1}^{2}$") for t in texts)
    assert colour_of("impacting P1") == IMPACTING
    assert colour_of("impacting P1^2") != IMPACTING
    assert colour_of("impacting P1^2") != colour_of("impacting P1^3")


def test_verification_names_the_orbits_as_the_result_did(swept):
    """A rerun meets each orbit as its own first: seeded with the result's orbits, the
    tight rerun names orbit B "impacting P1^2" as the result does, not a changed label."""
    from softimpact_cli.sweep.check import check_sweep, sample_indices

    scene, ds = swept
    picks = sample_indices(ds["label"].size, 40, 3)
    stored = ds["label"].values.ravel()[picks]
    assert (stored == impacting_code(1, 2)).sum() >= 5 and (stored == 1001).sum() >= 5
    report = check_sweep(scene, 40, 3, result=ds)
    assert report["changed"] <= 1, report["changes"]
