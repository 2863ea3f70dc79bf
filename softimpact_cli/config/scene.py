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
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..expressions import parse_multiple
from ..systems import LAWS, MODELS, System, get_system
from .limits import (
    MAX_NESTING,
    MAX_SEED,
    MAX_TRAJECTORIES,
    MAX_TRAJECTORY_SAMPLES,
    check_nesting,
    design_trajectories,
    parameter_problem,
    t0_problem,
)
from .reader import ConfigError, Section, did_you_mean, output_path, positive
from .sweep import (
    CatalogueSettings,
    Grid,
    InitialConditions,
    read_box,
    read_catalogue,
    read_grid,
    read_initial_conditions,
)

ANALYSIS_KINDS = ("trajectory", "catalogue", "basins", "stability", "dcrit", "bifurcation",
                  "map", "design")
SWEEP_KINDS = ("basins", "stability", "map")
METHODS = ("auto", "rk4", "dopri5", "rodas4", "stiff")


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
    cell_size: float = 0.0
    cell_hits: int = 8
    divergence_bound: float = 1e6
    max_steps_per_period: int = 200_000
    max_switches_per_period: int = 10_000

    @property
    def resolved_method(self) -> str:
        """The kernel method the run uses ('stiff' is the L-stable Rodas4; 'auto' runs the
        adaptive explicit pair and switches to Rodas4 where its step is stability bound)."""
        return {"stiff": "rodas4"}.get(self.method, self.method)


@dataclass(frozen=True)
class TrajectoryAnalysis:
    """[analysis] kind = "trajectory": one trajectory, recorded and classified."""

    kind: str
    state: tuple[float, ...]
    periods: int = 200
    t0: float = 0.0
    samples_per_period: int = 64


@dataclass(frozen=True)
class CatalogueAnalysis:
    """[analysis] kind = "catalogue": the one-body attractors (and a pair's combinations).

    Initial conditions: a ``grid`` x ``grid`` lattice plus ``random`` uniform samples over
    ``box`` (x and v ranges), imposed at ``t0``.
    """

    kind: str
    box: Mapping[str, tuple[float, float]]
    grid: int = 16
    random: int = 200
    seed: int = 0
    t0: float = 0.0
    match_tol: float = 1e-3


@dataclass(frozen=True)
class CriticalDistanceAnalysis:
    """[analysis] kind = "dcrit": d_crit(phi) of every combination, at the phi values of
    [grid] (default 256 points over [0, 2 pi)), plus x1 - x2 traces at ``traces``."""

    kind: str
    phis: tuple[float, ...]
    traces: tuple[float, ...] = ()
    samples: int = 512


@dataclass(frozen=True)
class BifurcationAnalysis:
    """[analysis] kind = "bifurcation": follow solutions as d moves from ``start`` to
    ``stop`` by ``step`` (each step from the previous end state); ``branches`` names the
    solutions to follow (default: every combination of the catalogue)."""

    kind: str
    start: float
    stop: float
    step: float
    branches: tuple[str, ...] = ()


@dataclass(frozen=True)
class SweepAnalysis:
    """[analysis] kind = "basins" | "stability": every initial condition of
    [initial_conditions] at every point of [grid], classified and labelled."""

    kind: str
    label_tol: float = 1e-3


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

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()


# ---------------------------------------------------------------- sections


def _read_system(source: str, doc: dict) -> tuple[System, dict[str, Any]]:
    sec = Section(source, "system", doc.get("system", {}))
    model = sec.choice("model", None, MODELS) if sec.has("model") else None
    if model is None:
        raise sec.fail("model", f"is required; one of {', '.join(map(repr, MODELS))}")
    bodies = sec.integer("bodies", 2, 1, 2)
    system = get_system(model, bodies)
    body_params = [p for p in system.parameters if p.name not in ("d", "phi", "k_c", "c_c")]
    values: dict[str, Any] = {}
    for param in body_params:
        values[param.name] = sec.number(
            param.name, param.default,
            lambda v, p=param: p.check(v) or parameter_problem(p.name, v))
    sec.finish(("model", "bodies") + tuple(p.name for p in body_params))
    return system, values


def _read_coupling(source: str, doc: dict, system: System, values: dict[str, Any]) -> None:
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
    values["law"] = sec.choice("law", "paper", LAWS)
    sec.finish(("d", "phi", "k_c", "c_c", "law"))


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
    )
    sec.finish()
    return settings


def _read_state(sec: Section, key: str, system: System) -> tuple[float, ...]:
    value = sec.raw(key)
    names = ", ".join(system.state_names)
    if not isinstance(value, list) or len(value) != system.dim:
        raise sec.fail(key, f"must be a list of {system.dim} numbers ({names}), got {value!r}")
    out = []
    for v in value:
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise sec.fail(key, f"must be a list of {system.dim} finite numbers ({names}), "
                                f"got {value!r}")
        out.append(float(v))
    return tuple(out)


