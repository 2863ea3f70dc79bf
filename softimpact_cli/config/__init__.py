"""Scenes: a TOML file becomes a validated, frozen :class:`Scene`.

A scene states only what differs from the defaults. Every problem a user can cause
raises :class:`ConfigError`, whose message is one line naming the file, the section and
key, and what is allowed. Unknown sections and keys are errors, never ignored.

- ``reader``: the table reader and the error type;
- ``scene``: [system], [coupling], [integrator], [analysis], [output] and the Scene;
- ``sweep``: [grid], [initial_conditions] and [catalogue] for sweeps.
"""

from .reader import ConfigError, check_writable
from .scene import (
    ANALYSIS_KINDS,
    CatalogueAnalysis,
    IntegratorSettings,
    Scene,
    TrajectoryAnalysis,
    load_scene,
    parse_scene,
)

__all__ = ["ANALYSIS_KINDS", "CatalogueAnalysis", "ConfigError", "IntegratorSettings", "Scene",
           "TrajectoryAnalysis", "check_writable", "load_scene", "parse_scene"]
