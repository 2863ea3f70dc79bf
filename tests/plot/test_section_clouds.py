"""plot stability --attractors: the curves beside the attractors' section clouds."""

import numpy as np
import xarray as xr

from softimpact_cli import plot
from softimpact_cli.analysis.nonperiodic import Attractor, Recurrent, attractor_table
from softimpact_cli.kernels.codes import IMPACTING_CHAOTIC_BASE, QUASI_PERIODIC_BASE
from tests.plot.test_stability_dcrit_figures import stability_sweep


def with_attractors(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with a chaotic set at phi = 0 and a torus at phi = pi/2 (grid points 0, 1)."""
    ring = np.linspace(0, 2 * np.pi, 50)
    rows = []
    for k, (kind, impacting, lam) in enumerate([("impacting chaotic", True, 0.02),
                                                ("quasi-periodic", False, 0.0)]):
        cloud = np.stack([np.cos(ring) + 3 * k, np.sin(ring), 0 * ring, 0 * ring], axis=1)
        rec = Recurrent(10 * k, k, np.zeros((1, 4), np.int64), cloud, impacting, cloud[-1], 0)
        a = Attractor(kind, k + 1, impacting, set())
        a.add(rec, {(0, 0, 0, 0)}, (np.array([lam, -0.1, -0.2, -0.3]), np.full(4, 1e-3)))
        rows.append(a)
    label = ds["label"].values.copy()
    label[0, 0], label[1, 0] = IMPACTING_CHAOTIC_BASE + 1, QUASI_PERIODIC_BASE + 2
    names = list(ds["label_name"].values) + ["impacting chaotic A1", "quasi-periodic A2"]
    ds = ds.assign(label=(ds["label"].dims, label))
    ds = ds.drop_vars(["label_code", "label_name"]).assign(
        label_code=("label_index", np.array([0, 1, IMPACTING_CHAOTIC_BASE + 1,
                                             QUASI_PERIODIC_BASE + 2], np.int32)),
        label_name=("label_index", np.array(names)))
    return xr.merge([ds, attractor_table(rows, ("x1", "v1", "x2", "v2"))],
                    combine_attrs="override")


def test_the_clouds_panel_names_each_attractor_with_its_exponent():
    fig = plot.stability(with_attractors(stability_sweep()), attractors=True)
    left, right = fig.axes[:2]
    texts = [t.get_text() for t in right.get_legend().get_texts()]
    assert texts == [r"impacting chaotic A1 (phi=0): $\lambda_1$ = +0.0200",
                     r"quasi-periodic A2 (phi=1.571): $\lambda_1$ = +0.0000"]
    assert len(right.lines) == 2 and right.lines[1].get_xdata().min() > 1.5
    curves = [t.get_text() for t in left.get_legend().get_texts()]
    assert "impacting chaotic $A_{1}$" in curves and "quasi-periodic $A_{2}$" in curves
