"""Switch location: first exits and maxima of a step's polynomial, and grazing touches.

``switching.first_exit(coef, engaged)`` must return the first u in [0, 1] where the
polynomial g(u) = sum coef[k] u^k leaves the side ``engaged`` (g >= 0) / not engaged
(g < 0), including an excursion that crosses and comes back inside the step;
``switching.poly_max(coef, u_end)`` the largest value of g on [0, u_end].
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.polynomial import polynomial as P
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from softimpact_cli.kernels import layout
from softimpact_cli.kernels.codes import OK
from softimpact_cli.kernels.switching import first_exit, poly_max
from tests import naive

from .helpers import DUFFING_PAIR, dopri5_fixed, problem, rk4_fixed


def coefficients(poly):
    c = np.zeros(5)
    c[: len(poly)] = poly
    return c


def from_roots(roots, scale=1.0):
    return coefficients(scale * P.polyfromroots(roots))


def root_tol(coef, root):
    """1e-12, or what the root's conditioning allows when g is evaluated in floating point
    (rounding ~ eps * sum |c_k| moves a root with slope g' by that over |g'|)."""
    slope = abs(P.polyval(root, P.polyder(np.asarray(coef, float))))
    return max(1e-12, 8 * np.finfo(float).eps * np.sum(np.abs(coef)) / slope)


def true_max(poly, u_end=1.0):
    """Reference maximum: end points and the real critical points in (0, u_end)."""
    crit = [r.real for r in P.polyroots(P.polyder(poly)) if abs(r.imag) < 1e-12
            and 0.0 < r.real < u_end] if len(np.trim_zeros(poly, "b")) > 1 else []
    return max(P.polyval(u, poly) for u in [0.0, u_end, *crit])


# ---------------------------------------------------------------------------------------
# first_exit


@pytest.mark.parametrize("root", [1e-9, 0.1, 0.3, 0.5, 0.77, 0.999999])
def test_first_exit_of_a_line(root):
    # not engaged (g < 0) and rising through the surface
    assert abs(first_exit(from_roots([root]), False) - root) < 1e-12
    # engaged (g > 0) and falling through it
    assert abs(first_exit(from_roots([root], -1.0), True) - root) < 1e-12


def test_no_exit_when_the_side_is_kept():
    assert first_exit(from_roots([1.5]), False) == -1.0  # stays below 0 on [0, 1]
    assert first_exit(from_roots([-0.5]), True) == -1.0  # stays above 0
    assert first_exit(coefficients([2.0, -1.0, 0.5, 0.1, -0.2]), True) == -1.0
    # a dip that stays on its side
    assert first_exit(coefficients([1e-6 + 0.16, -0.8, 1.0]), True) == -1.0  # min 1e-6 at 0.4


@pytest.mark.parametrize("roots, engaged, expected", [
    ([0.45, 0.8], True, 0.45),  # (u - .45)(u - .8): positive, then negative
    ([0.2, 0.6, 0.9], False, 0.2),  # cubic
    ([0.1, 0.15, 0.6, 0.9], True, 0.1),  # two crossings inside the first quarter
    ([0.3, 0.31, 0.7, 2.0], True, 0.3),  # a narrow excursion 0.3 .. 0.31
    ([0.55, 0.5500001, 3.0, -1.0], True, 0.55),  # a 1e-7 wide excursion
])
def test_first_exit_returns_the_first_root(roots, engaged, expected):
    poly = P.polyfromroots(roots)
    if (P.polyval(0.0, poly) >= 0) != engaged:
        poly = -poly
    u = first_exit(coefficients(poly), engaged)
    assert abs(u - expected) < root_tol(poly, expected), (u, expected)


@pytest.mark.parametrize("peak_at, height", [(0.37, 1e-6), (0.37, 1e-10), (0.62, 1e-8),
                                             (0.125, 1e-8), (0.9, 1e-12)])
def test_first_exit_catches_a_grazing_excursion(peak_at, height):
    """g = height - k (u - peak)^2: negative at both ends, above 0 only near the peak.
    The exit is at peak - sqrt(height / k), to 1e-12 (or to what its conditioning allows:
    g' there is only 2 sqrt(k height))."""
    k = 3.0
    poly = [height - k * peak_at**2, 2 * k * peak_at, -k]
    assert P.polyval(0.0, poly) < 0 and P.polyval(1.0, poly) < 0
    u = first_exit(coefficients(poly), False)
    expected = peak_at - np.sqrt(height / k)
    tol = root_tol(poly, expected)
    assert tol < 1e-8
    assert abs(u - expected) < tol, (u, expected)
    # mirrored: an engaged g dipping below 0
    u = first_exit(coefficients([-c for c in poly]), True)
    assert abs(u - expected) < tol


def test_first_exit_on_a_rounding_residual_restart():
    """A restart right at the switch may leave g a rounding error on the wrong side; it
    counts as zero (no immediate exit) when g then moves into its side."""
    assert first_exit(coefficients([-1e-17, 1.0, -0.2]), True) == -1.0
    assert first_exit(coefficients([1e-17, -1.0, 0.2]), False) == -1.0


def two_extrema_in_one_quarter():
    """h rises to a maximum at u = 0.05, falls below 0, has its minimum at u = 0.2 and
    rises for good (its third critical point is at u = 1.5, outside the step): an
    excursion below 0 inside (0, 0.25), with h > 0 and h' > 0 at both u = 0 and 0.25.
    Only 2 extrema in [0, 1], but in the same quarter of the step."""
    H = P.polyint(-P.polyfromroots([0.05, 0.2, 1.5]))
    H[0] = 2.5e-4
    H = 1000.0 * H
    roots = sorted(r.real for r in P.polyroots(H) if abs(r.imag) < 1e-12 and 0 < r.real < 1)
    assert len(roots) == 2 and 0.05 < roots[0] < 0.2 < roots[1] < 0.25
    assert P.polyval(0.0, H) > 0 and P.polyval(0.25, H) > 0 and P.polyval(1.0, H) > 0
    return H, roots[0]


def test_first_exit_with_two_extrema_in_one_subinterval():
    """KNOWN BUG (kernels/switching.py, first_exit): a sign change is searched for only at
    the 4 sub-interval ends and at a derivative sign change *between* them (da < 0 < db).
    An excursion between two extrema that share one quarter of the step is missed, so
    first_exit returns -1 (no exit) although g crosses the surface at u ~ 0.152. The
    module docstring's premise ("at most 3 extrema; 4 pieces isolate them") is false:
    equal pieces cannot isolate the extrema of every quartic."""
    H, root = two_extrema_in_one_quarter()
    u = first_exit(coefficients(H), True)
    assert abs(u - root) < 1e-12, f"first_exit returned {u}, the first crossing is at {root}"


# ---------------------------------------------------------------------------------------
# poly_max


@pytest.mark.parametrize("poly", [
    [0.3, -1.0],  # max at u = 0
    [-0.5, 0.2, 0.1],  # max at u = 1
    [0.0, 1.2, -1.5],  # interior max 0.24 at 0.4
    [1e-6 - 3 * 0.37**2, 6 * 0.37, -3.0],  # graze 1e-6 at 0.37
    list(P.polyfromroots([0.1, 0.3, 0.6, 0.95])),  # quartic, two interior minima
    list(-P.polyfromroots([0.1, 0.3, 0.6, 0.95])),
    [0.0, 0.5, -3.0, 4.0, -1.2],
])
@pytest.mark.parametrize("u_end", [1.0, 0.45])
def test_poly_max_finds_the_maximum(poly, u_end):
    got = poly_max(coefficients(poly), u_end)
    want = true_max(np.array(poly, float), u_end)
    assert abs(got - want) < 1e-14 * max(1.0, abs(want)), (got, want)


def test_poly_max_at_a_subinterval_boundary():
    """KNOWN BUG (kernels/switching.py, poly_max): g is evaluated only at u = 0 and u_end,
    and at critical points found by a strict sign change of g' (da > 0 and db < 0) over a
    quarter. A maximum exactly at a quarter point (g' = 0 there) is in neither quarter:
    g = u - u^2 has its maximum 0.25 at u = 0.5, poly_max returns 0.0. (first_exit does
    evaluate g at the quarter points, so it is not affected.)"""
    got = poly_max(coefficients([0.0, 1.0, -1.0]), 1.0)
    assert abs(got - 0.25) < 1e-14, f"poly_max returned {got}, the maximum is 0.25"


def test_poly_max_with_two_extrema_in_one_subinterval():
    """KNOWN BUG (kernels/switching.py, poly_max): same blind spot as first_exit. g = -H
    is negative at both ends with an interior maximum g(0.2) = 0.183 > 0, but g' < 0 at
    both ends of the first quarter, so poly_max returns g(0) = -0.25: a penetration (and
    the contact it proves) is reported as none."""
    H, _ = two_extrema_in_one_quarter()
    g = -H
    got = poly_max(coefficients(g), 1.0)
    want = true_max(g)
    assert want > 0.18
    assert abs(got - want) < 1e-12, f"poly_max returned {got}, the maximum is {want}"


# ---------------------------------------------------------------------------------------
# a grazing contact inside one step of the kernels


EPS = 1e-5  # depth of the graze


@pytest.fixture(scope="module")
def graze():
    """A free pair trajectory, the maximum (t*, m*) of x1 - x2 over [0, 1.5 T] (reached once,
    at t* ~ 0.77 T), and d = m* - EPS: the bodies touch for ~2 sqrt(2 EPS / |delta''|)
    around t* only."""
    par = dict(DUFFING_PAIR, d=100.0, phi=1.0)
    y0 = np.array([1.0, 0.0, 1.0, 0.0])
    T = 2 * np.pi / par["w"]
    sol = solve_ivp(lambda t, y: naive.duffing_pair_rhs(t, y, par), (0.0, 2 * T), y0,
                    method="DOP853", rtol=1e-13, atol=1e-13, dense_output=True)

    def delta(t):
        y = sol.sol(t)
        return y[0] - y[2]

    res = minimize_scalar(lambda t: -delta(t), bracket=(3.5, 3.7, 4.0), tol=1e-12)
    t_star, m_star = float(res.x), float(-res.fun)
    assert 3.5 < t_star < 4.0 and 1.2 < m_star < 1.4
    grid = np.linspace(0.0, 1.5 * T, 3001)
    assert np.max(delta(grid)) <= m_star  # the one maximum on the interval
    par = dict(par, d=m_star - EPS)
    # The stop pushes back as soon as it engages, so the true penetration is a little
    # less than EPS: the referee, restarted from the free state just before the touch.
    model = naive.duffing_pair_model(par)
    t0 = t_star - 0.2
    y_before = sol.sol(t0)
    ref = naive.solve_with_events(model.rhs, y_before, (t0, t_star + 0.2), model.switches,
                                  max_step=1e-4)
    assert len(ref.event_t) == 2 and ref.event_mode == [1, 0]  # in, then out
    t_on, t_off = ref.event_t
    times = np.linspace(t_on, t_off, 4001)
    ref = naive.solve_with_events(model.rhs, y_before, (t0, t_star + 0.2), model.switches,
                                  t_eval=times, max_step=1e-4)
    penetration = float(np.max(ref.y_eval[:, 0] - ref.y_eval[:, 2] - par["d"]))
    assert 0.5 * EPS < penetration < EPS
    return par, y0, t_star, delta, penetration


def pick_step(t_star, delta, d, span, n_min):
    """A fixed step h = span/n (n >= n_min) with t* mid-step and both ends clearly free."""
    for n in range(n_min, 4 * n_min):
        h = span / n
        k = int(t_star // h)
        frac = t_star / h - k
        if 0.35 < frac < 0.65 and max(delta(k * h), delta((k + 1) * h)) < d - 3 * EPS:
            return n, k * h, (k + 1) * h
    raise AssertionError("no suitable step")


@pytest.mark.parametrize("method", ["dopri5", "rk4"])
def test_grazing_touch_inside_a_step_is_detected(graze, method):
    par, y0, t_star, delta, penetration = graze
    pr = problem("duffing", 2, par)
    T = pr.period
    t_end = 1.5 * T  # past the graze (t* ~ 0.77 T), before the next approach
    if method == "dopri5":
        n, a, b = pick_step(t_star, delta, par["d"], t_end, 60)  # h ~ 0.12
        run = lambda locate: dopri5_fixed(pr, y0, 0.0, t_end, t_end / n, locate)  # noqa: E731
    else:
        # rk4's grid is T / steps_per_period; h ~ 0.024 (its global error must stay << EPS)
        n, a, b = pick_step(t_star, delta, par["d"], T, 200)
        run = lambda locate: rk4_fixed(pr, y0, 0.0, t_end, n, locate)  # noqa: E731
    assert delta(a) < par["d"] and delta(b) < par["d"]  # both ends of the step are free
    print(f"{method}: step {b - a:.4f}, ends {delta(a) - par['d']:.2e} {delta(b) - par['d']:.2e}")
    status, y, istate, fstate = run(True)
    assert status == OK
    assert istate[layout.N_CONTACTS] == 1, istate
    assert istate[layout.N_SWITCHES] == 2  # in and out
    # the located penetration is the referee's (dense output and global errors << EPS)
    got = fstate[layout.MAX_G]
    print(f"{method}: located penetration {got:.6e}, referee {penetration:.6e}")
    assert abs(got - penetration) < 0.01 * EPS, (got, penetration)
    # the plain scheme sees only the step ends: it misses the touch entirely
    status, _, istate, fstate = run(False)
    assert status == OK and istate[layout.N_CONTACTS] == 0
    assert fstate[layout.MAX_G] < 0.0
