"""A Neimark-Sacker point checked by brute force, independently of its location by the
continuation (a complex pair of the saltation monodromy on the unit circle).

Figure 14(c)'s Duffing pair (phi = 5.28, d = 10.5, k_c = 8): the impacting period-1 orbit
of the Lyapunov scan loses stability as c_c falls through c_NS = 4.0662267. Plain iteration
of the stroboscopic map (no variational equations, no Newton) must show:

- on both sides, a small perturbation of the fixed point decays or grows at the rate
  ln|mu| per period and turns by arg(mu) per period (the rotation number of the linear
  map), so the rates measured on either side bracket c_NS;
- past it, the bifurcation is subcritical: no small invariant curve growing like
  sqrt(c_NS - c_c); the perturbation grows until the trajectory lands on a distant torus
  (largest Lyapunov exponent 0) of the same size however close to c_NS, which also
  persists above c_NS beside the stable fixed point (hysteresis) and is gone further up.

The same orbit continued in d at c_c = 4.3 regains its stability at a supercritical NS
point (d = 9.040184), where the invariant curve grows like the square root (last test).
"""

from __future__ import annotations

import numpy as np
import pytest

from softimpact_cli.analysis.continuation import Settings, correct
from softimpact_cli.analysis.continuation_branches import continue_starts
from softimpact_cli.analysis.engine import Problem, record_trajectory
from softimpact_cli.analysis.lyapunov import lyapunov_spectrum
from softimpact_cli.analysis.shooting import OrbitMap
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.systems import get_system

PAIR = get_system("duffing", 2)
FIG14C = {**PAIR.defaults(), "d": 10.5, "phi": 5.28, "k_c": 8.0, "c_c": 4.3}
ORBIT_AT_4_3 = np.array([-9.55833715, -0.23131117, 1.73677921, -1.83088462])  # t = 0
ITERATION = IntegratorSettings(method="dopri5", rtol=1e-10, atol=1e-12)
BASE = OrbitMap(PAIR, FIG14C, "c_c", 1)


@pytest.fixture(scope="module")
def ns():
    """The Neimark-Sacker event of the impacting orbit followed from c_c = 4.3 down."""
    (branch,), _ = continue_starts(BASE, [("impacting P1", ORBIT_AT_4_3, 1)], 4.3,
                                   Settings((3.9, 4.3), step=0.05, max_step=0.2),
                                   switch_depth=0)
    events = [e for e in branch.events if e.kind == "Neimark-Sacker"]
    assert len(events) == 1
    return events[0].point


