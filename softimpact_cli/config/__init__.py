"""Scenes: a TOML file becomes a validated, frozen :class:`Scene`.

A scene states only what differs from the defaults. Every problem a user can cause
raises :class:`ConfigError`, whose message is one line naming the file, the section and
key, and what is allowed. Unknown sections and keys are errors, never ignored.

- ``reader``: the table reader and the error type;
- ``scene``: [system], [coupling], [integrator], [analysis], [output] and the Scene;
- ``axes``: the axes a sweep can span, defined once;
- ``sweep``: [grid], [initial_conditions] and [catalogue] for sweeps;
- ``verification``: [verification], how a sweep measures its label error.
"""

from .axes import COUPLING_AXES, GRID_AXES, GRID_UNITS
from .reader import ConfigError, check_writable
from .scene import (
    ANALYSIS_KINDS,
    SWEEP_KINDS,
    CatalogueAnalysis,
    IntegratorSettings,
    Scene,
    SweepAnalysis,
    TrajectoryAnalysis,
    load_scene,
    parse_scene,
    quick,
    result_path,
)
from .sweep import CatalogueSettings, Grid, InitialConditions
from .verification import VerificationSettings

__all__ = ["ANALYSIS_KINDS", "COUPLING_AXES", "GRID_AXES", "GRID_UNITS", "SWEEP_KINDS",
           "CatalogueAnalysis",
           "CatalogueSettings", "ConfigError", "Grid", "InitialConditions",
           "IntegratorSettings", "Scene", "SweepAnalysis", "TrajectoryAnalysis",
           "VerificationSettings",
           "check_writable", "load_scene", "parse_scene", "quick", "result_path"]
