"""Eight bodies, 2n = 16 state variables (issue 32 item 6), before the system exists: a
synthetic 8-body result goes through the chunk files (labels of many bodies' names and of
numbered impacting orbits, orbits of 16 variables) and the basin figure (a plane of two
of the 16 coordinates, the legend in the n-body names, every basin its own colour)."""

import numpy as np
import xarray as xr

from softimpact_cli.analysis.catalogue import Attractor, Catalogue, label_orbit
from softimpact_cli.analysis.labels import catalogue_code, code_of, impacting_code, name_of
from softimpact_cli.kernels.codes import EXTENDED_CATALOGUE_BASE
from softimpact_cli.plot.basins_figure import draw_basins
from softimpact_cli.plot.palette import colour_of
from softimpact_cli.store.sweep_store import RunIdentity, SweepStore
from softimpact_cli.sweep.chunks import RESULT_FIELDS

BODIES = 8
STATE = tuple(f"{q}{i}" for i in range(1, BODIES + 1) for q in ("x", "v"))


def body_attractors():
    """Two fake period-1 attractors of one body (at x = -2 and x = 3) and a period-2 one."""
    return (Attractor(1, 1, np.array([[-2.0, 0.0]]), 2.0, np.zeros(2), 0.0, 0.0),
            Attractor(2, 1, np.array([[3.0, 0.5]]), 3.0, np.zeros(2), 0.0, 0.0),
            Attractor(3, 2, np.array([[6.0, 0.0], [5.0, 1.0]]), 6.0, np.zeros(2), 0.0, 0.0))


def catalogue() -> Catalogue:
    atts = body_attractors()
    return Catalogue("chain", {}, atts, atts, (), {}, 0, more=(atts,) * (BODIES - 2))


def joint(choice) -> np.ndarray:
    """The (q, 16) orbit of bodies on attractors ``choice`` (indices into the body's)."""
    atts = body_attractors()
    q = max(atts[k].period for k in choice)
    return np.array([np.concatenate([atts[k].points[t % atts[k].period] for k in choice])
                     for t in range(q)])


def test_chunk_files_hold_sixteen_state_orbits_and_many_bodies_codes(tmp_path):
    cat = catalogue()
    names = cat.names
    index = {n: i for i, n in enumerate(names)}
    assert len(names) > 1000  # the extended codes are needed
    choices = [(0,) * 8, (1, 0, 1, 0, 1, 0, 1, 0), (2, 2, 1, 1, 0, 0, 2, 1)]
    orbits, codes = {}, []
    for k, choice in enumerate(choices):
        orbit = joint(choice)
        code = code_of(label_orbit(cat, orbit, impacting=False), index)
        codes.append(code)
        orbits[(0, code)] = (k, orbit)
    assert max(codes) > EXTENDED_CATALOGUE_BASE  # a combination past the first 1000
    codes += [impacting_code(1), impacting_code(1, 2)]
    orbits[(0, codes[-1])] = (4, np.arange(16.0).reshape(1, 16))
    identity = RunIdentity("b" * 64, chunk_size=5, n_total=5)
    result = {k: np.zeros(5, dtype=t) for k, t in RESULT_FIELDS.items()}
    result["label"][:] = codes
    result["orbits"] = orbits
    store = SweepStore(tmp_path / "r.h5")
    store.ensure_parts()
    store.write_chunk(0, result, identity, session_started=1.0)
    back, _ = store.read_chunk(0, identity)
    assert back["label"].tolist() == codes  # int32 holds every code
    for key, (flat, pts) in orbits.items():
        assert back["orbits"][key][0] == flat
        assert np.array_equal(back["orbits"][key][1], pts) and pts.shape[1] == 16
    assert [name_of(c, names) for c in codes[:3]] == [
        "B1:P1^1 " + " ".join(f"B{i}:P1-0^1" for i in range(2, 9)),
        "B1:P1^2 " + " ".join(f"B{i}:P1-0^{1 + i % 2}" for i in range(2, 9)),
        "B1:P2^3 B2:P2-0^3 B3:P1-0^2 B4:P1-0^2 B5:P1-0^1 B6:P1-0^1 B7:P2-0^3 B8:P1-0^2"]
    assert name_of(codes[-1], names) == "impacting P1^2"


def plane(codes, names) -> xr.Dataset:
    """A basin plane over (x1, x8) of an 8-body result: 6 x 5 starts, the labels in bands."""
    label = np.array(codes, dtype=np.int32)[np.arange(30) % len(codes)].reshape(6, 5)
    all_names = [name_of(c, names) for c in codes]
    points = np.full((len(codes), 1, 1, 16), np.nan)
    for i in range(len(codes)):
        points[i, 0, 0] = np.linspace(-1, 1, 16) * (i + 1)
    from softimpact_cli.analysis.labels import latex_of

    return xr.Dataset(
        {"label": (("panel", "x1", "x8"), label[None]),
         "label_code": (("label_index",), np.array(codes, dtype=np.int32)),
         "label_name": (("label_index",), np.array(all_names)),
         "label_latex": (("label_index",), np.array([latex_of(n) for n in all_names])),
         "attractor_points": (("label_index", "panel", "orbit_point", "variable"), points)},
        coords={"panel": [0], "d": ("panel", [2.0]), "phi": ("panel", [0.0]),
                "k_c": ("panel", [8.0]), "c_c": ("panel", [10.0]), "t0": ("panel", [0.0]),
                "x1": np.linspace(-3, 3, 6), "x8": np.linspace(-3, 3, 5),
                "variable": list(STATE)},
        attrs={"analysis": "basins", "ic_kind": "plane", "ic_dims": "x1 x8",
               "grid_swept": "d phi k_c c_c", "grid_dims": "panel", "t0_mode": "fixed",
               "forcing_period": 4.0, "plane_fixed": "", "model": "chain", "bodies": BODIES,
               "catalogue_names": list(names)})


def test_the_basin_figure_draws_sixteen_state_results_apart():
    names = catalogue().names
    # catalogue solutions take the palette's 30 colours in catalogue order, cyclically
    # (plot/palette.py): 0 and 1501 differ, 0 and 1500 would not
    codes = [catalogue_code(0), catalogue_code(1501), impacting_code(1), impacting_code(1, 2)]
    fig = draw_basins(plane(codes, names))
    legend = fig.axes[0].get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    assert len(texts) == 4
    assert any(t.startswith("$B_{1}{:}P^{1}_{1}") for t in texts)
    assert any("impacting $P_{1}^{2}$" in t for t in texts)
    colours = {colour_of(name_of(c, names), names) for c in codes}
    assert len(colours) == 4  # each basin its own colour
    fig.canvas.draw()  # the legend's mathtext renders
