"""Session-wide settings: the catalogue cache lives in a temporary folder, never in the
user's ~/.cache (subprocesses the tests start inherit the variable); hypothesis has no
per-example deadline (a first example may compile a kernel, and a shared machine's load
is not a property of the code) and, in `make test` (the CI gate), draws the same examples
every run (SOFTIMPACT_HYPOTHESIS=ci: a gate that passes or fails by chance tells nothing;
`make test-fast` keeps drawing new ones, and SOFTIMPACT_HYPOTHESIS=explore draws 20 times
as many where a test does not set its own count); SIGINT is not left ignored (see below)."""

import os
import shutil
import signal
import tempfile

from hypothesis import settings

settings.register_profile("softimpact", deadline=None)
settings.register_profile("ci", deadline=None, derandomize=True, database=None)
settings.register_profile("explore", deadline=None, max_examples=2000)
settings.load_profile(os.environ.get("SOFTIMPACT_HYPOTHESIS", "softimpact"))

_CACHE = tempfile.mkdtemp(prefix="softimpact-test-cache-")
os.environ["SOFTIMPACT_CACHE_DIR"] = _CACHE
os.environ.pop("SOFTIMPACT_NO_CACHE", None)  # the tests say when they want it off

# A shell starts background jobs with SIGINT ignored when job control is off (`cmd &` in
# a script), and an ignored signal stays ignored in every process the tests start: the
# interruption tests would then see no Ctrl-C at all (five failed that way when a CI run
# was launched in the background). Python's own handler again, inherited as "default" by
# the subprocesses.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_unconfigure(config):
    shutil.rmtree(_CACHE, ignore_errors=True)
