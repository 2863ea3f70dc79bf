"""Critical distances: below d_crit(phi) a non-impacting combination cannot exist.

For a combination's uncoupled joint orbit (period q forcing periods),

    d_crit = max over one joint period of x1(t) - x2(t).

The maximum is first bracketed on dense samples, then located as a root of the relative
velocity v1 - v2 (the derivative of x1 - x2) by the Illinois method on the flow itself,
to 1e-12 in time, so d_crit is accurate to the integration tolerance (~1e-11), not to the
sampling step.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config import IntegratorSettings
from ..systems import System
from .catalogue import Catalogue, body_problem, combinations, right_attractors
from .engine import Problem, flow, record_trajectory

TIGHT = IntegratorSettings(method="dopri5", rtol=1e-12, atol=1e-13)
NO_CONTACT_D = 1e12  # a gap no orbit reaches: the pair integrates uncoupled


def uncoupled_pair(system: System, values: dict, phi: float,
                   integrator: IntegratorSettings = TIGHT) -> Problem:
    return Problem(system, {**values, "phi": phi, "d": NO_CONTACT_D}, integrator)


def relative_trace(problem: Problem, start: np.ndarray, periods: int, samples: int
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, x1 - x2, states) over ``periods`` forcing periods from ``start`` at t = 0."""
    traj = record_trajectory(problem, start, 0.0, periods, samples)
    return traj.t, traj.y[:, 0] - traj.y[:, 2], traj.y


def locate_maximum(problem: Problem, t: np.ndarray, y: np.ndarray, k: int,
                   tol: float = 1e-12) -> tuple[float, float]:
    """Refine the sampled maximum at index k: (t*, x1 - x2 at t*) with v1 - v2 = 0."""
    n = len(t)
    lo, hi = max(k - 1, 0), min(k + 1, n - 1)

    def state(time: float) -> np.ndarray:
        i = int(np.clip(np.searchsorted(t, time) - 1, 0, n - 1))
        return flow(problem, y[i], t[i], time)[1]

    def rate(time: float) -> float:
        s = state(time)
        return s[1] - s[3]

    a, b = t[lo], t[hi]
    fa, fb = y[lo, 1] - y[lo, 3], y[hi, 1] - y[hi, 3]
    if not (fa >= 0.0 >= fb):  # maximum at a sample (or a kink): keep the sampled value
        return float(t[k]), float(y[k, 0] - y[k, 2])
    t_star = zero_of_rate(rate, a, b, fa, fb, tol)
    s = state(t_star)
    return float(t_star), float(s[0] - s[2])


def zero_of_rate(rate, a: float, b: float, fa: float, fb: float, tol: float) -> float:
    """The time in [a, b] where ``rate`` (a callable of time; ``fa >= 0 >= fb`` its values at
    the ends) falls through zero, by the Illinois method to ``tol``: where a maximum of a
    contact function lies (the pair's and the chain's critical distances)."""
    side = 0
    for _ in range(100):
        if b - a < tol:
            break
        m = a + fa * (b - a) / (fa - fb) if fa != fb else 0.5 * (a + b)
        if not a < m < b:
            m = 0.5 * (a + b)
        fm = rate(m)
        if fm > 0.0:
            a, fa = m, fm
            if side == 1:
                fb *= 0.5
            side = 1
        elif fm < 0.0:
            b, fb = m, fm
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a = b = m
    return 0.5 * (a + b)


def critical_distance(problem: Problem, start: np.ndarray, periods: int, samples: int = 512
                      ) -> tuple[float, float]:
    """(d_crit, time of the maximum in [0, periods T)) of the joint orbit through start."""
    t, g, y = relative_trace(problem, start, periods, samples)
    t, g, y = t[:-1], g[:-1], y[:-1]  # one joint period; the last sample repeats the first
    k = int(np.argmax(g))
    t_star, value = locate_maximum(problem, t, y, k)
    return value, t_star


def critical_distances(system: System, values: dict, left: list, phis: np.ndarray,
                       samples: int = 512, progress=None,
                       integrator: IntegratorSettings = TIGHT) -> xr.Dataset:
    """d_crit(phi) for every combination of the left attractors, at each phi.

    Returns a Dataset with d_crit(combination, phi) and t_max(combination, phi).
    """
    body = system.extra
    names: list[str] = []
    rows: dict[str, list] = {}
    times: dict[str, list] = {}
    for phi in phis:
        problem = uncoupled_pair(system, values, float(phi), integrator)

        right = right_attractors(body_problem(system, values, integrator), left, float(phi),
                                 body["right_sign"], body["right_phase"])
        for combo in combinations(left, right):
            q = combo.orbit.shape[0]
            d, t_star = critical_distance(problem, combo.orbit[0], q, samples)
            if combo.name not in rows:
                names.append(combo.name)
                rows[combo.name], times[combo.name] = [], []
            rows[combo.name].append(d)
            times[combo.name].append(t_star)
        if progress is not None:
            progress(1)
    return xr.Dataset(
        {
            "d_crit": (("combination", "phi"), np.array([rows[n] for n in names]),
                       {"long_name": "critical distance: max of x1 - x2 on the uncoupled "
                                     "joint orbit", "units": "1"}),
            "t_max": (("combination", "phi"), np.array([times[n] for n in names]),
                      {"long_name": "time of the maximum within the joint period",
                       "units": "1"}),
            "combination_label": (("combination",), np.array(names, dtype=object)),
        },
        coords={"combination": np.arange(len(names)),
                "phi": ("phi", np.asarray(phis, dtype=float), {"units": "rad"})},
    )


def traces(system: System, values: dict, catalogue: Catalogue, phis, samples: int = 512
           ) -> xr.Dataset:
    """x1 - x2 over one joint period for every combination at each phi (fig. 5 b-d)."""
    left = list(catalogue.attractors)
    body = system.extra
    max_q = 1
    data = []
    for phi in phis:
        problem = uncoupled_pair(system, values, float(phi))
        right = right_attractors(body_problem(system, values, TIGHT), left, float(phi),
                                 body["right_sign"], body["right_phase"])
        per_phi = []
        for combo in combinations(left, right):
            q = combo.orbit.shape[0]
            max_q = max(max_q, q)
            t, g, _ = relative_trace(problem, combo.orbit[0], q, samples)
            per_phi.append(g)
        data.append(per_phi)
    n_c = len(data[0]) if data else 0
    out = np.full((len(data), n_c, max_q * samples + 1), np.nan)
    for i, per_phi in enumerate(data):
        for j, g in enumerate(per_phi):
            out[i, j, : g.size] = g
    return xr.Dataset(
        {"relative_trace": (("trace_phi", "combination", "trace_sample"), out,
                            {"long_name": "x1 - x2 along the uncoupled joint orbit",
                             "units": "1"})},
        coords={"trace_phi": ("trace_phi", np.asarray(phis, dtype=float), {"units": "rad"}),
                "trace_sample": np.arange(max_q * samples + 1)},
        attrs={"trace_samples_per_period": samples},
    )