def _read_analysis(source: str, doc: dict, system: System, period: float, values=None):
    sec = Section(source, "analysis", doc.get("analysis", {}))
    kind = sec.choice("kind", "trajectory", ANALYSIS_KINDS)
    if kind == "trajectory":
        if not sec.has("state"):
            raise sec.fail("state", f"is required: the initial {', '.join(system.state_names)}")
        analysis = TrajectoryAnalysis(
            kind=kind,
            state=_read_state(sec, "state", system),
            periods=sec.integer("periods", 200, 1, 10_000_000),
            t0=_read_t0(sec, period),
            samples_per_period=sec.integer("samples_per_period", 64, 1, 100_000),
        )
        samples = analysis.periods * analysis.samples_per_period
        if samples > MAX_TRAJECTORY_SAMPLES:  # the recorded states: samples x dim floats
            raise sec.fail("periods", f"periods x samples_per_period = {samples} recorded "
                                      f"samples; at most {MAX_TRAJECTORY_SAMPLES}")
    elif kind == "catalogue":
        analysis = CatalogueAnalysis(
            kind=kind,
            box=read_box(sec, "box", ("x", "v"), system.extra["catalogue_box"]),
            grid=sec.integer("grid", 16, 0, 2000),
            random=sec.integer("random", 200, 0, 10_000_000),
            seed=sec.integer("seed", 0, 0, MAX_SEED),
            t0=_read_t0(sec, period),
            match_tol=sec.number("match_tol", 1e-3, positive),
        )
        if analysis.grid == 0 and analysis.random == 0:
            raise sec.fail("grid", "grid and random are both 0: no initial conditions")
    elif kind == "dcrit":
        if system.bodies != 2:
            raise sec.fail("kind", "critical distances need a pair ([system] bodies = 2)")
        raw = sec.raw("traces", [])
        if not isinstance(raw, list):
            raise sec.fail("traces", f"must be a list of phases, got {raw!r}")
        traces = []
        for v in raw:
            try:
                traces.append(parse_multiple(v, "pi", math.pi))
            except ValueError as exc:
                raise sec.fail("traces", str(exc)) from None
        analysis = CriticalDistanceAnalysis(kind=kind, phis=(), traces=tuple(traces),
                                            samples=sec.integer("samples", 512, 16, 1_000_000))
    elif kind == "bifurcation":
        if system.bodies != 2:
            raise sec.fail("kind", "bifurcation along d needs a pair ([system] bodies = 2)")
        start = sec.number("start", None)
        stop = sec.number("stop", None)
        step = sec.number("step", None, positive)
        for key, v in (("start", start), ("stop", stop)):
            if _check_axis(system, "d", v, period):
                raise sec.fail(key, f"{_check_axis(system, 'd', v, period)} (a distance d), "
                                    f"got {v!r}")
        if start == stop:
            raise sec.fail("stop", "must differ from start")
        if abs(stop - start) / step > 100_000:
            raise sec.fail("step", f"{abs(stop - start) / step:.0f} steps; at most 100000")
        raw = sec.raw("branches", [])
        if not isinstance(raw, list) or not all(isinstance(b, str) for b in raw):
            raise sec.fail("branches", f"must be a list of names like 'L1^1 R1-0^2', got "
                                       f"{raw!r}")
        from ..labels import parse_label

        for b in raw:
            try:
                if parse_label(b).kind != "pair":
                    raise ValueError(f"{b!r} is not a non-impacting pair solution")
            except ValueError as exc:
                raise sec.fail("branches", str(exc)) from None
        analysis = BifurcationAnalysis(kind, start, stop, step, tuple(raw))
    elif kind == "design":
        if system.bodies != 2:
            raise sec.fail("kind", "a design needs a pair ([system] bodies = 2)")
        from .design import read_design

        analysis = read_design(sec, values, lambda axis, v: _check_axis(system, axis, v, period))
    elif kind in SWEEP_KINDS:
        analysis = SweepAnalysis(kind=kind, label_tol=sec.number("label_tol", 1e-3, positive))
    sec.finish()
    return analysis


def _read_output(source: str, doc: dict, base: Path) -> Path:
    """[output] path; a value ending in "/" names a directory: the result is then
    ``<directory>/<scene stem>.h5`` (``path = "newdir/"`` writes newdir/<stem>.h5)."""
    sec = Section(source, "output", doc.get("output", {}))
    stem = Path(source).stem if source != "<string>" else "scene"
    value = sec.raw("path", f"results/{stem}.h5")
    if not isinstance(value, str) or not value:
        raise sec.fail("path", f"must be a file path string, got {value!r}")
    sec.finish(("path",))
    try:
        return output_path(value, stem)
    except ValueError as exc:
        raise sec.fail("path", str(exc)) from None


