"""softimpact: multistability of oscillators coupled through soft impacts."""

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
