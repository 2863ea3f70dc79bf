"""softimpact: multistability of oscillators coupled through soft impacts.

The Python API (see ``api``): ``load_scene``, ``run``, ``sweep``, ``open_result``,
``kinds()``, ``System`` (one parameter point: ``classify(u0)``, ``api_system``), the
accessor ``ds.si`` (``shares()``, ``names()``: ``accessor``) and the figures
``plot.<kind>(ds, ax=None)``, e.g. ``import softimpact_cli as si;
si.plot.basins(si.run(si.load_scene("configs/demo_basins.toml"), quick=True))``.
Importing the package loads neither matplotlib nor xarray; ``plot`` is imported on
first use.
"""

__version__ = "0.1.0"

import gc as _gc  # noqa: E402
import importlib  # noqa: E402
import os as _os  # noqa: E402
import sys as _sys  # noqa: E402

# The `softimpact` command collects cyclic garbage less often, from its first import on:
# the imports and a small sweep make millions of short-lived container objects (numba's,
# xarray's, pandas'), and at CPython's default first threshold (700) the collector took
# 0.07-0.2 s of a 2 s 10 x 10 sweep (two A/B runs, 2026-11-26). A program that imports
# the package keeps its own settings.
COMMAND_GC_THRESHOLD = (50_000, 20, 20)
if _sys.argv and _os.path.basename(_sys.argv[0]) == "softimpact":
    _gc.set_threshold(*COMMAND_GC_THRESHOLD)

# The API's functions are imported on first use (they import xarray, the store and the
# analyses). ``softimpact_cli.sweep`` and ``softimpact_cli.kinds`` are the functions
# ``api.sweep`` and ``api.kinds``: the subpackages of the same names, bound here by Python
# when they are first imported, are unbound again so that the names go to
# ``__getattr__``; ``from softimpact_cli.sweep import run_sweep`` and ``from
# softimpact_cli.kinds import KINDS`` work as before (the subpackages stay in sys.modules).
from . import kinds as _kinds_package  # noqa: E402, F401
from . import sweep as _sweep_package  # noqa: E402, F401
from .config import ConfigError  # noqa: E402

del sweep, kinds  # noqa: F821  (the subpackages' bindings; see above)

_API = ("kinds", "load_scene", "measure", "open_result", "run", "shrink_scene", "sweep")
__all__ = ["Classified", "ConfigError", "System", "kinds", "load_scene", "measure",
           "open_result", "plot", "run", "shrink_scene", "sweep"]

if "xarray" in _sys.modules:  # ds.si on datasets xarray opens itself (else on first use)
    from . import accessor as _accessor  # noqa: E402, F401


def __getattr__(name: str):
    # the API on first use; the figures (matplotlib), System (xarray, the sweep machinery)
    # only when a notebook first asks for them
    if name in _API:
        api = importlib.import_module(".api", __name__)
        globals().update({n: getattr(api, n) for n in _API})
        return globals()[name]
    if name in ("System", "Classified"):
        return getattr(importlib.import_module(".api_system", __name__), name)
    if name == "plot":
        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
