"""Shared parameter sets and kernel drivers of the numerical verification tests."""

from __future__ import annotations

import hashlib
import inspect

import numpy as np

from softimpact_cli.analysis.engine import Problem
from softimpact_cli.kernels import layout
from softimpact_cli.kernels.orbit import new_state, no_samples
from softimpact_cli.systems import get_system

DUFFING_BODY = dict(c=0.05, k1=1.0, k2=0.01, F=1.0, w=1.3)
DUFFING_PAIR = dict(DUFFING_BODY, d=1.0, phi=np.pi, k_c=8.0, c_c=10.0, law="paper")
BILINEAR_BODY = dict(c=0.02, k1=1.0, k2=29.0, F=0.518, w=0.86, d1=1.26)
BILINEAR_PAIR = dict(BILINEAR_BODY, d=1.0, phi=np.pi, k_c=8.0, c_c=10.0, law="paper")


def problem(model: str, bodies: int, values: dict, **integrator) -> Problem:
    pr = Problem(get_system(model, bodies), dict(values))
    return pr.with_integrator(**integrator) if integrator else pr


def run_advance(pr: Problem, y0, t0: float, t1: float, opts: np.ndarray | None = None):
    """Call the problem's kernel ``advance`` once over [t0, t1]; (status, y, istate, fstate)."""
    y = np.array(y0, dtype=np.float64)
    surfaces = pr.kernel_args()
    istate, fstate, work = new_state(y, surfaces[0], surfaces[1])
    if opts is None:
        opts = pr.options()
    status = pr.advance(pr.system.rhs, pr.params, y, float(t0), float(t1), surfaces, opts,
                        (istate, fstate, work), no_samples(y.size))
    return int(status), y, istate, fstate


def dopri5_fixed(pr: Problem, y0, t0: float, t1: float, h: float, locate: bool = True):
    """dopri5 as a fixed-step method: rtol = atol = 1 (nothing rejected), H_MAX = h."""
    pr = pr.with_integrator(method="dopri5", rtol=1.0, atol=1.0, locate_switches=locate)
    opts = pr.options()
    opts[layout.H_MAX] = h
    return run_advance(pr, y0, t0, t1, opts)


def rk4_fixed(pr: Problem, y0, t0: float, t1: float, steps_per_period: int,
              locate: bool = True):
    pr = pr.with_integrator(method="rk4", steps_per_period=steps_per_period,
                            locate_switches=locate)
    return run_advance(pr, y0, t0, t1)


def fit_slope(h, err) -> float:
    """Least-squares slope of log(err) against log(h)."""
    return float(np.polyfit(np.log(np.asarray(h, float)), np.log(np.asarray(err, float)), 1)[0])


def stable_identity(layout: str, *dispatchers) -> None:
    """Give a test's jitted functions a UUID made of their name and source (and of the
    packed-parameter ``layout`` they read), as ``kernels.numba_cache.stabilise`` does for
    the package: the kernels' disk cache, specialised on these functions, is then reused
    by the next test run instead of growing by one entry per process, and a changed source
    gets a new identity instead of stale cached code."""
    for disp in dispatchers:
        text = inspect.getsource(disp.py_func) + layout
        digest = hashlib.sha1(text.encode()).hexdigest()[:16]
        if getattr(disp, "_MemoMixin__uuid", None) is None:
            disp._set_uuid(f"tests:{disp.py_func.__module__}.{disp.__name__}:{digest}")
