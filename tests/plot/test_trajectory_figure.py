"""Trajectory figure: a non-impacting orbit shows a clearance, an impacting one a
penetration."""

import numpy as np
import xarray as xr

from softimpact_cli.plot.trajectory_figure import draw_trajectory


def trajectory(max_penetration: float, impacting: int) -> xr.Dataset:
    t = np.linspace(0, 8.0, 81)
    state = np.stack([np.sin(t), np.cos(t), -np.sin(t), -np.cos(t)], axis=1)
    st = np.arange(5) * 2.0
    return xr.Dataset(
        {"state": (("time", "variable"), state),
         "section_time": (("section",), st),
         "section_state": (("section", "variable"), state[::20])},
        coords={"time": t, "variable": ["x1", "v1", "x2", "v2"]},
        attrs={"analysis": "trajectory", "model": "duffing", "bodies": 2,
               "forcing_period": 2.0, "t0": 1.0, "outcome": "converged", "period": 1,
               "max_penetration": max_penetration, "impacting": impacting,
               "parameters": "c=0.05, d=6.0, phi=1.9634954084936207",
               "scene_text": "# synthetic: no scene"})


def summary(fig) -> str:
    return "\n".join(t.get_text() for ax in fig.axes for t in ax.texts)


def test_non_impacting_orbit_shows_its_clearance():
    text = summary(draw_trajectory(trajectory(-3.5, 0)))
    assert "clearance" in text and "3.5" in text and "penetration" not in text


def test_impacting_orbit_shows_its_penetration():
    text = summary(draw_trajectory(trajectory(0.25, 1)))
    assert "penetration" in text and "0.25" in text and "clearance" not in text


def test_title_has_phi_in_pi_and_the_start_time():
    fig = draw_trajectory(trajectory(-3.5, 0))
    assert r"\varphi = 5\pi/8" in fig.get_suptitle()
    assert "t_0 = T/2" in fig.get_suptitle()
