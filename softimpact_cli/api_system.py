"""``si.System``: one parameter point of a scene's model, to build with in a notebook.

::

    import softimpact_cli as si

    system = si.System({"system": {"model": "duffing"},
                        "coupling": {"d": 6.0, "phi": 0.0, "k_c": 8.0, "c_c": 10.0}})
    system.classify([8.0, 0.0, -4.0, 0.0])      # Classified(label='L1^1 R1-0^1', period=1, ...)
    system.with_(d=8.0).classify([8.0, 0.0, -4.0, 0.0])   # same kernels, new parameters
    system.catalogue()                           # the attractors: an xarray.Dataset
    system.trajectory([8.0, 0.0, -4.0, 0.0], periods=40)  # as [analysis] kind = "trajectory"

What it is: the model of a scene (``[system]``, ``[coupling]``) at its parameter values,
with the scene's ``[integrator]`` settings and attractor search (``[catalogue]``, or the
settings of a catalogue scene's ``[analysis]``, else the defaults). ``classify`` is the
labelling a sweep does for each initial condition (Attractors.jl's ``mapper(u0)``): the
same kernels, catalogue, capture by known orbits and second stage, so a start gets the
label a basins sweep at these parameters gives it. The parameters travel to the
compiled kernels as a float64 array (``parameter_array``): a System at other values
(``with_``) uses the kernels already compiled.

``softimpact_cli`` imports this module when ``si.System`` is first used (it imports
xarray and the sweep machinery; importing the package does not).

A chaotic or quasi-periodic attractor is numbered per call (``chaotic A1`` is the first
such attractor that call met), as each sweep numbers its own.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Any, NamedTuple

import numpy as np
import xarray as xr

from .analysis.catalogue import catalogue_dataset
from .analysis.engine import Problem
from .analysis.labels import name_of
from .analysis.trajectory import trajectory_dataset
from .api import SceneLike, _handed_out, load_scene
from .config import ConfigError, Scene
from .config.axes import COUPLING_AXES
from .config.limits import MAX_TRAJECTORY_SAMPLES
from .config.sweep import GRID_AXES, CatalogueSettings, Grid, InitialConditions, read_catalogue
from .config.toml_text import toml_text
from .kernels.codes import outcome
from .kinds.catalogue import CatalogueAnalysis
from .kinds.scene import parse_scene
from .kinds.sweeps import SweepAnalysis
from .sweep.chunks import run_chunk
from .sweep.runner import prepare_inputs
from .sweep.second_stage import relabel, unpack


class Classified(NamedTuple):
    """Where one initial condition goes.

    label : the attractor's name, as a sweep's ``label_name`` ("L1^1 R1-0^1",
        "impacting P2", "chaotic A1", "unresolved", "diverged")
    period : its period in forcing periods (0 where it has none)
    outcome : "converged", "unresolved" or "diverged" (the kernels' status)
    code : the integer label code a sweep stores (``kernels.codes``)
    """

    label: str
    period: int
    outcome: str
    code: int


class System:
    """The model of a scene at one parameter point (see the module docstring).

    ``scene``: a Scene, a path, TOML text or a mapping of sections, as
    :func:`softimpact_cli.load_scene` takes. A mapping may be just ``[system]``,
    ``[coupling]``, ``[integrator]`` and ``[catalogue]`` (the attractor search): without
    ``[analysis]`` it is read as a catalogue scene searching with those ``[catalogue]``
    keys. A scene with a grid gives its base values (``[system]``, ``[coupling]``), not
    a grid point. ConfigError (one line) for a scene that is not valid.
    """

    def __init__(self, scene: SceneLike):
        if isinstance(scene, Mapping) and "analysis" not in scene and \
                isinstance(scene.get("catalogue", {}), Mapping):
            scene = {**{k: v for k, v in scene.items() if k != "catalogue"},
                     "analysis": {"kind": "catalogue", **scene.get("catalogue", {})}}
        self._scene = load_scene(scene)
        self._point = _point_scene(self._scene)
        self._inputs = None  # the catalogue and the labelling context, on first use

    # ---------------------------------------------------------------- what it is

    @property
    def scene(self) -> Scene:
        """The validated scene this System was made from (its text says its values)."""
        return self._scene

    @property
    def model(self) -> str:
        return self._scene.system.model

    @property
    def state_names(self) -> tuple[str, ...]:
        """The state's variables, in the order ``u0`` lists them."""
        return tuple(self._scene.system.state_names)

    @property
    def parameters(self) -> Mapping[str, Any]:
        """Every parameter by name (read-only): the model's numbers in the kernels'
        order, then the stop law's name where the model has one."""
        values = self._scene.values
        names = self._scene.system.parameter_names
        out = {name: float(values[name]) for name in names}
        out.update({k: v for k, v in values.items() if k not in out})
        return MappingProxyType(out)

    @property
    def parameter_array(self) -> np.ndarray:
        """The parameters as the compiled kernels receive them: float64, (n,)."""
        packed = self._scene.system.pack(self._scene.values)
        packed.setflags(write=False)
        return packed

    def __repr__(self) -> str:
        numbers = ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                            for k, v in self.parameters.items())
        return f"System({self.model}, {self._scene.system.bodies} bodies: {numbers})"

    # ---------------------------------------------------------------- other values

    def with_(self, **changes: float) -> System:
        """A new System with the parameters ``changes`` (e.g. ``d=8.0``), checked as
        the scene's keys are (the same one-line ConfigError); this one is unchanged.
        Nothing is compiled again: the kernels take the parameters as an array."""
        self._preset_only("with_")
        sections = {name: dict(body) for name, body in self._scene.sections.items()}
        system_keys = set(self._scene.system.parameter_names) - set(COUPLING_AXES)
        for name, value in changes.items():
            if name in COUPLING_AXES or name in self._scene.values and name not in system_keys:
                section = "coupling"
            elif name in system_keys:
                section = "system"
            else:
                known = ", ".join(self.parameters)
                raise ConfigError(f"with_: {name}: not a parameter of this "
                                  f"{self.model} system; one of {known}")
            if isinstance(value, np.generic):
                value = value.item()
            sections.setdefault(section, {})[name] = value

        source = str(self._scene.source)
        return System(parse_scene(toml_text(sections, source), source))

    # ---------------------------------------------------------------- computing

    def catalogue(self) -> xr.Dataset:
        """The attractors of one body and (for a pair) the combinations at these values:
        the dataset of ``[analysis] kind = "catalogue"`` with this scene's search
        settings (found once per System and kept)."""

        inputs = self._labelling()
        return _handed_out(catalogue_dataset(inputs.first, self._scene.system,
                                             self._scene.integrator))

    def classify(self, u0, t0: float = 0.0) -> Classified:
        """The label and period of the initial state ``u0`` (``state_names`` order)
        imposed at time ``t0``, as a basins sweep at these values labels it."""

        state = self._state(u0, "u0")
        t0 = _finite(t0, "t0")
        inputs = self._labelling()
        context = replace(inputs.context, states=state[None, :], t0=np.array([t0]))
        out = run_chunk(context, 0, 1)
        recurrent = unpack(out)
        if recurrent:  # followed on the section: a chaotic or quasi-periodic attractor
            relabel(context, out["label"], out["orbits"], recurrent, self.state_names)
        code = int(out["label"][0])
        return Classified(name_of(code, inputs.names), int(out["period"][0]),
                          outcome(int(out["status"][0])), code)

    def trajectory(self, u0, periods: int = 200, t0: float = 0.0,
                   samples_per_period: int = 64) -> xr.Dataset:
        """``periods`` forcing periods from ``u0`` at ``t0``, recorded densely
        (``samples_per_period``) and classified: the dataset of ``[analysis] kind =
        "trajectory"`` (``si.plot.trajectory`` draws it)."""

        state = self._state(u0, "u0")
        periods = _whole(periods, "periods")
        samples_per_period = _whole(samples_per_period, "samples_per_period")
        if periods * samples_per_period > MAX_TRAJECTORY_SAMPLES:
            raise ConfigError(f"trajectory: periods x samples_per_period = "
                              f"{periods * samples_per_period} recorded samples; at most "
                              f"{MAX_TRAJECTORY_SAMPLES}")
        sc = self._scene
        problem = Problem(sc.system, sc.values, sc.integrator)
        return _handed_out(trajectory_dataset(problem, state, _finite(t0, "t0"), periods,
                                              samples_per_period))

    # ---------------------------------------------------------------- helpers

    def _preset_only(self, what: str) -> None:
        """One line for what a chain (model = "chain") cannot do here yet."""
        if self._scene.system.model == "chain":
            raise ConfigError(f"System.{what}: not yet for model = \"chain\" (the "
                              "Python System holds a preset's scene; a chain's scene runs "
                              "its catalogue and sweeps through softimpact sweep); "
                              "trajectory() works")

    def _labelling(self):
        """The sweep's inputs at this point (catalogue, names, workers' context)."""
        self._preset_only("catalogue and classify")
        if self._inputs is None:
            self._inputs = prepare_inputs(self._point)
        return self._inputs

    def _state(self, u0, name: str) -> np.ndarray:
        try:
            state = np.asarray(u0, dtype=float)
        except (TypeError, ValueError):
            state = None
        dim = len(self.state_names)
        if state is None or state.shape != (dim,) or not np.all(np.isfinite(state)):
            raise ConfigError(f"{name}: must be {dim} finite numbers "
                              f"({', '.join(self.state_names)}), got {u0!r}")
        return state


