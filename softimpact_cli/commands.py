"""The library functions the command line calls, imported when a command runs: they
import the analyses, xarray and the store, which ``softimpact --help`` and the command
line's start do without (``cli.py`` imports only this module's names, inside the
commands)."""

from .analysis.engine import Problem
from .analysis.step_stability import rk4_step_warning
from .analysis.warmup import announce_compilation
from .api import measure as measure_result
from .api import open_result, read_result, shrink_scene
from .api import sweep as run_to_file
from .kinds.results import (
    compare_results,
    describe,
    format_comparison,
    format_summary,
    outcome_warnings,
)
from .kinds.run import plan_text
from .plot import save
from .report.compare import limits_exceeded
from .report.fractality import fractality_lines
from .report.info import compare_shares, incomplete_summary
from .report.outcomes import STRICT_STATUS, outcome_notes
from .report.verification import verification_line
from .reproduce.report import reproduce as run_reproduce
from .reproduce.runs import CACHE
from .reproduce.table import summary
from .store.catalogue_cache import cache_folder, clear, switched_off
from .store.catalogue_cache import info as cache_state
from .store.sweep_store import SweepStore
from .sweep.verification import OVER, VERIFIED

__all__ = [
    "CACHE", "OVER", "VERIFIED", "Problem", "STRICT_STATUS", "SweepStore",
    "announce_compilation", "cache_folder", "cache_state", "clear", "compare_results",
    "compare_shares", "describe", "format_comparison", "format_summary",
    "fractality_lines", "incomplete_summary", "limits_exceeded", "measure_result",
    "open_result", "outcome_notes", "outcome_warnings", "plan_text", "read_result",
    "rk4_step_warning", "run_reproduce",
    "run_to_file", "save", "shrink_scene", "summary", "switched_off", "verification_line",
]