def fixed_point(c_c: float, near: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(state (4,), multipliers (4,) largest first, eigenvectors (4, 4)) at c_c by Newton."""
    u, value, _ = correct(BASE, np.append(near, c_c), None, 1e-10)
    mu, vectors = np.linalg.eig(value.monodromy)
    order = np.argsort(-np.abs(mu))
    return u[:-1], mu[order], vectors[:, order]


def section_points(c_c: float, state: np.ndarray, periods: int) -> np.ndarray:
    """(periods + 1, 4) stroboscopic points of a plain trajectory from ``state``."""
    problem = Problem(PAIR, {**FIG14C, "c_c": c_c}, ITERATION)
    trajectory = record_trajectory(problem, state, 0.0, periods, 1)
    assert trajectory.status == 0
    return trajectory.section_y


def rate_and_rotation(points: np.ndarray, centre: np.ndarray, skip: int = 50
                      ) -> tuple[float, float]:
    """Brute force on section points near a fixed point: (growth rate of the distance per
    period, a least-squares slope of its log; rotation number in turns per period, the
    argument / 2 pi of the eigenvalues of the 2 x 2 linear map that best carries each
    deviation to the next, in the plane of the deviations' two principal directions)."""
    dev = points[skip:] - centre
    r = np.linalg.norm(dev, axis=1)
    n = np.flatnonzero((r > 1e-8) & (r < 1e-2))  # above the integration noise, linear
    slope = np.polyfit(n, np.log(r[n]), 1)[0]
    plane = np.linalg.svd(dev[n] / r[n, None], full_matrices=False)[2][:2]
    xy = (dev @ plane.T) / r[:, None]  # scaled by the current distance: each pair weighs 1
    pairs = n[np.isin(n + 1, n)]
    A = np.linalg.lstsq(xy[pairs], xy[pairs + 1] * (r[pairs + 1] / r[pairs])[:, None],
                        rcond=None)[0].T
    rotation = abs(np.angle(np.linalg.eigvals(A)[0])) / (2 * np.pi)
    return float(slope), float(rotation)


def test_the_neimark_sacker_point_has_a_complex_pair_on_the_unit_circle(ns):
    mu = ns.multipliers
    assert ns.parameter == pytest.approx(4.0662267, abs=1e-6)
    assert abs(mu[0]) == pytest.approx(1.0, abs=1e-6) and mu[0].imag != 0
    assert mu[1] == pytest.approx(np.conj(mu[0]))
    assert np.all(np.abs(mu[2:]) < 0.7) and ns.impacting


def test_perturbations_decay_and_grow_at_the_floquet_rate_and_turn_by_arg_mu(ns):
    """c_NS -+ 0.04: the fitted rates equal ln|mu| to 2%, the rotation arg(mu) / 2 pi to
    2e-3; the rates bracket c_NS to 1e-3 (a linear fit through the two); on the stable
    side the plain trajectory ends on Newton's fixed point."""
    c_ns = ns.parameter
    measured = {}
    for side, offset, start in (("stable", 0.04, 1e-4), ("unstable", -0.04, 1e-6)):
        c_c = c_ns + offset
        y, mu, vectors = fixed_point(c_c, ns.state)
        kick = vectors[:, 0].real / np.linalg.norm(vectors[:, 0].real)
        points = section_points(c_c, y + start * kick, 5000)
        rate, rotation = rate_and_rotation(points, y)
        assert rate == pytest.approx(np.log(abs(mu[0])), rel=0.02), side
        assert rotation == pytest.approx(np.angle(mu[0]) / (2 * np.pi), abs=2e-3), side
        measured[c_c] = rate
        if side == "stable":
            assert np.max(np.abs(points[-1] - y)) < 1e-6
    (c_hi, r_hi), (c_lo, r_lo) = measured.items()
    crossing = c_lo + (c_hi - c_lo) * r_lo / (r_lo - r_hi)
    assert crossing == pytest.approx(c_ns, abs=1e-3)


def test_it_is_subcritical_past_it_the_pair_lands_on_a_large_torus_with_hysteresis(ns):
    """No sqrt law: 0.01 and 0.03 below c_NS the attractor reached from the orbit has the
    same size (5%), not sqrt(3) times; its largest Lyapunov exponent is 0 (a torus); 0.02
    above c_NS it persists beside the stable fixed point; 0.1 above, the pair returns to
    the fixed point."""
    c_ns = ns.parameter
    sizes = {}
    for below in (0.01, 0.03):
        y, _, vectors = fixed_point(c_ns - below, ns.state)
        points = section_points(c_ns - below, y + 1e-2 * vectors[:, 0].real, 12000)
        sizes[below] = np.max(np.linalg.norm(points[-1000:] - y, axis=1))
        if below == 0.01:
            torus = points[-1]
            spectrum = lyapunov_spectrum(Problem(PAIR, {**FIG14C, "c_c": c_ns - below},
                                                 ITERATION), torus, periods=500,
                                         transient=20, segments=10)
    assert sizes[0.01] > 1.0
    assert sizes[0.03] / sizes[0.01] == pytest.approx(1.0, abs=0.05)
    assert abs(spectrum.exponents[0]) < 2e-3 and spectrum.exponents[1] < -0.02
    for above, stays in ((0.02, True), (0.1, False)):
        y, mu, _ = fixed_point(c_ns + above, ns.state)
        assert np.all(np.abs(mu) < 1)
        points = section_points(c_ns + above, torus, 4000)
        distance = np.linalg.norm(points[-500:] - y, axis=1)
        assert (distance.min() > 0.5) if stays else (distance.max() < 1e-6), above


def curve_size_and_rotation(points: np.ndarray, centre: np.ndarray) -> tuple[float, float]:
    """(largest distance of the section points from the fixed point ``centre``; rotation
    number in turns per period: the mean turn per period of the points about their mean,
    in the plane of their two principal directions)."""
    dev = points - centre
    xy = dev @ np.linalg.svd(dev, full_matrices=False)[2][:2].T
    xy -= xy.mean(axis=0)
    turns = np.unwrap(np.arctan2(xy[:, 1], xy[:, 0]))
    rotation = abs(turns[-1] - turns[0]) / (2 * np.pi * (len(turns) - 1))
    return float(np.max(np.linalg.norm(dev, axis=1))), float(rotation)


@pytest.mark.slow
def test_a_supercritical_neimark_sacker_point_in_d_grows_a_sqrt_invariant_curve():
    """The same orbit at c_c = 4.3 followed down in d from 10.5: it loses stability at a
    subcritical NS point (d = 10.2994) and regains it at d_NS = 9.040184 in a narrow window
    down to its grazing at 9.0318. That NS point is supercritical: 0.004 below it the pair
    converges to the fixed point; 0.0005-0.004 above it the section points settle on a
    closed invariant curve whose size grows like sqrt(d - d_NS) (log-log slope 0.5 +- 0.06,
    size^2 linear in d with its zero 2e-4 from d_NS), turning at arg(mu) / 2 pi of the
    critical pair (1e-3), with two Lyapunov exponents ~0 (a torus) and the others < 0."""
    (branch,), _ = continue_starts(OrbitMap(PAIR, {**FIG14C, "d": 10.5}, "d", 1),
                                   [("impacting P1", ORBIT_AT_4_3, 1)], 10.5,
                                   Settings((9.0, 10.5), step=0.05, max_step=0.3),
                                   switch_depth=0)
    kinds = [(e.kind, round(e.point.parameter, 4)) for e in branch.events]
    assert ("Neimark-Sacker", 10.2994) in kinds and ("grazing", 9.0318) in kinds
    ns = next(e.point for e in branch.events
              if e.kind == "Neimark-Sacker" and e.point.parameter < 9.5)
    d_ns, mu = ns.parameter, ns.multipliers
    assert d_ns == pytest.approx(9.040184, abs=1e-5) and abs(mu[0]) == pytest.approx(1, abs=1e-6)
    assert np.all(np.abs(mu[2:]) < 0.8) and ns.impacting
    d_map = OrbitMap(PAIR, {**FIG14C, "d": 10.5}, "d", 1)

    def fixed(d):
        u, value, _ = correct(d_map, np.append(ns.state, d), None, 1e-10)
        m, vectors = np.linalg.eig(value.monodromy)
        k = np.argmax(np.abs(m))
        return u[:-1], m[k], vectors[:, k].real

    def iterate(d, state, periods):
        problem = Problem(PAIR, {**FIG14C, "d": d}, ITERATION)
        return record_trajectory(problem, state, 0.0, periods, 1).section_y

    y, m, _ = fixed(d_ns - 0.004)
    assert abs(m) < 1
    assert np.max(np.abs(iterate(d_ns - 0.004, y + 1e-3 * np.eye(4)[0], 5000)[-1] - y)) < 1e-6
    offsets = np.array([0.0005, 0.001, 0.002, 0.004])
    sizes = []
    for offset in offsets:
        y, m, v = fixed(d_ns + offset)
        points = iterate(d_ns + offset, y + 1e-3 * v / np.linalg.norm(v), 8000)
        size, rotation = curve_size_and_rotation(points[-3000:], y)
        earlier, _ = curve_size_and_rotation(points[-6000:-3000], y)
        assert size == pytest.approx(earlier, rel=0.01)  # settled: a closed curve
        assert rotation == pytest.approx(np.angle(mu[0]) / (2 * np.pi), abs=1e-3)
        sizes.append(size)
        if offset == 0.002:
            spectrum = lyapunov_spectrum(Problem(PAIR, {**FIG14C, "d": d_ns + offset},
                                                 ITERATION), points[-1], periods=500,
                                         transient=20, segments=10)
    slope = np.polyfit(np.log(offsets), np.log(sizes), 1)[0]
    assert slope == pytest.approx(0.5, abs=0.06)
    a, b = np.polyfit(offsets, np.square(sizes), 1)
    assert abs(-b / a) < 5e-4  # size^2 = a (d - d_NS - delta0): delta0 ~ 0
    assert np.all(np.abs(spectrum.exponents[:2]) < 3e-3) and spectrum.exponents[2] < -0.02