def _point_scene(scene: Scene) -> Scene:
    """``scene`` as a basins sweep of one grid point (its values) over one listed state:
    what ``System.classify`` labels with (the states are replaced per call)."""
    values = {**scene.values, "t0": 0.0}
    grid = Grid({a: (float(values.get(a, 0.0)),) for a in GRID_AXES}, ())
    ic = InitialConditions(kind="list", state_names=tuple(scene.system.state_names),
                           states=(tuple(0.0 for _ in scene.system.state_names),), t0=0.0)
    catalogue = scene.catalogue
    a = scene.analysis
    if catalogue is None and isinstance(a, CatalogueAnalysis):  # its own search settings
        catalogue = CatalogueSettings(box=a.box, grid=a.grid, random=a.random, seed=a.seed,
                                      match_tol=a.match_tol)
    if catalogue is None:
        catalogue = read_catalogue(str(scene.source), {},
                                   scene.system.extra["catalogue_box"])
    analysis = SweepAnalysis("basins", getattr(a, "label_tol", 1e-3))
    return replace(scene, grid=grid, initial_conditions=ic, analysis=analysis,
                   catalogue=catalogue)


def _finite(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.number) or \
            not math.isfinite(float(value)):
        raise ConfigError(f"{name}: must be a finite number, got {value!r}")
    return float(value)


def _whole(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ConfigError(f"{name}: must be a whole number >= 1, got {value!r}")
    return int(value)