SECTIONS = ("system", "coupling", "integrator", "analysis", "output", "grid",
            "initial_conditions", "catalogue")


def parse_scene(text: str, source: str = "<string>") -> Scene:
    """Validate a scene given as TOML text; ``source`` names it in error messages."""
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{source}: invalid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses once per nested array or inline table
        raise ConfigError(f"{source}: tables or arrays nested too deeply; at most "
                          f"{MAX_NESTING} levels") from None
    check_nesting(source, doc)
    for name in doc:
        if name not in SECTIONS or not isinstance(doc[name], dict):
            hint = did_you_mean(name, SECTIONS)
            what = "unknown section" if name not in SECTIONS else "must be a table"
            raise ConfigError(f"{source}: [{name}]: {what}{hint}; sections: "
                              f"{', '.join(SECTIONS)}")
    system, values = _read_system(source, doc)
    _read_coupling(source, doc, system, values)
    integrator = _read_integrator(source, doc)
    period = 2.0 * math.pi / values["w"]
    analysis = _read_analysis(source, doc, system, period, values)
    check = lambda axis, v: _check_axis(system, axis, v, period)  # noqa: E731
    output = _read_output(source, doc, Path("."))
    grid = initial = catalogue = None
    if analysis.kind == "bifurcation":
        catalogue = read_catalogue(source, doc, system.extra["catalogue_box"])
        for name in ("grid", "initial_conditions"):
            if name in doc:
                raise ConfigError(f"{source}: [{name}]: not used by kind 'bifurcation'")
    elif analysis.kind == "dcrit":
        grid_doc = doc.get("grid", {})
        if set(grid_doc) - {"phi"}:
            raise ConfigError(f"{source}: [grid] {sorted(set(grid_doc) - {'phi'})[0]}: "
                              "critical distances sweep phi only")
        if "phi" in grid_doc:
            grid = read_grid(source, doc, values, system.bodies, period, check)
            phis = grid.axes["phi"]
        else:
            phis = tuple(np.linspace(0.0, 2 * np.pi, 256, endpoint=False).tolist())
        from dataclasses import replace as _replace

        analysis = _replace(analysis, phis=phis)
        catalogue = read_catalogue(source, doc, system.extra["catalogue_box"])
    elif analysis.kind == "design":
        if "grid" in doc:
            raise ConfigError(f"{source}: [grid]: not used by kind 'design' (its search box "
                              "is [analysis] bounds)")
        if "initial_conditions" not in doc:
            raise ConfigError(f"{source}: [initial_conditions]: is required for a design "
                              "(kind = \"random\", box, n, seed: the basin-stability samples)")
        ic_kind = doc["initial_conditions"].get("kind", "plane")
        if ic_kind != "random":
            raise ConfigError(f"{source}: [initial_conditions] kind: a design's basin "
                              f"stability needs kind = \"random\", got {ic_kind!r}")
        initial = read_initial_conditions(source, doc, system.state_names, period, False)
        for key in ("screen_n", "robust_n"):
            if (getattr(analysis, key) or 0) > initial.count:
                raise ConfigError(f"{source}: [analysis] {key}: must be <= [initial_conditions]"
                                  f" n = {initial.count}, got {getattr(analysis, key)}")
        total = design_trajectories(analysis, initial.count)
        if total > MAX_TRAJECTORIES:
            raise ConfigError(f"{source}: [analysis]/[initial_conditions]: the design runs up "
                              f"to {total} trajectories (candidates x screen_n + refine x n + "
                              f"perturbed points x robust_n + n); at most {MAX_TRAJECTORIES}")
        catalogue = read_catalogue(source, doc, system.extra["catalogue_box"])
    elif analysis.kind in SWEEP_KINDS:
        grid = read_grid(source, doc, values, system.bodies, period, check)
        initial = read_initial_conditions(source, doc, system.state_names, period,
                                          "t0" in grid.swept)
        total = grid.size * initial.count
        if total > MAX_TRAJECTORIES:
            raise ConfigError(f"{source}: [grid]/[initial_conditions]: {grid.size} grid points"
                              f" x {initial.count} initial conditions = {total} trajectories; "
                              f"at most {MAX_TRAJECTORIES} trajectories per sweep")
        catalogue = read_catalogue(source, doc, system.extra["catalogue_box"])
    else:
        for name in ("grid", "initial_conditions", "catalogue"):
            if name in doc and not (analysis.kind in ("dcrit", "bifurcation")
                                    and name == "catalogue") and not (
                    analysis.kind == "dcrit" and name == "grid"):
                raise ConfigError(f"{source}: [{name}]: only for the analyses "
                                  f"{', '.join(SWEEP_KINDS)}; kind is {analysis.kind!r}")
    return Scene(source=source, text=text, system=system, values=values,
                 integrator=integrator, analysis=analysis, output=output,
                 sections={k: dict(v) for k, v in doc.items()}, grid=grid,
                 initial_conditions=initial, catalogue=catalogue)


