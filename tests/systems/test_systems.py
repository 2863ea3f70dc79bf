"""The numba systems against the spec: right-hand sides, Jacobians, surfaces, symmetry."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softimpact_cli.kernels.switching import mode_of
from softimpact_cli.systems import get_system
from tests import naive
from tests.kernels.helpers import BILINEAR_BODY, BILINEAR_PAIR, DUFFING_BODY, DUFFING_PAIR

RNG_SEED = 20240611


def pair_values(model, law, rng):
    """Random but physical pair parameters (d spans both signs, phi any angle)."""
    base = dict(DUFFING_PAIR if model == "duffing" else BILINEAR_PAIR)
    base.update(
        c=rng.uniform(0.0, 0.5), k1=rng.uniform(0.1, 3.0), F=rng.uniform(0.0, 2.0),
        w=rng.uniform(0.3, 2.0), d=rng.uniform(-2.0, 3.0), phi=rng.uniform(0.0, 2 * np.pi),
        k_c=rng.uniform(0.0, 20.0), c_c=rng.uniform(0.0, 20.0), law=law,
    )
    base["k2"] = rng.uniform(-0.05, 0.1) if model == "duffing" else rng.uniform(0.0, 40.0)
    if model == "bilinear":
        base["d1"] = rng.uniform(0.0, 2.0)
    return base


NAIVE_PAIR = {"duffing": naive.duffing_pair_rhs, "bilinear": naive.bilinear_pair_rhs}
NAIVE_BODY = {"duffing": naive.duffing_body_rhs, "bilinear": naive.bilinear_body_rhs}


def numba_rhs(system, t, y, p, mode):
    out = np.full(system.dim, np.nan)
    system.rhs(t, np.array(y, float), p, mode, out)
    return out


def consistent_mode(system, p, y):
    sf = system.surfaces(p)
    return int(mode_of(np.array(y, float), sf.A, sf.b))


@pytest.mark.parametrize("law", ["paper", "no-tension"])
@pytest.mark.parametrize("model", ["duffing", "bilinear"])
def test_pair_rhs_matches_naive_on_random_states(model, law):
    rng = np.random.default_rng(RNG_SEED)
    system = get_system(model, 2)
    seen_contact = seen_pulling = 0
    for _ in range(400):
        par = pair_values(model, law, rng)
        p = system.pack(par)
        y = rng.uniform(-4.0, 4.0, 4)
        t = rng.uniform(-50.0, 50.0)
        mode = consistent_mode(system, p, y)
        got = numba_rhs(system, t, y, p, mode)
        want = NAIVE_PAIR[model](t, y, par)
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12,
                                   err_msg=f"{model} {law} y={y} t={t} mode={mode} par={par}")
        delta = y[0] - y[2] - par["d"]
        if delta >= 0:
            seen_contact += 1
            if par["k_c"] * delta + par["c_c"] * (y[1] - y[3]) < 0:
                seen_pulling += 1
    # the sample really exercised both sides and the tension case
    assert seen_contact > 50 and seen_pulling > 10


@pytest.mark.parametrize("law", ["paper", "no-tension"])
@pytest.mark.parametrize("model", ["duffing", "bilinear"])
def test_pair_rhs_in_frozen_modes(model, law):
    """A mode is a frozen decision: every mode's field equals the naive field with the
    same decisions forced, whatever side the state is on."""
    rng = np.random.default_rng(RNG_SEED + 1)
    system = get_system(model, 2)
    for _ in range(100):
        par = pair_values(model, law, rng)
        p = system.pack(par)
        n = system.surfaces(p).A.shape[0]
        y = rng.uniform(-4.0, 4.0, 4)
        t = rng.uniform(0.0, 20.0)
        for mode in range(2**n):
            flags = dict(contact=bool(mode & 1))
            if model == "bilinear":
                flags.update(left=bool(mode & 2), right=bool(mode & 4))
            if law == "no-tension":
                flags["pushing"] = bool(mode & (1 << (n - 1)))
            got = numba_rhs(system, t, y, p, mode)
            want = NAIVE_PAIR[model](t, y, par, **flags)
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12,
                                       err_msg=f"{model} {law} mode={mode} flags={flags}")


@pytest.mark.parametrize("model", ["duffing", "bilinear"])
def test_body_rhs_matches_naive(model):
    rng = np.random.default_rng(RNG_SEED + 2)
    system = get_system(model, 1)
    base = DUFFING_BODY if model == "duffing" else BILINEAR_BODY
    for _ in range(300):
        par = dict(base, c=rng.uniform(0, 0.5), F=rng.uniform(0, 2), w=rng.uniform(0.3, 2))
        if model == "bilinear":
            par["d1"] = rng.uniform(0.0, 2.0)
        p = system.pack(par)
        y = rng.uniform(-4.0, 4.0, 2)
        t = rng.uniform(-50.0, 50.0)
        got = numba_rhs(system, t, y, p, consistent_mode(system, p, y))
        np.testing.assert_allclose(got, NAIVE_BODY[model](t, y, par), rtol=1e-12, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    y=st.lists(st.floats(-5.0, 5.0), min_size=4, max_size=4),
    d=st.floats(-3.0, 3.0), d1=st.floats(0.0, 3.0), law=st.sampled_from(["paper", "no-tension"]),
)
def test_surfaces_are_the_documented_functions(y, d, d1, law):
    x1, v1, x2, v2 = y
    y = np.array(y)
    dpar = dict(DUFFING_PAIR, d=d, law=law)
    bpar = dict(BILINEAR_PAIR, d=d, d1=d1, law=law)
    expected = {
        "duffing": [x1 - x2 - d],
        "bilinear": [x1 - x2 - d, -x1 - d1, x2 - d1],
    }
    for model, par in (("duffing", dpar), ("bilinear", bpar)):
        system = get_system(model, 2)
        sf = system.surfaces(system.pack(par))
        g = sf.A @ y + sf.b
        want = list(expected[model])
        if law == "no-tension":
            want.append(par["k_c"] * (x1 - x2 - d) + par["c_c"] * (v1 - v2))
        assert sf.A.shape == (len(want), 4)
        np.testing.assert_allclose(g, want, rtol=1e-12, atol=1e-12)
        assert sf.contact == 0 and sf.names[0] == "contact"
        n = len(want)
        # the stop-force surface is watched only in contact; every other one always
        for mode in range(2**n):
            watched = int(sf.relevance[mode])
            for i in range(n):
                expect = not (law == "no-tension" and i == n - 1) or bool(mode & 1)
                assert bool((watched >> i) & 1) == expect
    body = get_system("bilinear", 1)
    sf = body.surfaces(body.pack(dict(BILINEAR_BODY, d1=d1)))
    np.testing.assert_allclose(sf.A @ y[:2] + sf.b, [-x1 - d1], atol=1e-12)
    assert sf.contact == -1
    duff = get_system("duffing", 1)
    assert duff.surfaces(duff.pack(DUFFING_BODY)).A.shape == (0, 2)


def finite_difference_jacobian(system, t, y, p, mode, eps=1e-6):
    n = system.dim
    J = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = eps
        J[:, j] = (numba_rhs(system, t, y + e, p, mode) - numba_rhs(system, t, y - e, p, mode)) / (
            2 * eps)
    dfdt = (numba_rhs(system, t + eps, y, p, mode) - numba_rhs(system, t - eps, y, p, mode)) / (
        2 * eps)
    return J, dfdt


@pytest.mark.parametrize("bodies", [1, 2])
@pytest.mark.parametrize("law", ["paper", "no-tension"])
@pytest.mark.parametrize("model", ["duffing", "bilinear"])
def test_jacobian_matches_finite_differences(model, bodies, law):
    rng = np.random.default_rng(RNG_SEED + 3)
    system = get_system(model, bodies)
    worst = 0.0
    for _ in range(40):
        if bodies == 2:
            par = pair_values(model, law, rng)
        else:
            par = dict(DUFFING_BODY if model == "duffing" else BILINEAR_BODY)
            par["k2"] = 0.05 if model == "duffing" else 29.0
        p = system.pack(par)
        n_surf = system.surfaces(p).A.shape[0]
        y = rng.uniform(-3.0, 3.0, system.dim)
        t = rng.uniform(0.0, 20.0)
        for mode in range(2**n_surf):
            J = np.full((system.dim, system.dim), np.nan)
            dfdt = np.full(system.dim, np.nan)
            system.jacobian(t, y, p, mode, J, dfdt)
            J_fd, dfdt_fd = finite_difference_jacobian(system, t, y, p, mode)
            scale = 1.0 + np.max(np.abs(J_fd))
            np.testing.assert_allclose(J, J_fd, atol=1e-7 * scale, rtol=0,
                                       err_msg=f"{model} bodies={bodies} mode={mode}")
            np.testing.assert_allclose(dfdt, dfdt_fd, atol=1e-7 * (1 + par["F"]), rtol=0)
            worst = max(worst, np.max(np.abs(J - J_fd)) / scale)
    assert worst < 1e-7


def mirrored(y):
    """(x1, v1, x2, v2) -> (-x2, -v2, -x1, -v1): swap the bodies and mirror them."""
    x1, v1, x2, v2 = y
    return np.array([-x2, -v2, -x1, -v1])


def test_bilinear_body_mirror_symmetry():
    """If x(t) solves the left body, -x(t) solves the right body with phi = pi.

    At the rhs level, with the bodies out of contact (large d): the right body's
    acceleration at (-x, -v) equals minus the left body's at (x, v), for every t."""
    rng = np.random.default_rng(RNG_SEED + 4)
    system = get_system("bilinear", 2)
    par = dict(BILINEAR_PAIR, d=100.0, phi=np.pi)
    p = system.pack(par)
    for _ in range(300):
        x, v = rng.uniform(-3.0, 3.0, 2)
        t = rng.uniform(0.0, 30.0)
        y = np.array([x, v, -x, -v])
        f = numba_rhs(system, t, y, p, consistent_mode(system, p, y))
        np.testing.assert_allclose(f[2:], -f[:2], rtol=1e-12, atol=1e-12)
        # and the left body of the pair is the one-body system
        body = get_system("bilinear", 1)
        pb = body.pack(BILINEAR_BODY)
        fb = numba_rhs(body, t, y[:2], pb, consistent_mode(body, pb, y[:2]))
        np.testing.assert_allclose(f[:2], fb, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("law", ["paper", "no-tension"])
@pytest.mark.parametrize("model", ["bilinear", "duffing"])
def test_pair_mirror_symmetry_with_contact(model, law):
    """Swapping and mirroring the bodies maps the pair at phi to the pair at -phi with the
    clock shifted by (phi + pi)/w (the contact function x1 - x2 - d is invariant):
    f(t + (phi + pi)/w, S y; -phi) = S f(t, y; phi) with S the swap-mirror."""
    rng = np.random.default_rng(RNG_SEED + 5)
    system = get_system(model, 2)
    n_contact = 0
    for _ in range(300):
        par = pair_values(model, law, rng)
        y = rng.uniform(-3.0, 3.0, 4)
        t = rng.uniform(0.0, 30.0)
        p = system.pack(par)
        mpar = dict(par, phi=-par["phi"])
        mp = system.pack(mpar)
        f = numba_rhs(system, t, y, p, consistent_mode(system, p, y))
        ts = t + (par["phi"] + np.pi) / par["w"]
        ym = mirrored(y)
        fm = numba_rhs(system, ts, ym, mp, consistent_mode(system, mp, ym))
        np.testing.assert_allclose(fm, mirrored(f), rtol=1e-10, atol=1e-10)
        n_contact += y[0] - y[2] >= par["d"]
    assert n_contact > 30
