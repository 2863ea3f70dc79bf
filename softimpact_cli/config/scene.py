"""Scenes: a TOML file becomes a validated, frozen :class:`Scene`.

A scene states only what differs from the defaults. Every problem a user can cause
raises :class:`ConfigError` whose message is one line naming the file, the section and
key, and what is allowed. Unknown sections and keys are errors, never ignored.
"""

from __future__ import annotations

import hashlib
import math
import os
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..kernels import ALIASES, METHOD_MODULES, MethodTraits, method_traits
from ..kernels.cells import MAX_CELL_DIM
from ..systems import LAW_KEYS, LAWS, MODELS, STOP_LAWS, System, get_system
from ..systems.base import SUPPORTED_BODIES, forcing_period_of
from ..systems.piecewise_linear import exact_refusal
from .axes import COUPLING_AXES
from .chain_scene import CHAIN, TABLES, read_chain
from .limits import (
    MAX_NESTING,
    check_nesting,
    parameter_problem,
    t0_problem,
)
from .reader import ConfigError, Section, did_you_mean, output_path, positive
from .sweep import (
    CatalogueSettings,
    Grid,
    InitialConditions,
    read_catalogue,
)
from .verification import VerificationSettings

METHODS = (*METHOD_MODULES, *ALIASES)  # the kernels' registry


def forcing_period(values: Mapping[str, Any]) -> float:
    """The forcing period T = 2 pi / w of a parameter point (``values["w"]``)."""
    return forcing_period_of(values["w"])


@dataclass(frozen=True)
class SceneContext:
    """What reading a kind's sections needs from the rest of the scene.

    check_axis(axis, value) -> what is wrong with ``value`` on a grid/design axis, or None.
    """

    source: str
    doc: Mapping[str, Any]
    system: System
    values: Mapping[str, Any]
    period: float  # forcing period 2 pi / w
    check_axis: Callable[[str, float], str | None]

    def refuse(self, *sections: str) -> None:
        """One line when the scene has a section this kind does not read."""
        for name in sections:
            if name in self.doc:
                raise ConfigError(f"{self.source}: [{name}]: not used by kind "
                                  f"{self.doc.get('analysis', {}).get('kind', 'trajectory')!r}")

    def read_catalogue(self) -> CatalogueSettings:
        """The scene's [catalogue] section (its box by default the system's)."""
        return read_catalogue(self.source, self.doc, self.system.extra["catalogue_box"])


@dataclass(frozen=True)
class IntegratorSettings:
    """The validated [integrator] section (see README for meanings and defaults)."""

    method: str = "auto"
    steps_per_period: int = 1440
    locate_switches: bool = True
    rtol: float = 1e-8
    atol: float = 1e-10
    max_periods: int = 3000
    max_orbit_period: int = 30
    convergence_tol: float = 1e-6
    capture_tol: float = 1e-2
    capture_hits: int = 3
    cell_size: float = 0.02  # benchmarks/bench_settings.py: safe on the study's five planes
    cell_hits: int = 8
    divergence_bound: float = 1e6
    max_steps_per_period: int = 200_000
    max_switches_per_period: int = 10_000
    # the second stage for unresolved trajectories (analysis/section_follow.py,
    # analysis/nonperiodic.py; README "Attractors that are not periodic")
    section_periods: int = 4000  # 0: off (unresolved stays unresolved)
    section_cell: float = 0.5
    section_recurrences: int = 100
    section_locate: int = 500
    section_max_period: int = 200
    section_lyapunov_periods: int = 400
    section_zero_exponent: float = 0.004

    @property
    def resolved_method(self) -> str:
        """The kernel method the run uses ('stiff' is the L-stable Rodas4; 'auto' runs the
        adaptive explicit pair and switches to Rodas4 where its step is stability bound)."""
        return ALIASES.get(self.method, self.method)

    @property
    def traits(self) -> MethodTraits:
        """What the method is: has a tolerance, fixed step, closed form (kernels)."""
        return method_traits(self.method)


@dataclass(frozen=True)
class Scene:
    source: str
    text: str
    system: System
    values: Mapping[str, Any]
    integrator: IntegratorSettings
    analysis: Any
    output: Path
    sections: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    grid: Grid | None = None
    initial_conditions: InitialConditions | None = None
    catalogue: CatalogueSettings | None = None
    verification: VerificationSettings | None = None  # sweep kinds only

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()


# ---------------------------------------------------------------- sections


