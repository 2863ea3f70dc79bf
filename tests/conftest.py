"""Session-wide settings: the catalogue cache lives in a temporary folder, never in the
user's ~/.cache (subprocesses the tests start inherit the variable); hypothesis has no
per-example deadline (a first example may compile a kernel, and a shared machine's load
is not a property of the code)."""

import os
import shutil
import tempfile

from hypothesis import settings

settings.register_profile("softimpact", deadline=None)
settings.load_profile("softimpact")

_CACHE = tempfile.mkdtemp(prefix="softimpact-test-cache-")
os.environ["SOFTIMPACT_CACHE_DIR"] = _CACHE
os.environ.pop("SOFTIMPACT_NO_CACHE", None)  # the tests say when they want it off


def pytest_unconfigure(config):
    shutil.rmtree(_CACHE, ignore_errors=True)
