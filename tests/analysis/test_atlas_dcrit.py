"""Acceptance: in the study's (phi, d) plane the atlas's grazing curves of the four
non-impacting solutions of the Duffing pair are the dcrit kind's d_crit(phi) curves, to
1e-8 at 64 phases (each curve followed from one point at phi = 0 through the kinks where
another local maximum of x1 - x2 becomes the largest)."""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.atlas import AtlasSettings, Seed, trace_curves
from softimpact_cli.analysis.atlas_augmented import AugmentedMap
from softimpact_cli.analysis.catalogue import (
    body_catalogue,
    body_problem,
    combinations,
    right_attractors,
    sample_states,
)
from softimpact_cli.analysis.continuation import correct
from softimpact_cli.analysis.critical_distance import (
    critical_distance,
    critical_distances,
    uncoupled_pair,
)
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems import get_system

PAIR = get_system("duffing", 2)
STUDY = {**PAIR.defaults(), "k_c": 8.0, "c_c": 10.0, "phi": 0.0, "d": 22.0}
PHASES = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)


def on_curve_at(aug: AugmentedMap, points: list, phi: float) -> float | None:
    """d where the curve crosses phi (Newton at fixed phi from the bracketing chord)."""
    exact = [p for p in points if abs(p.u[4] - phi) < 1e-12]  # the start, an end on an edge
    if exact:
        return float(exact[0].u[-1])
    for left, right in zip(points[:-1], points[1:], strict=True):
        x0, x1 = left.u[4] - phi, right.u[4] - phi
        if x0 * x1 > 0 or x0 == x1:
            continue
        w = x0 / (x0 - x1)
        u, _, _ = correct(aug, (1 - w) * left.u + w * right.u, np.eye(6)[4], 1e-10)
        return float(u[-1])
    return None


@pytest.mark.slow
def test_grazing_curves_equal_the_critical_distances_at_64_phases():
    integ = IntegratorSettings()
    left, _ = body_catalogue(body_problem(PAIR, STUDY, integ),
                             sample_states({"x": (-12, 12), "v": (-12, 12)}, 6, 30, 1))
    right = right_attractors(body_problem(PAIR, STUDY, integ), left, 0.0,
                             PAIR.extra["right_sign"], PAIR.extra["right_phase"])
    combos = list(combinations(left, right))
    assert len(combos) == 4
    seeds = []
    for combo in combos:
        q = combo.orbit.shape[0]
        top, _ = critical_distance(uncoupled_pair(PAIR, STUDY, 0.0), combo.orbit[0], q)
        seeds.append(Seed("grazing", combo.name, q, np.concatenate([combo.orbit[0],
                                                                    [0.0, top]]), 4))
    settings = AtlasSettings(("phi", "d"), ((0.0, 2 * np.pi), (0.0, 22.0)), step=0.05,
                             max_step=0.3, max_points=600, tolerance=1e-10)
    curves = trace_curves(PAIR, STUDY, settings, seeds)
    assert [c.orbit for c in curves] == [c.name for c in combos]
    reference = critical_distances(PAIR, STUDY, left, PHASES)
    names = [str(n) for n in reference["combination_label"].values]
    for curve in curves:
        aug = AugmentedMap(PAIR, STUDY, ("phi", "d"), curve.periods, "grazing")
        d_crit = reference["d_crit"].values[names.index(curve.orbit)]
        along = np.array([on_curve_at(aug, curve.points, phi) for phi in PHASES], dtype=float)
        assert np.all(np.isfinite(along)), curve.orbit  # the curve spans every phase
        assert np.max(np.abs(along - d_crit)) < 1e-8, curve.orbit