def _read_system(source: str, doc: dict) -> tuple[System, dict[str, Any]]:
    sec = Section(source, "system", doc.get("system", {}))
    model = sec.choice("model", None, MODELS + (CHAIN,)) if sec.has("model") else None
    if model is None:
        raise sec.fail("model", f"is required; one of {', '.join(map(repr, MODELS))} or "
                                f"{CHAIN!r}")
    if model == CHAIN:
        return read_chain(source, doc)
    for name in TABLES:
        if name in doc:
            raise ConfigError(f"{source}: [[{name}]]: only for model = {CHAIN!r}; the "
                              f"{model} model's stop is [coupling]")
    bodies = sec.integer("bodies", 2, min(SUPPORTED_BODIES), max(SUPPORTED_BODIES))
    system = get_system(model, bodies)
    body_params = [p for p in system.parameters if p.name not in COUPLING_AXES]
    values: dict[str, Any] = {}
    for param in body_params:
        values[param.name] = sec.number(
            param.name, param.default,
            lambda v, p=param: p.check(v) or parameter_problem(p.name, v))
    sec.finish(("model", "bodies") + tuple(p.name for p in body_params))
    return system, values


def _read_coupling(source: str, doc: dict, system: System, values: dict[str, Any]) -> None:
    if system.model == CHAIN:
        if "coupling" in doc:
            raise ConfigError(f"{source}: [coupling]: not for model = {CHAIN!r}; its stops are "
                              "[[stop]] tables, its phases [system] phi")
        return
    if system.bodies == 1:
        if "coupling" in doc:
            raise ConfigError(f"{source}: [coupling]: only for a pair; [system] bodies = 1 here")
        return
    sec = Section(source, "coupling", doc.get("coupling", {}))
    for param in system.parameters:
        if param.name == "phi":
            values["phi"] = sec.multiple("phi", param.default, "pi", math.pi)
            problem = parameter_problem("phi", values["phi"])
            if problem:
                raise sec.fail("phi", f"{problem}, got {values['phi']!r}")
        elif param.name in ("d", "k_c", "c_c"):
            values[param.name] = sec.number(
                param.name, param.default,
                lambda v, p=param: p.check(v) or parameter_problem(p.name, v))
    law = STOP_LAWS[sec.choice("law", "paper", LAWS)]
    values["law"] = law.name
    for key in LAW_KEYS.values():  # a law's own keys (the Hunt-Crossley exponent)
        if key in law.keys:
            values[key.name] = sec.number(key.name, key.default, key.check)
        elif sec.has(key.name):
            users = " or ".join(repr(lw.name) for lw in STOP_LAWS.values() if key in lw.keys)
            raise sec.fail(key.name, f"only with law = {users}; law is {law.name!r}")
    sec.finish(COUPLING_AXES + ("law",) + tuple(LAW_KEYS))


def _read_integrator(source: str, doc: dict) -> IntegratorSettings:
    sec = Section(source, "integrator", doc.get("integrator", {}))
    d = IntegratorSettings()
    settings = IntegratorSettings(
        method=sec.choice("method", d.method, METHODS),
        steps_per_period=sec.integer("steps_per_period", d.steps_per_period, 4, 1_000_000),
        locate_switches=sec.boolean("locate_switches", d.locate_switches),
        rtol=sec.number("rtol", d.rtol,
                        lambda v: None if 1e-14 <= v < 1 else "must be in [1e-14, 1)"),
        atol=sec.number("atol", d.atol, positive),
        max_periods=sec.integer("max_periods", d.max_periods, 1, 10_000_000),
        max_orbit_period=sec.integer("max_orbit_period", d.max_orbit_period, 1, 1000),
        convergence_tol=sec.number("convergence_tol", d.convergence_tol, positive),
        capture_tol=sec.number("capture_tol", d.capture_tol,
                               lambda v: None if 0 <= v <= 0.1 else "must be in [0, 0.1]"),
        capture_hits=sec.integer("capture_hits", d.capture_hits, 1, 1000),
        cell_size=sec.number("cell_size", d.cell_size,
                             lambda v: None if v >= 0 else "must be >= 0 (0: no cells)"),
        cell_hits=sec.integer("cell_hits", d.cell_hits, 1, 1000),
        divergence_bound=sec.number("divergence_bound", d.divergence_bound, positive),
        max_steps_per_period=sec.integer("max_steps_per_period", d.max_steps_per_period, 10,
                                         100_000_000),
        max_switches_per_period=sec.integer("max_switches_per_period",
                                            d.max_switches_per_period, 2, 100_000_000),
        section_periods=sec.integer("section_periods", d.section_periods, 0, 10_000_000),
        section_cell=sec.number("section_cell", d.section_cell, positive),
        section_recurrences=sec.integer("section_recurrences", d.section_recurrences, 1,
                                        1_000_000),
        section_locate=sec.integer("section_locate", d.section_locate, 10, 1_000_000),
        section_max_period=sec.integer("section_max_period", d.section_max_period, 1, 999),
        section_lyapunov_periods=sec.integer("section_lyapunov_periods",
                                             d.section_lyapunov_periods, 10, 10_000_000),
        section_zero_exponent=sec.number("section_zero_exponent", d.section_zero_exponent,
                                         positive),
    )
    sec.finish()
    return settings


