"""Basin figure: markers explained in the legend, one title, phi in pi, letters, t0."""

import numpy as np
import xarray as xr

from softimpact_cli.plot.basins_figure import draw_basins

NAMES = ["L1^1 R1-0^1", "L1^2 R1-0^1"]
LATEX = [r"$L^{1}_{1}R^{1}_{1-0}$", r"$L^{2}_{1}R^{1}_{1-0}$"]


def basins(phis=(0.0, 0.573 * np.pi), t0=0.0, **attrs) -> xr.Dataset:
    """A plane sweep as the store holds it: len(phis) panels of 4 x 3 initial conditions,
    two solutions, each with one stroboscopic point."""
    n = len(phis)
    label = np.zeros((n, 4, 3), dtype=np.int32)
    label[:, :2, :] = 1
    points = np.full((2, n, 1, 4), np.nan)
    points[0, :, 0] = [0.0, 0.0, 1.0, 0.0]
    points[1, :, 0] = [-6.0, 0.0, 1.0, 0.0]
    return xr.Dataset(
        {"label": (("panel", "x1", "x2"), label),
         "label_code": (("label_index",), np.array([0, 1], dtype=np.int32)),
         "label_name": (("label_index",), np.array(NAMES)),
         "label_latex": (("label_index",), np.array(LATEX)),
         "attractor_points": (("label_index", "panel", "orbit_point", "variable"), points),
         "combination_name": (("combination",), np.array(NAMES))},
        coords={"panel": np.arange(n), "d": ("panel", [9.0] * n), "phi": ("panel", list(phis)),
                "k_c": ("panel", [8.0] * n), "c_c": ("panel", [10.0] * n),
                "t0": ("panel", [t0] * n), "x1": np.linspace(-12, 12, 4),
                "x2": np.linspace(-12, 12, 3), "variable": ["x1", "v1", "x2", "v2"]},
        attrs={"analysis": "basins", "ic_kind": "plane", "ic_dims": "x1 x2",
               "grid_swept": "d phi k_c c_c", "grid_dims": "panel", "t0_mode": "fixed",
               "forcing_period": 4.0, "plane_fixed": "", "model": "duffing", "bodies": 2,
               "parameters": "c=0.05, k1=1.0, d=6.0, phi=0.0, k_c=8.0, c_c=10.0, law=paper",
               **attrs})


def legend_entries(legend) -> list[list]:
    """The artists drawn as each legend entry's handle."""
    from matplotlib.offsetbox import DrawingArea

    out = []

    def walk(box):
        for child in box.get_children():
            if isinstance(child, DrawingArea):
                out.append(child.get_children())
            elif hasattr(child, "get_children"):
                walk(child)

    walk(legend)
    return out


def all_text(fig) -> list[str]:
    texts = [fig.get_suptitle()] if fig._suptitle else []
    for ax in fig.axes:
        texts += [ax.get_title()] + [t.get_text() for t in ax.texts]
    return texts


def test_legend_pairs_each_basin_with_its_attractor_marker():
    fig = draw_basins(basins())
    legend = fig.axes[0].get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    assert [t.split()[0] for t in texts] == LATEX and "50.0%" in texts[0]
    # each entry draws the basin's colour patch beside its attractor's marker
    entries = legend_entries(legend)
    assert len(entries) == 2
    for artists in entries:
        kinds = {type(a).__name__ for a in artists}
        assert {"Rectangle", "Line2D"} <= kinds
        assert any(getattr(a, "get_marker", lambda: None)() == "o" for a in artists)
    markers = [line for line in fig.axes[0].get_lines() if line.get_marker() == "o"]
    assert len(markers) == 2 and all(m.get_markeredgecolor() == "k" for m in markers)
    assert "markers" in fig.get_suptitle()


def test_one_title_not_repeated_in_the_panels():
    fig = draw_basins(basins())
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    # panel titles carry only what differs between panels; the rest is said once
    assert all("k_c" not in t and "t_0" not in t for t in titles)
    assert "k_c = 8" in fig.get_suptitle() and "t_0 = 0" in fig.get_suptitle()
    assert "4 x 3 initial conditions" in fig.get_suptitle()
    one = draw_basins(basins(phis=(np.pi / 2,)))
    assert not one._suptitle or not one.get_suptitle()
    assert sum(bool(ax.get_title()) for ax in one.axes) == 1


def test_phi_in_multiples_of_pi_panel_letters_and_start_time():
    fig = draw_basins(basins(t0=2.0))
    texts = all_text(fig)
    assert any(r"\varphi = 0.573\pi" in t for t in texts)
    assert not any("1.80013" in t for t in texts)
    assert "(a)" in texts and "(b)" in texts
    assert "t_0 = T/2" in fig.get_suptitle()
