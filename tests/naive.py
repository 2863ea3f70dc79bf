"""Slow, obviously-correct NumPy references for the models of SPEC.md section 2.

Nothing here imports the package: the equations are transcribed from the spec, with
plain if/else on the state (the Heaviside steps), so that the numba systems and kernels
can be checked against an independent implementation.

Every right-hand side takes the state and a plain dict of parameter values (the same
keys the package's ``System.pack`` takes). Optional keyword flags *freeze* a switch
(contact engaged, stop pushing, left/right spring engaged) instead of reading it from
the state: that is the vector field of one mode, which an event-driven integrator needs.

``solve_with_events`` is the referee: scipy's DOP853 with a terminal event on every
switching function, restarted at each event with the mode flipped for the surfaces that
fired (the mode after an event comes from the crossing, never from the sign of g at the
event point, which is ~0).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

# ---------------------------------------------------------------------------------------
# contact force


def contact_force(x1, v1, x2, v2, par, contact=None, pushing=None):
    """F_C of SPEC.md: 0 while x1 - x2 < d, else k_c delta + c_c delta' ("paper" law).

    With ``law = "no-tension"`` the force is clipped at 0 (max(F_C, 0)). With
    ``law = "hunt-crossley"`` it is k_c delta^n + c_c delta^n delta' (n = ``exponent``,
    default 1.5), and 0 while delta < 0 even in a frozen contact.
    ``contact``/``pushing`` freeze the two decisions instead of reading the state.
    """
    delta = x1 - x2 - par["d"]
    if contact is None:
        contact = delta >= 0.0
    if not contact:
        return 0.0
    if par.get("law", "paper") == "hunt-crossley":
        if delta < 0.0:
            return 0.0
        n = par.get("exponent", 1.5)
        return par["k_c"] * delta**n + par["c_c"] * delta**n * (v1 - v2)
    fc = par["k_c"] * delta + par["c_c"] * (v1 - v2)
    if par.get("law", "paper") == "no-tension":
        if pushing is None:
            pushing = fc >= 0.0
        if not pushing:
            return 0.0
    return fc


# ---------------------------------------------------------------------------------------
# single bodies


def duffing_body_rhs(t, y, par):
    x, v = y
    acc = (par["F"] * np.sin(par["w"] * t) - par["c"] * v - par["k1"] * x
           - par["k2"] * x**3)
    return np.array([v, acc])


def bilinear_body_rhs(t, y, par, left=None):
    """The left body: second spring k2 engaged while x <= -d1."""
    x, v = y
    if left is None:
        left = -x - par["d1"] >= 0.0
    spring = par["k2"] * (x + par["d1"]) if left else 0.0
    acc = par["F"] * np.sin(par["w"] * t) - par["c"] * v - par["k1"] * x - spring
    return np.array([v, acc])


# ---------------------------------------------------------------------------------------
# pairs


def duffing_pair_rhs(t, y, par, contact=None, pushing=None):
    x1, v1, x2, v2 = y
    fc = contact_force(x1, v1, x2, v2, par, contact, pushing)
    F, w, c, k1, k2 = par["F"], par["w"], par["c"], par["k1"], par["k2"]
    a1 = F * np.sin(w * t) - c * v1 - k1 * x1 - k2 * x1**3 - fc
    a2 = F * np.sin(w * t + par["phi"]) - c * v2 - k1 * x2 - k2 * x2**3 + fc
    return np.array([v1, a1, v2, a2])


def bilinear_pair_rhs(t, y, par, contact=None, pushing=None, left=None, right=None):
    x1, v1, x2, v2 = y
    fc = contact_force(x1, v1, x2, v2, par, contact, pushing)
    F, w, c, k1, k2, d1 = par["F"], par["w"], par["c"], par["k1"], par["k2"], par["d1"]
    if left is None:
        left = -x1 - d1 >= 0.0  # H(-x1 - d1)
    if right is None:
        right = x2 - d1 >= 0.0  # H(x2 - d1)
    s1 = k2 * (x1 + d1) if left else 0.0
    s2 = k2 * (x2 - d1) if right else 0.0
    a1 = F * np.sin(w * t) - c * v1 - k1 * x1 - s1 - fc
    a2 = F * np.sin(w * t + par["phi"]) - c * v2 - k1 * x2 - s2 + fc
    return np.array([v1, a1, v2, a2])


# ---------------------------------------------------------------------------------------
# models as (rhs of a mode, switching functions), for solve_with_events


@dataclass
class Switched:
    """A piecewise-smooth model: ``rhs(t, y, mode)`` and switching functions ``g_i(t, y)``.

    Bit i of ``mode`` is the side of g_i (set: g_i >= 0), tracked through crossings.
    """

    rhs: Callable[[float, np.ndarray, int], np.ndarray]
    switches: list[Callable[[float, np.ndarray], float]]
    names: list[str] = field(default_factory=list)


def _delta(par):
    return lambda t, y: y[0] - y[2] - par["d"]


def _stop_force(par):
    # The no-tension decision; tracked in every mode (it only matters in contact).
    return lambda t, y: par["k_c"] * (y[0] - y[2] - par["d"]) + par["c_c"] * (y[1] - y[3])


def duffing_pair_model(par) -> Switched:
    sw = [_delta(par)]
    names = ["contact"]
    if par.get("law", "paper") == "no-tension":
        sw.append(_stop_force(par))
        names.append("stop force")

    def rhs(t, y, mode):
        pushing = bool(mode & 2) if len(sw) > 1 else None
        return duffing_pair_rhs(t, y, par, contact=bool(mode & 1), pushing=pushing)

    return Switched(rhs, sw, names)


def bilinear_pair_model(par) -> Switched:
    sw = [_delta(par), lambda t, y: -y[0] - par["d1"], lambda t, y: y[2] - par["d1"]]
    names = ["contact", "left spring", "right spring"]
    if par.get("law", "paper") == "no-tension":
        sw.append(_stop_force(par))
        names.append("stop force")

    def rhs(t, y, mode):
        pushing = bool(mode & 8) if len(sw) > 3 else None
        return bilinear_pair_rhs(t, y, par, contact=bool(mode & 1), pushing=pushing,
                                 left=bool(mode & 2), right=bool(mode & 4))

    return Switched(rhs, sw, names)


def bilinear_body_model(par) -> Switched:
    def rhs(t, y, mode):
        return bilinear_body_rhs(t, y, par, left=bool(mode & 1))

    return Switched(rhs, [lambda t, y: -y[0] - par["d1"]], ["spring"])


# ---------------------------------------------------------------------------------------
# the referee


@dataclass
class EventSolution:
    t_eval: np.ndarray
    y_eval: np.ndarray  # (len(t_eval), dim)
    y_end: np.ndarray
    event_t: list[float]
    event_surface: list[int]
    event_mode: list[int]  # mode after each event


def solve_with_events(rhs_per_mode: Callable, y0: Sequence[float], t_span: tuple[float, float],
                      switches: Sequence[Callable], t_eval: Sequence[float] | None = None,
                      rtol: float = 1e-12, atol: float = 1e-12,
                      max_events: int = 100_000, method: str = "DOP853",
                      **solver_options) -> EventSolution:
    """Integrate a switched system with DOP853 (or ``method``), restarting at every crossing.

    ``rhs_per_mode(t, y, mode)``; ``switches[i](t, y)`` = g_i; bit i of the initial mode is
    ``g_i(t0, y0) >= 0``. Each event watches only the crossing *out of* the current side
    (direction -1 when the bit is set, +1 otherwise), so a rounding residual on the wrong
    side right after a restart cannot fire again. After an event the bits of the surfaces
    that fired are flipped. ``solver_options`` go to ``solve_ivp`` (e.g. ``max_step``: scipy
    only sees a sign change between its step ends, so a graze shorter than a step needs it).
    """
    t0, t1 = map(float, t_span)
    y = np.array(y0, dtype=float)
    mode = 0
    for i, g in enumerate(switches):
        if g(t0, y) >= 0.0:
            mode |= 1 << i
    t_eval = np.array([] if t_eval is None else t_eval, dtype=float)
    y_eval = np.full((t_eval.size, y.size), np.nan)
    ev_t, ev_s, ev_m = [], [], []
    t = t0
    n_events = 0
    while t < t1:
        events = []
        for i, g in enumerate(switches):
            def ev(tt, yy, g=g):
                return g(tt, yy)
            ev.terminal = True
            ev.direction = -1.0 if (mode >> i) & 1 else 1.0
            events.append(ev)
        m = mode
        todo = (t_eval >= t) & (t_eval <= t1)
        sol = solve_ivp(lambda tt, yy, m=m: rhs_per_mode(tt, yy, m), (t, t1), y, method=method,
                        rtol=rtol, atol=atol, events=events, dense_output=True,
                        **solver_options)
        if sol.status < 0:
            raise RuntimeError(sol.message)
        t_stop = sol.t[-1]
        # states at the requested times inside this smooth piece (end point included)
        sel = todo & (t_eval <= t_stop)
        if sel.any():
            y_eval[sel] = sol.sol(t_eval[sel]).T
            exact = sel & (t_eval == t_stop)
            y_eval[exact] = sol.y[:, -1]
        y = sol.y[:, -1].copy()
        t = t_stop
        if sol.status == 1:
            fired = 0
            for i, te in enumerate(sol.t_events):
                if len(te) and te[-1] == t_stop:
                    fired |= 1 << i
            if fired == 0:  # pragma: no cover - scipy always reports the terminal event
                raise RuntimeError("terminal event without a surface")
            mode ^= fired
            for i in range(len(switches)):
                if (fired >> i) & 1:
                    ev_t.append(t)
                    ev_s.append(i)
                    ev_m.append(mode)
            n_events += 1
            if n_events > max_events:
                raise RuntimeError("too many events (chattering?)")
        else:
            break
    return EventSolution(t_eval, y_eval, y, ev_t, ev_s, ev_m)


def solve_model(model: Switched, y0, t_span, t_eval=None, rtol=1e-12, atol=1e-12):
    return solve_with_events(model.rhs, y0, t_span, model.switches, t_eval, rtol, atol)


def duffing_pair_energy(y, par):
    """sum(v^2/2 + k1 x^2/2 + k2 x^4/4) + the stop's potential energy: k_c/2 delta^2 while
    delta > 0, or k_c delta^(n+1)/(n+1) for the Hunt-Crossley law."""
    y = np.asarray(y)
    x1, v1, x2, v2 = y[..., 0], y[..., 1], y[..., 2], y[..., 3]
    k1, k2 = par["k1"], par["k2"]
    e = 0.0
    for x, v in ((x1, v1), (x2, v2)):
        e = e + 0.5 * v**2 + 0.5 * k1 * x**2 + 0.25 * k2 * x**4
    delta = np.where(x1 - x2 - par["d"] > 0.0, x1 - x2 - par["d"], 0.0)
    if par.get("law", "paper") == "hunt-crossley":
        n = par.get("exponent", 1.5)
        return e + par["k_c"] * delta ** (n + 1) / (n + 1)
    return e + 0.5 * par["k_c"] * delta**2


# ---------------------------------------------------------------------------------------
# basin planes with known answers, and a loop-by-loop basin entropy (analysis.basin_entropy)


def newton_basins(n: int, half_width: float = 2.0, iterations: int = 40) -> np.ndarray:
    """Basins of Newton's method for z^3 = 1 on an n x n grid of [-w, w]^2 (rows: Im z):
    the index (0, 1, 2) of the cube root of unity each start ends nearest to."""
    axis = np.linspace(-half_width, half_width, n)
    z = axis[None, :] + 1j * axis[:, None]
    for _ in range(iterations):
        z = z - (z**3 - 1) / (3 * z**2 + (z == 0))  # z = 0 (never on an even grid) stays
    roots = np.exp(2j * np.pi * np.arange(3) / 3)
    return np.argmin(np.abs(z[..., None] - roots), axis=-1)


def cantor_comb(base: int, kept: tuple[int, ...], level: int, rows: int) -> np.ndarray:
    """Two basins split by a Cantor set of vertical lines: column i (of base**level) is in
    basin 1 when every base-``base`` digit of i is in ``kept``. The boundary is C x [0, 1]
    for the Cantor set C of ``kept`` digits: box-counting dimension
    1 + ln(len(kept)) / ln(base), so alpha = 1 - ln(len(kept)) / ln(base)."""
    i = np.arange(base**level)
    inside = np.ones(i.size, dtype=bool)
    for _ in range(level):
        inside &= np.isin(i % base, kept)
        i = i // base
    return np.tile(inside.astype(np.int32), (rows, 1))


def basin_entropy_loops(labels, n: int) -> tuple[float, float]:
    """(S_b, S_bb) of Daza et al. 2016 box by box with Python loops: complete n x n boxes
    from the first cell, p_j = share of label j in the box, S = -sum p ln p."""
    labels = np.asarray(labels)
    entropies = []
    for top in range(0, labels.shape[0] - n + 1, n):
        for left in range(0, labels.shape[1] - n + 1, n):
            box = labels[top:top + n, left:left + n].ravel().tolist()
            s = 0.0
            for value in set(box):
                p = box.count(value) / len(box)
                s -= p * np.log(p)
            entropies.append(s)
    boundary = [s for s in entropies if s > 0]
    return float(np.mean(entropies)), float(np.mean(boundary)) if boundary else float("nan")
