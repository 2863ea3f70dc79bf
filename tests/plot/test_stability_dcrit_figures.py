"""Stability and d_crit figures: phi in multiples of pi, t0 and parameters in the title."""

import numpy as np
import xarray as xr

from softimpact_cli.analysis.stability import basin_stability
from softimpact_cli.plot.dcrit_figure import draw_dcrit
from softimpact_cli.plot.stability_figure import draw_stability

NAMES = ["L1^1 R1-0^1", "L1^2 R1-0^1"]


def stability_sweep(t0=0.0) -> xr.Dataset:
    phi = np.array([0.0, np.pi / 2, np.pi, 3 * np.pi / 2])
    label = np.zeros((4, 10), dtype=np.int32)
    label[:, :3] = 1
    one = ("phi", np.ones(4))
    return xr.Dataset(
        {"label": (("phi", "sample"), label),
         "label_code": (("label_index",), np.array([0, 1], dtype=np.int32)),
         "label_name": (("label_index",), np.array(NAMES)),
         "combination_name": (("combination",), np.array(NAMES))},
        coords={"phi": phi, "d": ("phi", 9 * one[1]), "k_c": one, "c_c": one,
                "t0": ("phi", np.full(4, t0)), "sample": np.arange(10)},
        attrs={"analysis": "stability", "ic_dims": "sample", "grid_dims": "phi",
               "grid_swept": "phi", "t0_mode": "fixed", "forcing_period": 4.0,
               "model": "duffing", "bodies": 2,
               "parameters": "c=0.05, d=9.0, phi=0.0, k_c=1.0, c_c=1.0, law=paper"})


def test_stability_title_has_parameters_and_t0_and_phi_ticks_in_pi():
    ds = stability_sweep(t0=1.0)
    fig = draw_stability(ds, basin_stability(ds), "phi")
    ax = fig.axes[0]
    title = ax.get_title()
    assert "t_0 = T/4" in title and "d = 9" in title and "c = 0.05" in title
    assert r"\varphi" not in title  # the swept axis is on the horizontal axis, not here
    assert r"$\pi/2$" in [t.get_text() for t in ax.get_xticklabels()]
    assert not fig._suptitle


def test_entropy_of_the_shares_on_a_right_hand_axis():
    """3 of 10 samples in one basin at every phase: H = -(0.3 ln 0.3 + 0.7 ln 0.7)."""
    ds = stability_sweep()
    bs = basin_stability(ds)
    plain = draw_stability(ds, bs, "phi")
    assert len(plain.axes) == 1
    fig = draw_stability(ds, bs, "phi", entropy=True)
    assert len(fig.axes) == 2
    right = fig.axes[1]
    assert right.get_ylabel() == "basin entropy of the shares H (nats)"
    h = -(0.3 * np.log(0.3) + 0.7 * np.log(0.7))
    np.testing.assert_allclose(right.lines[0].get_ydata(), h)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "entropy of the shares H (right axis)" in labels


def dcrit_result() -> xr.Dataset:
    phi = np.linspace(0, 2 * np.pi, 9)
    trace_phi = np.array([np.pi / 4, np.pi])
    trace = np.sin(np.linspace(0, 2 * np.pi, 17))[None, None, :].repeat(2, 0).repeat(2, 1)
    return xr.Dataset(
        {"d_crit": (("combination", "phi"), np.vstack([2 + np.sin(phi), 8 + np.cos(phi)])),
         "combination_label": (("combination",), np.array(NAMES)),
         "combination_name": (("combination",), np.array(NAMES)),
         "relative_trace": (("trace_phi", "combination", "trace_sample"), trace)},
        coords={"phi": phi, "trace_phi": trace_phi, "combination": [0, 1]},
        attrs={"analysis": "dcrit", "forcing_period": 4.0, "trace_samples_per_period": 16,
               "model": "duffing", "parameters": "c=0.05, w=1.3, d=6.0, phi=0.0"})


def test_dcrit_phases_in_multiples_of_pi_and_panel_letters():
    fig = draw_dcrit(dcrit_result())
    titles = [ax.get_title() for ax in fig.axes]
    assert any(r"\varphi = \pi/4" in t for t in titles)
    assert any(t.endswith(r"\varphi = \pi$") for t in titles)
    assert not any(r"1\pi" in t or "0.25" in t for t in titles)
    ticks = [t.get_text() for t in fig.axes[0].get_xticklabels()]
    assert r"$2\pi$" in ticks and r"$\pi/4$" in ticks
    letters = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert {"(a)", "(b)", "(c)"} <= letters
    assert r"\omega = 1.3" in fig.get_suptitle() and "d = 6" not in fig.get_suptitle()


def test_plot_stability_entropy_from_the_command_line(tmp_path):
    from click.testing import CliRunner

    from softimpact_cli.cli import main
    from softimpact_cli.store import write_result

    ds = stability_sweep()
    ds.attrs.update({"complete": 1, "scene_text": "", "n": 40})
    result = write_result(ds, tmp_path / "s.h5")
    out = tmp_path / "s.png"
    run = CliRunner().invoke(main, ["plot", "stability", str(result), "-o", str(out),
                                    "--entropy"])
    assert run.exit_code == 0, run.output
    assert out.stat().st_size > 10_000