def scene_stem(source: str) -> str:
    """The name a result takes from its scene: the file's stem, "scene" for a scene given
    as text or a mapping (source "<string>", "<dict>")."""
    return "scene" if source.startswith("<") else Path(source).stem


def _read_output(source: str, doc: dict, base: Path) -> Path:
    """[output] path; a value ending in "/" names a directory: the result is then
    ``<directory>/<scene stem>.h5`` (``path = "newdir/"`` writes newdir/<stem>.h5)."""
    sec = Section(source, "output", doc.get("output", {}))
    stem = scene_stem(source)
    value = sec.raw("path", f"results/{stem}.h5")
    if not isinstance(value, str) or not value:
        raise sec.fail("path", f"must be a file path string, got {value!r}")
    sec.finish(("path",))
    try:
        return output_path(value, stem)
    except ValueError as exc:
        raise sec.fail("path", str(exc)) from None


SECTIONS = ("system", "coupling", "integrator", "analysis", "output", "grid",
            "initial_conditions", "catalogue", "verification", *TABLES)


def copy_sections(doc: Mapping[str, Any]) -> dict[str, Any]:
    """A scene's sections, copied: a table as a dict, an array of tables ([[stop]]) as a
    list of dicts."""
    return {name: [dict(t) for t in body] if isinstance(body, list) else dict(body)
            for name, body in doc.items()}


def read_common(text: str, source: str = "<string>"
                ) -> tuple[dict, str, System, dict[str, Any], IntegratorSettings, SceneContext]:
    """The sections every scene has, validated: (TOML document, scene text, system,
    parameter values, integrator settings, the context a kind reads its sections with).
    The method's default waits for the grid (``settle_method``)."""
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{source}: invalid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses once per nested array or inline table
        raise ConfigError(f"{source}: tables or arrays nested too deeply; at most "
                          f"{MAX_NESTING} levels") from None
    check_nesting(source, doc)
    for name in doc:
        if name in TABLES:  # arrays of tables ([[stop]]), read with the chain
            continue
        if name not in SECTIONS or not isinstance(doc[name], dict):
            hint = did_you_mean(name, SECTIONS)
            what = "unknown section" if name not in SECTIONS else "must be a table"
            raise ConfigError(f"{source}: [{name}]: {what}{hint}; sections: "
                              f"{', '.join(SECTIONS)}")
    system, values = _read_system(source, doc)
    _read_coupling(source, doc, system, values)
    integrator = _read_integrator(source, doc)
    if system.dim > MAX_CELL_DIM and "cell_size" not in doc.get("integrator", {}):
        integrator = replace(integrator, cell_size=0.0)  # the default where cells cannot go
    if integrator.cell_size > 0.0 and system.dim > MAX_CELL_DIM:
        raise ConfigError(f"{source}: [integrator] cell_size: recurrence cells hold states of "
                          f"at most {MAX_CELL_DIM} variables, this system has {system.dim}; "
                          "use cell_size = 0")
    period = forcing_period(values)
    ctx = SceneContext(source, doc, system, values, period,
                       lambda axis, v: _check_axis(system, axis, v, period))
    return doc, text, system, values, integrator, ctx


def settle_method(source: str, doc: dict, text: str, system: System, values: dict[str, Any],
                  grid: Grid | None, integrator: IntegratorSettings
                  ) -> tuple[IntegratorSettings, str]:
    """(integrator, scene text) once the scene's grid is known: the default method chosen
    over every parameter point it runs ("exact" where all allow it, said in the text),
    and "exact" checked at each of them."""
    points = _parameter_points(values, grid)
    integrator = _default_method(doc, system, points, integrator)
    if integrator.traits.closed_form and "method" not in doc.get("integrator", {}):
        # said in the text: its hash (resume, caches) then tells the runs apart from
        # those made when the default was "auto"
        text += ('\n# [integrator] method = "exact": the default for a piecewise-linear '
                 "system (no method, rtol or atol set)\n")
    if integrator.traits.closed_form:
        _check_exact(source, system, points, integrator)
    if system.extra.get("rigid") and not integrator.locate_switches:
        raise ConfigError(f"{source}: [integrator] locate_switches: a rigid stop's impacts "
                          "are located events; locate_switches = false is for soft stops")
    return integrator, text


