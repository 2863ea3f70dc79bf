"""Deduplication and naming of the second stage's recurrent sets (analysis/nonperiodic.py),
and the chunk arrays they travel in (sweep/second_stage.py): no integration here."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softimpact_cli.analysis.nonperiodic import (
    SETTLING,
    Recurrent,
    attractor_table,
    identify,
    kind_of,
    known_attractors,
)
from softimpact_cli.analysis.section_follow import SectionFollow
from softimpact_cli.kernels.codes import (
    CHAOTIC_BASE,
    IMPACTING_QUASI_PERIODIC_BASE,
    QUASI_PERIODIC_BASE,
    UNRESOLVED_LABEL,
)
from softimpact_cli.sweep.second_stage import pack, unpack

# three recurrent sets on the section: a chaotic blob around (0, 0), a contracting set
# around (20, 20) (a periodic orbit still settling), an impacting torus around (-20, 5)
CENTRES = {0: (0.0, 0.0), 1: (20.0, 20.0), 2: (-20.0, 5.0)}
LARGEST = {0: 0.02, 1: -0.1, 2: 0.0}


def recurrent(flat: int, which: int, seed: int) -> Recurrent:
    rng = np.random.default_rng(seed)
    cloud = np.array(CENTRES[which]) + rng.uniform(-3, 3, size=(300, 2))
    cells = np.unique(np.floor(cloud / 0.5).astype(np.int64), axis=0)
    return Recurrent(flat, flat // 10, cells, cloud, which == 2, cloud[-1], 100.0 * flat)


def spectrum_of_centre(point, state, t):
    which = min(CENTRES, key=lambda k: np.hypot(*(np.array(CENTRES[k]) - state)))
    return np.array([LARGEST[which], -0.07]), np.array([1e-3, 1e-3])


def test_kind_of_the_largest_exponent():
    assert kind_of(False, 0.02, 0.004) == "chaotic"
    assert kind_of(True, 0.02, 0.004) == "impacting chaotic"
    assert kind_of(False, -0.003, 0.004) == "quasi-periodic"
    assert kind_of(True, 0.004, 0.004) == "impacting quasi-periodic"
    assert kind_of(False, -0.01, 0.004) == SETTLING


def test_sets_are_deduplicated_numbered_and_named():
    which = [1, 0, 2, 0, 1, 2, 0]
    found = [recurrent(10 * i + 3, w, seed=i) for i, w in enumerate(which)]
    codes, attractors = identify(found, spectrum_of_centre, 0.004)
    # the settling set takes no number: the chaotic one is A1, the torus A2
    assert [a.name for a in attractors] == [f"unresolved ({SETTLING})", "chaotic A1",
                                            "impacting quasi-periodic A2"]
    expected = {1: UNRESOLVED_LABEL, 0: CHAOTIC_BASE + 1, 2: IMPACTING_QUASI_PERIODIC_BASE + 2}
    assert codes.tolist() == [expected[w] for w in which]
    # every trajectory sits at its own grid point (flat // 10): one row per point
    assert [sum(p.members for p in a.at.values()) for a in attractors] == [2, 3, 2]
    assert [sorted(a.at) for a in attractors] == [[0, 4], [1, 3, 6], [2, 5]]
    table = attractor_table(attractors, ("x", "v"))
    assert table["nonperiodic_code"].values.tolist() == [expected[w] for w in (1, 1, 0, 0,
                                                                             0, 2, 2)]
    assert table["nonperiodic_cloud"].shape == (7, 300, 2)
    assert table["nonperiodic_flat"].values.tolist() == [3, 43, 13, 33, 63, 23, 53]


def test_a_set_that_changes_kind_between_grid_points_is_another_attractor():
    # the same cells at grid points 0 and 1, chaotic at 0 and a torus at 1 (as figure
    # 15(b)'s set at c_c = 3 and 4), then chaotic again at point 2
    found = [recurrent(10 * p + 1, 0, seed=p) for p in range(3)]

    def by_point(point, state, t):
        return np.array([0.0 if point == 1 else 0.02, -0.1]), np.array([1e-3, 1e-3])

    codes, attractors = identify(found, by_point, 0.004)
    assert [a.name for a in attractors] == ["chaotic A1", "quasi-periodic A2"]
    assert [sorted(a.at) for a in attractors] == [[0, 2], [1]]
    assert codes.tolist() == [CHAOTIC_BASE + 1, QUASI_PERIODIC_BASE + 2, CHAOTIC_BASE + 1]


def test_known_attractors_keep_their_codes():
    """A verification rerun names what it finds after the result it checks."""
    first = [recurrent(1, 2, seed=1), recurrent(2, 0, seed=2)]
    _, attractors = identify(first, spectrum_of_centre, 0.004)
    table = attractor_table(attractors, ("x", "v"))
    again = [recurrent(5, 0, seed=9), recurrent(8, 1, seed=8)]
    codes, _ = identify(again, spectrum_of_centre, 0.004, known_attractors(table, 0.5))
    assert codes.tolist() == [CHAOTIC_BASE + 2, UNRESOLVED_LABEL]


def test_a_set_with_another_contact_flag_is_another_attractor():
    a = recurrent(0, 0, seed=1)
    b = recurrent(1, 0, seed=2)
    b = Recurrent(b.flat, b.point, b.cells, b.cloud, True, b.end_state, b.end_time)
    codes, attractors = identify([a, b], spectrum_of_centre, 0.004)
    assert [x.name for x in attractors] == ["chaotic A1", "impacting chaotic A2"]


def test_identify_wants_flat_order():
    with pytest.raises(ValueError, match="increasing flat index"):
        identify([recurrent(5, 0, 1), recurrent(2, 0, 2)], spectrum_of_centre, 0.004)


def follow_of(rec: Recurrent) -> SectionFollow:
    return SectionFollow("recurrent", 0, 10, np.zeros((0, 2)), rec.cells, rec.cloud, 3,
                         0.5 if rec.impacting else -1.0, rec.end_state, rec.end_time)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.sampled_from([0, 1, 2]), min_size=1, max_size=12),
       st.integers(1, 5), st.randoms(use_true_random=False))
def test_labels_do_not_depend_on_chunks_or_their_order(which, chunk, rnd):
    """Whatever the chunk size and the order chunks finish in (workers, executors), the
    gathered sets give the same codes: the parent sorts by flat index before naming."""
    found = [recurrent(7 * i, w, seed=i) for i, w in enumerate(which)]
    reference, _ = identify(found, spectrum_of_centre, 0.004)
    parts = [pack([(r.flat, r.point, follow_of(r)) for r in found[i: i + chunk]], 2)
             for i in range(0, len(found), chunk)]
    rnd.shuffle(parts)
    gathered = sorted((r for p in parts for r in unpack(p)), key=lambda r: r.flat)
    assert [r.flat for r in gathered] == [r.flat for r in found]
    assert all(np.array_equal(a.cells, b.cells) and a.impacting == b.impacting
               for a, b in zip(gathered, found, strict=True))
    codes, _ = identify(gathered, spectrum_of_centre, 0.004)
    assert codes.tolist() == reference.tolist()


def test_a_chunk_file_from_before_the_second_stage_has_no_sets():
    assert unpack({"label": np.zeros(3)}) == []
    assert unpack(pack([], 4)) == []


def test_recurrent_sets_survive_a_chunk_file(tmp_path):
    """What a resumed run reads back from a chunk file names the same attractors."""
    from softimpact_cli.store.sweep_store import RunIdentity, SweepStore
    from softimpact_cli.sweep.chunks import RESULT_FIELDS

    found = [recurrent(i, w, seed=i) for i, w in enumerate([0, 2, 0])]
    result = {k: np.zeros(3, dtype=t) for k, t in RESULT_FIELDS.items()}
    result["orbits"] = {}
    result.update(pack([(r.flat, r.point, follow_of(r)) for r in found], 2))
    identity = RunIdentity("c" * 64, chunk_size=3, n_total=3)
    store = SweepStore(tmp_path / "r.h5")
    store.write_chunk(0, result, identity, session_started=1.0)
    back = unpack(store.read_chunk(0, identity)[0])
    assert [(r.flat, r.point, r.impacting) for r in back] == [
        (r.flat, r.point, r.impacting) for r in found]
    assert all(np.array_equal(a.cloud, b.cloud) and np.array_equal(a.end_state, b.end_state)
               for a, b in zip(back, found, strict=True))
    assert identify(back, spectrum_of_centre, 0.004)[0].tolist() == \
        identify(found, spectrum_of_centre, 0.004)[0].tolist()
