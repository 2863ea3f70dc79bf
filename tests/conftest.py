"""Session-wide settings: the catalogue cache lives in a temporary folder, never in the
user's ~/.cache (subprocesses the tests start inherit the variable)."""

import os
import shutil
import tempfile

_CACHE = tempfile.mkdtemp(prefix="softimpact-test-cache-")
os.environ["SOFTIMPACT_CACHE_DIR"] = _CACHE
os.environ.pop("SOFTIMPACT_NO_CACHE", None)  # the tests say when they want it off


def pytest_unconfigure(config):
    shutil.rmtree(_CACHE, ignore_errors=True)
