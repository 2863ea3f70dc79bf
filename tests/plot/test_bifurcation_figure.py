"""Bifurcation figure: each point is drawn in the colour of the solution it is on."""

import numpy as np
import xarray as xr
from matplotlib.colors import to_hex

from softimpact_cli.kernels.codes import IMPACTING_BASE, UNRESOLVED_LABEL
from softimpact_cli.plot.bifurcation_figure import draw_bifurcation
from softimpact_cli.plot.palette import IMPACTING, colour_of

NAMES = ["L1^1 R1-0^1", "L1^1 R1-0^2"]


def followed_pair() -> xr.Dataset:
    """Two branches over 6 steps of d, as ``bifurcation_dataset`` stores them: branch 1
    is destroyed at d = 3.5, impacts at d = 3, then falls onto branch 0's solution
    (x1 = -0.2, x2 = 1) at d = 2 and 1; branch 0 is unresolved at the last step."""
    d = np.array([6.0, 5.0, 4.0, 3.0, 2.0, 1.0])
    x1 = np.array([[-0.2] * 6, [-6.0, -6.0, -6.0, -7.0, -0.2, -0.2]])[:, :, None]
    x2 = np.array([[1.0] * 6, [9.0, 9.0, 9.0, 5.0, 1.0, 1.0]])[:, :, None]
    code = np.array([[0, 0, 0, 0, 0, UNRESOLVED_LABEL], [1, 1, 1, IMPACTING_BASE + 1, 0, 0]])
    impacting = (code >= IMPACTING_BASE).astype(np.int8)
    codes = [UNRESOLVED_LABEL, 0, 1, IMPACTING_BASE + 1]
    label_names = ["unresolved", *NAMES, "impacting P1"]
    return xr.Dataset(
        {"section_x1": (("branch", "d", "point"), x1),
         "section_x2": (("branch", "d", "point"), x2),
         "label": (("branch", "d"), code.astype(np.int32)),
         "impacting": (("branch", "d"), impacting),
         "period": (("branch", "d"), np.ones((2, 6), dtype=np.int16)),
         "branch_name": (("branch",), np.array(NAMES, dtype=object)),
         "destroyed_at": (("branch",), [np.nan, 3.5]),
         "falls_to": (("branch",), np.array(["", NAMES[0]], dtype=object)),
         "impacting_range": (("branch", "bound"), [[np.nan, np.nan], [3.0, 3.0]]),
         "label_code": (("label_index",), np.array(codes, dtype=np.int32)),
         "label_name": (("label_index",), np.array(label_names, dtype=object)),
         "combination_name": (("combination",), np.array(NAMES, dtype=object))},
        coords={"branch": [0, 1], "d": d, "point": [0], "bound": ["high", "low"]},
        attrs={"analysis": "bifurcation", "model": "duffing", "forcing_period": 2 * np.pi,
               "parameters": "c=0.05, d=6.0, phi=1.9634954084936207, k_c=8.0"})


def drawn_points(ax) -> dict[tuple[float, float], set[tuple[str, str]]]:
    """(d, x) -> the set of (colour, marker) drawn there."""
    out: dict = {}
    for line in ax.get_lines():
        if line.get_linestyle() not in ("None", ""):
            continue
        for x, y in zip(line.get_xdata(), line.get_ydata(), strict=True):
            out.setdefault((float(x), float(y)), set()).add(
                (to_hex(line.get_color()), line.get_marker()))
    return out


def test_a_point_takes_the_colour_of_the_solution_it_is_on():
    fig = draw_bifurcation(followed_pair())
    left = drawn_points(fig.axes[0])
    blue, orange = colour_of(NAMES[0], NAMES), colour_of(NAMES[1], NAMES)
    # branch 1 before destruction: its own colour
    assert left[(6.0, -6.0)] == {(orange, "o")}
    # after falling onto branch 0's solution it is drawn in that solution's colour: the
    # fallen branch no longer hides the solution it fell to under its own colour
    assert left[(2.0, -0.2)] == {(blue, "o")}
    assert left[(1.0, -0.2)] == {(blue, "o")} | {c for c in left[(1.0, -0.2)] if c[1] == "+"}
    # impacting and unresolved states have their own styles
    assert left[(3.0, -7.0)] == {(IMPACTING, "x")}
    assert ("+" in {m for _, m in left[(1.0, -0.2)]})
    assert all(orange not in {c for c, _ in v} for k, v in left.items() if k[0] <= 3.0)


def test_one_title_with_phi_in_multiples_of_pi_and_panel_letters():
    fig = draw_bifurcation(followed_pair())
    title = fig.get_suptitle()
    assert r"5\pi/8" in title and "t_0" in title
    assert [ax.get_title() for ax in fig.axes] == ["", ""]
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert "(a)" in texts and "(b)" in texts
