"""Numba kernels: integrate, locate switches, classify. Arrays in, arrays and codes out.

Kernels import only numpy, numba and math; they never raise, print or touch files.
Every integrator module provides ``advance`` with one signature, so the trajectory
kernels take the method as a first-class function:

    advance(rhs, p, y, t, t_end, A, b, relevance, contact, opts, istate, fstate, work,
            sample_t, sample_y) -> status
"""

from .numba_cache import source_keyed_cache, stabilise

with source_keyed_cache():  # every jitted module of the package, imported here
    from . import auto, cells, common, dense, dopri5, orbit, rk4, rosenbrock, switching

for _module in (auto, cells, common, dense, dopri5, orbit, rk4, rosenbrock, switching):
    stabilise(_module)

# method name -> module (each has ``advance`` and ``ORDER``; "auto" switches between
# dopri5 and rodas4 per step and per contact mode)
METHODS = {"rk4": rk4, "dopri5": dopri5, "rodas4": rosenbrock, "auto": auto}