def read_output(source: str, doc: dict) -> Path:
    """[output] path of a scene (see ``_read_output``)."""
    return _read_output(source, doc, Path("."))


def _parameter_points(values: dict, grid: Grid | None) -> list[dict]:
    """The scene's parameter values at each point of a grid that sweeps model parameters
    besides the coupling (``Grid.parameters``), else the scene's values alone."""
    if grid is None or not grid.parameters:
        return [values]
    seen = {tuple(grid.point(i)[a] for a in grid.parameters) for i in range(grid.size)}
    return [{**values, **dict(zip(grid.parameters, key, strict=True))} for key in sorted(seen)]


def _default_method(doc: dict, system, points: list[dict], integrator: IntegratorSettings
                    ) -> IntegratorSettings:
    """A scene that names no method and no tolerance integrates a piecewise-linear system
    (the bilinear models with a linear stop law) on its exact flow, else with "auto";
    ``points``: the parameter values of every point it runs (all must allow it)."""
    chosen = doc.get("integrator", {})
    if any(k in chosen for k in ("method", "rtol", "atol")) or not integrator.locate_switches:
        return integrator
    if not system.piecewise_linear:
        return integrator

    if any(exact_refusal(system, system.pack(values)) is not None for values in points):
        return integrator
    return replace(integrator, method="exact")


def _check_exact(source: str, system, points: list[dict],
                 integrator: IntegratorSettings) -> None:
    """Method 'exact' integrates piecewise-linear systems only, switches located, at
    every parameter point of the scene."""
    if not integrator.locate_switches:
        raise ConfigError(f"{source}: [integrator] method = \"exact\" locates every switch; "
                          "locate_switches = false is for rk4 (the study's plain scheme)")
    for values in points:
        why = exact_refusal(system, system.pack(values)) if system.piecewise_linear else (
            f"the {system.model} model is not piecewise linear")
        if why is not None:
            varying = [k for k in values if any(p[k] != values[k] for p in points)]
            at = (" at the grid point " + ", ".join(f"{k} = {values[k]:g}" for k in varying)
                  if varying else "")
            raise ConfigError(f"{source}: [integrator] method = \"exact\": {why}{at}; use "
                              "\"auto\"")


def _check_axis(system: System, axis: str, value: float, period: float) -> str | None:
    """What is wrong with ``value`` on the grid or design ``axis``, or None."""
    if axis == "t0":
        if value < 0:
            return "must be >= 0"
        return t0_problem(value, period)
    for param in system.parameters:
        if param.name == axis:
            return param.check(value) or parameter_problem(axis, value)
    if axis in LAW_KEYS:  # a stop law's own key (the Hunt-Crossley exponent)
        return LAW_KEYS[axis].check(value)
    return None


QUICK_PLANE = 24  # --quick: largest plane resolution per axis
QUICK_SAMPLES = 100  # --quick: largest number of random samples
QUICK_AXIS = 6  # --quick: largest number of values per swept grid axis (maps, sweeps)


def thin(values: tuple[float, ...], most: int) -> tuple[float, ...]:
    """At most ``most`` of ``values``, evenly spread, the first and last always kept."""
    if len(values) <= most:
        return values
    keep = np.unique(np.round(np.linspace(0, len(values) - 1, most)).astype(int))
    return tuple(values[i] for i in keep)


def result_path(scene: Scene, option: str | None) -> Path:
    """The result file of a run: ``option`` (``-o``) when given, else [output] path.

    As in [output] path, a value ending in "/" names a directory, and the result is
    ``<directory>/<scene stem>.h5``.
    """
    if option is None:
        return scene.output
    stem = scene_stem(scene.source)
    try:
        return output_path(option, stem)
    except ValueError as exc:
        raise ConfigError(f"-o/--output: {exc}") from None


def read_scene_file(path: str | os.PathLike) -> str:
    """The text of the scene file at ``path``; ConfigError naming it when it cannot be read."""
    path = Path(path)
    try:
        return path.read_text()
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such scene file") from None
    except IsADirectoryError:
        raise ConfigError(f"{path}: is a directory, not a scene file") from None
    except (OSError, UnicodeDecodeError) as exc:
        reason = getattr(exc, "strerror", None) or exc.__class__.__name__
        raise ConfigError(f"{path}: cannot read scene file ({reason})") from None
