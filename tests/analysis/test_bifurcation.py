"""Following solutions along d: destruction at grazing, stable under refinement."""

import numpy as np
import pytest

from softimpact_cli.analysis.bifurcation import bifurcation_dataset, d_values
from softimpact_cli.analysis.catalogue import sample_states
from softimpact_cli.analysis.critical_distance import critical_distances
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.store.catalogues import build_catalogue
from softimpact_cli.systems import get_system

VALUES = dict(c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3, d=22.5, phi=5 * np.pi / 8, k_c=8.0,
              c_c=20.0, law="paper")
SYSTEM = get_system("duffing", 2)


@pytest.fixture(scope="module")
def catalogue():
    return build_catalogue(SYSTEM, VALUES, IntegratorSettings(),
                           sample_states({"x": (-12, 12), "v": (-12, 12)}, 8, 40, seed=3))


def run(catalogue, step, integrator):
    return bifurcation_dataset(SYSTEM, VALUES, integrator, catalogue, ["L1^2 R1-0^2"],
                               d_values(17.2, 15.0, step))


def test_destruction_point_stable_under_refinement(catalogue):
    coarse = run(catalogue, 0.2, IntegratorSettings())
    fine = run(catalogue, 0.1, IntegratorSettings(rtol=5e-9, atol=5e-11,
                                                   convergence_tol=5e-7))
    a = float(coarse["destroyed_at"].values[0])
    b = float(fine["destroyed_at"].values[0])
    assert np.isfinite(a) and abs(a - b) < 1e-4
    # it is the grazing value: the combination's critical distance at this phi
    dc = critical_distances(SYSTEM, VALUES, list(catalogue.attractors),
                            np.array([VALUES["phi"]]))
    names = list(dc["combination_label"].values)
    assert a == pytest.approx(float(dc["d_crit"].values[names.index("L1^2 R1-0^2"), 0]),
                              abs=1e-8)
    # and it lies between the last step where the branch lived and the first where not
    d = coarse["d"].values
    alive = coarse["label"].values[0] == catalogue.names.index("L1^2 R1-0^2")
    last_alive = d[alive].min()
    first_dead = d[~alive].max()
    assert first_dead < a <= last_alive


def test_after_destruction_impacting_then_falls(catalogue):
    ds = bifurcation_dataset(SYSTEM, VALUES, IntegratorSettings(), catalogue,
                             ["L1^2 R1-0^2"], d_values(17.0, 14.0, 0.25))
    high, low = ds["impacting_range"].values[0]
    assert ds["destroyed_at"].values[0] > high >= low
    assert str(ds["falls_to"].values[0]) in catalogue.names
    # on the branch's own stretch no impacting state is recorded
    alive = ds["label"].values[0] == catalogue.names.index("L1^2 R1-0^2")
    assert not ds["impacting"].values[0][alive].any()
