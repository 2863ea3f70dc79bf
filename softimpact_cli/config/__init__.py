"""Scenes: a TOML file becomes a validated, frozen :class:`Scene`.

A scene states only what differs from the defaults. Every problem a user can cause
raises :class:`ConfigError`, whose message is one line naming the file, the section and
key, and what is allowed. Unknown sections and keys are errors, never ignored.

- ``reader``: the table reader and the error type;
- ``scene``: [system], [coupling], [integrator], [output] and the Scene (its kind's
  sections are read by ``kinds.scene``, above: config knows no kind);
- ``axes``: the axes a sweep can span, defined once;
- ``sweep``: [grid], [initial_conditions] and [catalogue] for sweeps;
- ``verification``: [verification], how a sweep measures its label error.
"""

from .axes import COUPLING_AXES, GRID_AXES, GRID_UNITS
from .reader import ConfigError, check_writable
from .scene import IntegratorSettings, Scene, SceneContext, forcing_period, result_path
from .sweep import CatalogueSettings, Grid, InitialConditions
from .verification import VerificationSettings

__all__ = ["COUPLING_AXES", "GRID_AXES", "GRID_UNITS", "CatalogueSettings", "ConfigError",
           "Grid", "InitialConditions", "IntegratorSettings", "Scene", "SceneContext",
           "VerificationSettings", "check_writable", "forcing_period", "result_path"]

# names that moved up to the kinds (config knows no kind: ARCHITECTURE.md)
_MOVED = {"parse_scene": "kinds.scene", "load_scene": "kinds.scene", "quick": "kinds.scene",
          "ANALYSIS_KINDS": "kinds", "SWEEP_KINDS": "kinds",
          "CatalogueAnalysis": "kinds.catalogue", "SweepAnalysis": "kinds.sweeps",
          "TrajectoryAnalysis": "kinds.trajectory"}


def __getattr__(name: str):
    if name in _MOVED:
        raise AttributeError(f"softimpact_cli.config.{name} moved: import it from "
                             f"softimpact_cli.{_MOVED[name]} (config reads no kind)")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