def _check_axis(system: System, axis: str, value: float, period: float) -> str | None:
    """What is wrong with ``value`` on the grid or design ``axis``, or None."""
    if axis == "t0":
        if value < 0:
            return "must be >= 0"
        return t0_problem(value, period)
    for param in system.parameters:
        if param.name == axis:
            return param.check(value) or parameter_problem(axis, value)
    return None


def _read_t0(sec: Section, period: float) -> float:
    """[analysis] t0: a time in T-multiples, at most MAX_T0_PERIODS periods from 0."""
    t0 = sec.multiple("t0", 0.0, "T", period)
    problem = t0_problem(t0, period)
    if problem:
        raise sec.fail("t0", f"{problem}, got {t0!r}")
    return t0


QUICK_PLANE = 24  # --quick: largest plane resolution per axis
QUICK_SAMPLES = 100  # --quick: largest number of random samples
QUICK_AXIS = 6  # --quick: largest number of values per swept grid axis (maps, sweeps)
QUICK_PHIS = 64  # --quick: largest number of phases of a critical-distance curve
QUICK_STEPS = 50  # --quick: largest number of d steps of a bifurcation diagram


def _thin(values: tuple[float, ...], most: int) -> tuple[float, ...]:
    """At most ``most`` of ``values``, evenly spread, the first and last always kept."""
    if len(values) <= most:
        return values
    keep = np.unique(np.round(np.linspace(0, len(values) - 1, most)).astype(int))
    return tuple(values[i] for i in keep)


def quick(scene: Scene, plane: int = QUICK_PLANE, samples: int = QUICK_SAMPLES,
          flag: str = "--quick", axis: int | None = QUICK_AXIS) -> Scene:
    """The scene at lower resolution (CI, previews): planes at most ``plane`` per axis, at
    most ``samples`` random samples and, unless ``axis`` is None, at most ``axis`` values
    per swept grid axis (endpoints kept; explicit panels stay), at most QUICK_PHIS phases
    of a critical-distance curve and QUICK_STEPS steps of a bifurcation diagram. The stored
    scene text says so (its hash differs)."""
    from dataclasses import replace

    ic = scene.initial_conditions
    if ic is not None and ic.kind == "plane":
        ic = replace(ic, resolution=tuple(min(r, plane) for r in ic.resolution))
    elif ic is not None and ic.kind == "random":
        ic = replace(ic, n=min(ic.n, samples))
    grid, analysis = scene.grid, scene.analysis
    note = f"planes at most {plane} x {plane}, at most {samples} random samples"
    if axis is not None:
        note += f", at most {axis} values per swept grid axis"
        if grid is not None and not grid.panels and analysis.kind in SWEEP_KINDS:
            grid = replace(grid, axes={a: _thin(v, axis) if a in grid.swept else v
                                       for a, v in grid.axes.items()})
        if analysis.kind == "dcrit":
            analysis = replace(analysis, phis=_thin(analysis.phis, QUICK_PHIS))
            note += f", at most {QUICK_PHIS} phases"
        elif analysis.kind == "bifurcation":
            span = abs(analysis.stop - analysis.start)
            analysis = replace(analysis, step=max(analysis.step, span / QUICK_STEPS))
            note += f", at most {QUICK_STEPS} steps in d"
    if ic is scene.initial_conditions and grid is scene.grid and analysis is scene.analysis:
        return scene
    return replace(scene, initial_conditions=ic, grid=grid, analysis=analysis,
                   text=scene.text + f"\n# {flag}: {note}\n")


def result_path(scene: Scene, option: str | None) -> Path:
    """The result file of a run: ``option`` (``-o``) when given, else [output] path.

    As in [output] path, a value ending in "/" names a directory, and the result is
    ``<directory>/<scene stem>.h5``.
    """
    if option is None:
        return scene.output
    stem = Path(scene.source).stem if scene.source != "<string>" else "scene"
    try:
        return output_path(option, stem)
    except ValueError as exc:
        raise ConfigError(f"-o/--output: {exc}") from None


def load_scene(path: str | os.PathLike) -> Scene:
    """Read and validate the scene file at ``path``."""
    path = Path(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such scene file") from None
    except IsADirectoryError:
        raise ConfigError(f"{path}: is a directory, not a scene file") from None
    except (OSError, UnicodeDecodeError) as exc:
        reason = getattr(exc, "strerror", None) or exc.__class__.__name__
        raise ConfigError(f"{path}: cannot read scene file ({reason})") from None
    return parse_scene(text, str(path))
