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

# The packages ``sweep`` and ``kinds`` first (``api`` imports ``kinds``): importing a
# submodule binds it as an attribute of this package, which would replace the function
# of the same name bound below if it came later. So ``softimpact_cli.sweep`` and
# ``softimpact_cli.kinds`` are the functions; ``from softimpact_cli.sweep import
# run_sweep`` and ``from softimpact_cli.kinds import KINDS`` work as before.
from . import sweep as _sweep_package  # noqa: E402, F401
from .api import (  # noqa: E402
    ConfigError,
    kinds,
    load_scene,
    measure,
    open_result,
    run,
    shrink_scene,
    sweep,
)

__all__ = ["Classified", "ConfigError", "System", "kinds", "load_scene", "measure",
           "open_result", "plot", "run", "shrink_scene", "sweep"]

if "xarray" in _sys.modules:  # ds.si on datasets xarray opens itself (else on first use)
    from . import accessor as _accessor  # noqa: E402, F401


def __getattr__(name: str):
    # the figures import matplotlib, System xarray and the sweep machinery: only when a
    # notebook first asks for them
    import importlib

    if name == "plot":
        return importlib.import_module(".plot", __name__)
    if name in ("System", "Classified"):
        return getattr(importlib.import_module(".api_system", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
