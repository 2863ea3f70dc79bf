"""Numba kernels: integrate, locate switches, classify. Arrays in, arrays and codes out.

Kernels import only numpy, numba and math; they never raise, print or touch files.
Every integrator module provides ``advance`` with one signature, so the trajectory
kernels take the method as a first-class function:

    advance(rhs, p, y, t, t_end, surfaces, opts, state, samples) -> status

with the bundles ``surfaces = (A, b, relevance, contacts)`` (``contacts`` the bit mask of
the contact surfaces), ``state = (istate, fstate,
work)`` (``orbit.new_state``) and ``samples = (sample_t, sample_y)``. A method module
holds its tableau and its hooks (step, error norm, dense output, controller constants)
and builds ``advance`` with a loop of ``driver`` (see there); adding one is its module
and a line in METHOD_MODULES.
"""

from importlib import import_module
from typing import NamedTuple

from .numba_cache import source_keyed_cache, stabilise

# method name -> its module; "auto" switches between dopri5's and rodas4's steps per step
# and per contact mode. The order is the order scenes list them in (the default first).
# "exact" is the closed-form flow of piecewise-linear systems (bilinear, linear stop laws).
METHOD_MODULES = {"auto": "auto", "rk4": "rk4", "dopri5": "dopri5", "rodas4": "rosenbrock",
                  "exact": "exact"}
ALIASES = {"stiff": "rodas4"}  # other names a scene may use

_SHARED = ("cells", "codes", "common", "control", "dense", "driver", "layout", "linalg",
           "orbit", "switching", "saltation", "lyapunov", "impacts")
with source_keyed_cache():  # every jitted module of the package, imported here
    _modules = {name: import_module(f".{name}", __name__)
                for name in (*_SHARED, *METHOD_MODULES.values())}
    # each method's advance with rigid impacts (kernels/impacts.py); compiled when used
    IMPACT_ADVANCE = {name: _modules["impacts"].impact_loop(name, _modules[module].advance)
                      for name, module in METHOD_MODULES.items()}
for _module in _modules.values():
    stabilise(_module)
METHODS = {name: _modules[module] for name, module in METHOD_MODULES.items()}


class MethodTraits(NamedTuple):
    """What a method is, as data on its module: ``tolerance`` (rtol and atol steer its
    steps), ``fixed_step`` (steps_per_period steps per forcing period), ``closed_form``
    (the exact flow of piecewise-linear systems)."""

    tolerance: bool
    fixed_step: bool
    closed_form: bool


def method_traits(name: str) -> MethodTraits:
    """The traits of method ``name`` (an alias too); all False for an unknown name (a
    result written by another version)."""
    module = METHODS.get(ALIASES.get(name, name))
    if module is None:
        return MethodTraits(False, False, False)
    return MethodTraits(module.HAS_TOLERANCE, module.FIXED_STEP, module.CLOSED_FORM)
