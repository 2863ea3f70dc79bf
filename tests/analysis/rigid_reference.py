"""Independent references for the rigid impact oscillator (no softimpact code).

    x'' + 2 zeta x' + x = cos(w t),   a wall at x = sigma: x reaching sigma with v > 0
    leaves with v+ = -r v-.

``scipy_sections`` integrates it with scipy's DOP853 and a terminal event per impact;
``period_one`` is Shaw and Holmes's (1983) closed-form period-1 single-impact orbit.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp


def amplitude(zeta: float, w: float) -> float:
    """Amplitude A of the non-impacting periodic response (grazing at sigma = A)."""
    return 1.0 / np.sqrt((1.0 - w * w) ** 2 + (2.0 * zeta * w) ** 2)


def scipy_sections(zeta, w, sigma, r, state, periods, rtol=1e-12, atol=1e-13):
    """The state at t = n T, n = 0..periods, from ``state`` at t = 0 (impacts as events);
    and the impact count."""
    T = 2.0 * np.pi / w

    def rhs(t, y):
        return [y[1], np.cos(w * t) - 2.0 * zeta * y[1] - y[0]]

    def hit(t, y):
        return y[0] - sigma
    hit.terminal, hit.direction = True, 1.0

    y, t, impacts = np.array(state, float), 0.0, 0
    out = [y.copy()]
    for n in range(1, periods + 1):
        while True:
            sol = solve_ivp(rhs, (t, n * T), y, method="DOP853", rtol=rtol, atol=atol,
                            events=hit)
            if sol.status == 1:  # an impact: reset, and restart past it
                t, y = sol.t_events[0][0], sol.y_events[0][0].copy()
                y[0], y[1] = sigma, -r * y[1]
                impacts += 1
                continue
            t, y = n * T, sol.y[:, -1]
            break
        out.append(y.copy())
    return np.array(out), impacts


def period_one(zeta: float, w: float, sigma: float, r: float):
    """Shaw and Holmes's period-1 single-impact orbits: [(impact time in [0, T), impact
    velocity v- > 0, state at t = 0)], both solutions of the quadratic, physical or not.

    After the impact at t0 (x = sigma, v = -r v-) the motion is
    x = A cos(w t - psi) + e^{-zeta s} (C1 cos(wd s) + C2 sin(wd s)), s = t - t0; returning
    to (sigma, v-) after one period T is linear in (c, s, v-, C1, C2), c = A cos(w t0 - psi),
    s = A sin(w t0 - psi); with c^2 + s^2 = A^2 a quadratic."""
    A, T = amplitude(zeta, w), 2.0 * np.pi / w
    psi = np.arctan2(2.0 * zeta * w, 1.0 - w * w)
    wd = np.sqrt(1.0 - zeta * zeta)
    E, cd, sd = np.exp(-zeta * T), np.cos(wd * T), np.sin(wd * T)
    # unknowns u = (c, s, v, C1, C2); rows M u = rhs
    M = np.array([
        [1.0, 0.0, 0.0, 1.0, 0.0],                       # x(t0+) = sigma
        [0.0, -w, r, -zeta, wd],                          # v(t0+) = -r v
        [1.0, 0.0, 0.0, E * cd, E * sd],                  # x(t0 + T) = sigma
        [0.0, -w, -1.0, E * (-zeta * cd - wd * sd), E * (wd * cd - zeta * sd)],  # v = v-
    ])
    rhs = np.array([sigma, 0.0, sigma, 0.0])
    # u = u0 + s * u1 (s free): solve with s moved to the right-hand side
    keep = [0, 2, 3, 4]
    u0 = np.linalg.solve(M[:, keep], rhs)
    u1 = np.linalg.solve(M[:, keep], -M[:, 1])
    # c(s)^2 + s^2 = A^2
    a2, a1, a0 = u1[0] ** 2 + 1.0, 2.0 * u0[0] * u1[0], u0[0] ** 2 - A * A
    disc = a1 * a1 - 4.0 * a2 * a0
    out = []
    if disc < 0.0:
        return out
    for s in ((-a1 + np.sqrt(disc)) / (2.0 * a2), (-a1 - np.sqrt(disc)) / (2.0 * a2)):
        c, v, C1, C2 = u0 + s * u1
        t0 = ((np.arctan2(s, c) + psi) / w) % T
        # the state at t = T (= 0 mod T), s = T - t0 after the impact
        sl = T - t0
        ex = np.exp(-zeta * sl)
        x = A * np.cos(w * T - psi) + ex * (C1 * np.cos(wd * sl) + C2 * np.sin(wd * sl))
        vx = (-A * w * np.sin(w * T - psi)
              + ex * ((-zeta * C1 + wd * C2) * np.cos(wd * sl)
                      + (-zeta * C2 - wd * C1) * np.sin(wd * sl)))
        out.append((t0, v, np.array([x, vx])))
    return out


def scipy_largest_exponent(zeta, w, sigma, r, state, periods, transient, segments,
                           separation=1e-8, rtol=1e-11, atol=1e-13):
    """Benettin's original estimate of the largest Lyapunov exponent (Benettin, Galgani and
    Strelcyn 1976): a fiducial trajectory and a neighbour ``separation`` away, both
    integrated by :func:`scipy_sections` with the impacts as events, the neighbour pulled
    back to that distance along their difference every forcing period; the logarithms of
    the growths, after ``transient`` periods, summed per segment and divided by its
    duration. Returns (mean, standard error over the ``segments``), 1/time."""
    T = 2.0 * np.pi / w
    y = np.array(state, float)
    for _ in range(transient):
        y = scipy_sections(zeta, w, sigma, r, y, 1, rtol, atol)[0][-1]
    neighbour = y + separation * np.array([1.0, 1.0]) / np.sqrt(2.0)
    logs = []
    for _ in range(periods):
        y_next = scipy_sections(zeta, w, sigma, r, y, 1, rtol, atol)[0][-1]
        n_next = scipy_sections(zeta, w, sigma, r, neighbour, 1, rtol, atol)[0][-1]
        gap = np.linalg.norm(n_next - y_next)
        logs.append(np.log(gap / separation))
        y, neighbour = y_next, y_next + (n_next - y_next) * (separation / gap)
    per_segment = np.array(logs).reshape(segments, -1).sum(axis=1) / (periods // segments * T)
    return per_segment.mean(), per_segment.std(ddof=1) / np.sqrt(segments)
