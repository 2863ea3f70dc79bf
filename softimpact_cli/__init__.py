"""softimpact: multistability of oscillators coupled through soft impacts.

The Python API (see ``api``): ``load_scene``, ``run``, ``sweep``, ``open_result`` and the
figures ``plot.<kind>(ds, ax=None)``, e.g. ``import softimpact_cli as si;
si.plot.basins(si.run(si.load_scene("configs/demo_basins.toml"), quick=True))``.
Importing the package loads neither matplotlib nor xarray; ``plot`` is imported on
first use.
"""

__version__ = "0.1.0"


def _compile_kernels_into_a_source_keyed_cache() -> None:
    # numba binds a function's cache folder when it is decorated: point it at a folder
    # keyed by our sources while our kernels and systems are imported, then restore it.
    import numba

    from ._numba_cache_dir import cache_dir

    previous = numba.config.CACHE_DIR
    folder = cache_dir()
    if folder is not None:
        numba.config.CACHE_DIR = folder
    try:
        from . import kernels, systems  # noqa: F401
    finally:
        numba.config.CACHE_DIR = previous


_compile_kernels_into_a_source_keyed_cache()

# The modules named like API functions first (``run.py``, the package ``sweep``):
# importing a submodule binds it as an attribute of this package, which would replace
# the function of the same name bound below if it came later. So ``softimpact_cli.run``
# and ``softimpact_cli.sweep`` are the functions; ``from softimpact_cli.run import
# run_scene`` and ``from softimpact_cli.sweep import run_sweep`` work as before.
from . import run as _run_module  # noqa: E402, F401
from . import sweep as _sweep_package  # noqa: E402, F401
from .api import ConfigError, load_scene, open_result, run, shrink_scene, sweep  # noqa: E402

__all__ = ["ConfigError", "load_scene", "open_result", "plot", "run", "shrink_scene", "sweep"]


def __getattr__(name: str):
    # the figures import matplotlib: only when a notebook first asks for them
    if name == "plot":
        import importlib

        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
