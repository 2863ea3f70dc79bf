"""Saltation matrices against their closed forms, the driver's stop at a switch, and the
Gram-Schmidt step of Benettin's method."""

import numpy as np
import pytest

from softimpact_cli.kernels import layout
from softimpact_cli.kernels.codes import OK, TOO_MANY_SWITCHES
from softimpact_cli.kernels.lyapunov import orthonormalise
from softimpact_cli.kernels.saltation import apply_to_tangents, saltation
from softimpact_cli.systems import get_system

from .helpers import BILINEAR_PAIR, DUFFING_PAIR, problem, run_advance

A_CONTACT = np.array([1.0, 0.0, -1.0, 0.0])
E = np.array([0.0, -1.0, 0.0, 1.0])  # where the stop force enters


def _salt(system, values, y, t, before, after, a):
    p = system.pack(values)
    S = np.empty((4, 4))
    rate = saltation(system.rhs, p, t, np.array(y, dtype=float), 4, before, after,
                     np.array(a, dtype=float), S)
    return S, rate


@pytest.mark.parametrize("rate", [2.0, 0.3, -1.5])
def test_paper_law_contact_closed_form(rate):
    """Onset (mode 0 -> contact) and release (contact -> 0) of the paper's law on the
    surface x1 - x2 = d: S = I +- c_c e a^T, whatever the crossing speed delta'."""
    values = dict(DUFFING_PAIR, c_c=7.0)
    d = values["d"]
    y = [0.4 + d, 0.2 + rate, 0.4, 0.2]  # delta = 0, delta' = rate
    onset, r = _salt(get_system("duffing", 2), values, y, 0.7, 0, 1, A_CONTACT)
    assert r == pytest.approx(rate)
    np.testing.assert_allclose(onset, np.eye(4) + 7.0 * np.outer(E, A_CONTACT), atol=1e-12)
    release, _ = _salt(get_system("duffing", 2), values, y, 0.7, 1, 0, A_CONTACT)
    np.testing.assert_allclose(release, np.eye(4) - 7.0 * np.outer(E, A_CONTACT), atol=1e-12)
    assert np.linalg.det(onset) == pytest.approx(1.0)


def test_continuous_fields_give_identity():
    """Where the field is continuous the formula gives I: Hunt-Crossley's onset, the
    no-tension law's force surface, the bilinear springs' gaps."""
    duffing = get_system("duffing", 2)
    d = DUFFING_PAIR["d"]
    y = [d + 0.4, 1.1, 0.4, 0.2]
    S, _ = _salt(duffing, dict(DUFFING_PAIR, law="hunt-crossley"), y, 0.3, 0, 1, A_CONTACT)
    np.testing.assert_allclose(S, np.eye(4), atol=1e-14)
    # no-tension, in contact, on the force surface k_c delta + c_c delta' = 0
    values = dict(DUFFING_PAIR, law="no-tension")
    kc, cc = values["k_c"], values["c_c"]
    delta = 0.05
    y = [d + 0.4 + delta, 0.2 - kc * delta / cc, 0.4, 0.2]
    force_row = [kc, cc, -kc, -cc]
    S, _ = _salt(duffing, values, y, 0.3, 1 | 2, 1, force_row)
    np.testing.assert_allclose(S, np.eye(4), atol=1e-12)
    # bilinear: the left body's spring engages at x1 = -d1 (surface bit 1)
    bil = get_system("bilinear", 2)
    y = [-BILINEAR_PAIR["d1"], -0.7, 2.0, 0.1]
    S, _ = _salt(bil, BILINEAR_PAIR, y, 0.3, 0, 2, [-1.0, 0.0, 0.0, 0.0])
    np.testing.assert_allclose(S, np.eye(4), atol=1e-14)


def test_apply_to_tangents_is_matrix_product():
    rng = np.random.default_rng(0)
    S = rng.normal(size=(4, 4))
    Phi = rng.normal(size=(4, 4))
    z = np.concatenate([rng.normal(size=4), Phi.ravel()])
    apply_to_tangents(S, z, 4)
    np.testing.assert_allclose(z[4:].reshape(4, 4), S @ Phi, rtol=1e-14)


def test_orthonormalise_matches_qr():
    """ln R_jj equal numpy's QR's ln|R_jj|, the columns orthonormal, also for columns
    ten orders of magnitude apart."""
    rng = np.random.default_rng(1)
    Phi = rng.normal(size=(4, 4)) @ np.diag([1e3, 1.0, 1e-4, 1e-7])
    z = np.concatenate([np.zeros(4), Phi.ravel()])
    logs = np.empty(4)
    orthonormalise(z, 4, logs)
    _, r = np.linalg.qr(Phi)
    np.testing.assert_allclose(logs, np.log(np.abs(np.diag(r))), atol=1e-10)
    Q = z[4:].reshape(4, 4)
    np.testing.assert_allclose(Q.T @ Q, np.eye(4), atol=1e-14)


def test_advance_stops_on_the_switch():
    """With a switch budget of 0 the driver returns TOO_MANY_SWITCHES on the surface,
    the switch time in fstate[T_SWITCH]; advancing on from there ends where one
    uninterrupted call ends."""
    pr = problem("duffing", 2, DUFFING_PAIR, method="dopri5", rtol=1e-11, atol=1e-12)
    y0 = np.array([0.3, 1.0, -0.2, -1.0])  # delta = -0.5, closing at 2
    T = pr.period
    _, y_ref, istate_ref, _ = run_advance(pr, y0, 0.0, T)
    assert istate_ref[layout.N_SWITCHES] >= 2
    opts = pr.options()
    opts[layout.MAX_SWITCHES] = 0.0
    from softimpact_cli.kernels.orbit import new_state, no_samples

    y = y0.copy()
    sf = pr.kernel_args()
    state = new_state(y, sf[0], sf[1])
    t, stops = 0.0, 0
    while True:
        status = pr.advance(pr.system.rhs, pr.params, y, t, T, sf, opts, state,
                            no_samples(4))
        if status == OK:
            break
        assert status == TOO_MANY_SWITCHES
        t = state[1][layout.T_SWITCH]
        stops += 1
        assert 0.0 < t < T
        assert abs(y[0] - y[2] - DUFFING_PAIR["d"]) < 1e-10  # on the contact surface
    assert stops == istate_ref[layout.N_SWITCHES]
    np.testing.assert_allclose(y, y_ref, atol=1e-8)
