"""Analysis kinds: one home each, one registry.

Each kind (``[analysis] kind = ...``) is a module of this package declaring an
:class:`AnalysisKind`: its ``[analysis]`` keys and the other sections it reads (the config
side), how ``--quick`` shrinks it, how it runs (a function returning an
``xarray.Dataset``; sweep kinds run through the chunked, resumable ``sweep.runner``), the
plan ``--dry-run`` prints, its ``check`` and its ``info`` summary. The config reader, the
CLI, ``run``, ``check``, ``info`` and the sweep runner look a kind up here; none of them
branches on a kind's name.

Adding a kind: a module here with its settings dataclass and its ``KINDS`` tuple, its
line in :data:`MODULES`, and a figure: ``plot/<kind>_figure.py`` and its function
``plot.<kind>(ds, ax=None)`` in ``plot/__init__.py``, which the kind names in its
:class:`PlotSpec` (the ``softimpact plot <kind>`` command is built from it).
The functions a kind names from later layers (analysis, sweep, store, plot) are imported
when called, so that reading a scene imports no analysis code.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..config.reader import ConfigError, Section
from ..systems import System

# the modules declaring kinds, in the order `--help` lists them
MODULES = ("trajectory", "catalogue", "sweeps", "tipping", "fatal_shock", "dcrit", "bifurcation",
           "design", "fractality", "lyapunov", "continuation")


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


@dataclass(frozen=True)
class Sections:
    """The sections a kind read besides [analysis] (None where it reads none)."""

    analysis: Any
    grid: Any = None
    initial_conditions: Any = None
    catalogue: Any = None


@dataclass(frozen=True)
class PlotOption:
    """A command-line option of ``softimpact plot <kind>``, passed to the figure function
    as the keyword ``keyword``. ``kind``: "int>=1" (a positive integer), "choice"
    (one of ``choices``), "text" or "flag" (present or not)."""

    flag: str
    keyword: str
    help: str
    kind: str = "text"
    default: Any = None
    choices: tuple[str, ...] = ()


@dataclass(frozen=True)
class PlotSpec:
    """How ``softimpact plot <kind>`` draws a result of a kind.

    draw : "module:function" (imported when called; default the figure function
        ``plot.<kind>``), called as ``draw(ds, **options)`` and returning a Figure; it
        raises ConfigError for an option the result cannot honour
    help : the command's help text; options : its PlotOption tuple
    complete : refuse an incomplete result
    accept(attrs) -> bool, expected : which results it draws besides the kind's own
        (``expected`` names them in the refusal)
    """

    help: str
    draw: str | None = None
    options: tuple[PlotOption, ...] = ()
    complete: bool = False
    accept: Callable[[Mapping[str, Any]], bool] | None = None
    expected: str | None = None


@dataclass(frozen=True)
class AnalysisKind:
    """One analysis kind.

    read(sec, ctx) -> settings : the [analysis] keys (``sec.finish()`` follows)
    sections(settings, ctx) -> Sections : [grid], [initial_conditions], [catalogue]
    shrink(settings, grid) -> (settings, grid, note or "") : what ``--quick`` reduces
        beyond planes and samples (the config's ``quick`` does those for every kind)
    run(scene, progress, **options) -> Dataset : None for sweep kinds (``sweep.runner``)
    plan(scene, workers, chunk_size) -> str : the first line of ``--dry-run``
    check(scene, sample, seed, result) -> report : ``softimpact check`` (None: no check)
    summary(ds) -> dict : the kind's part of ``info``
    after_sweep(ds, scene, catalogue) -> Dataset : a sweep kind's extra variables
    report(ds) -> str : what the CLI prints after a run besides the one-line outcome
    info_lines(ds) -> list[str] : lines of ``info`` that only this kind prints (at the top)
    info_after(ds) -> list[str] : such lines after the table of keys
    info_catalogue : ``info`` lists the result's catalogue (a design prints its own)
    outcome_counts(ds) -> (trajectories, unresolved, diverged) or None : for the warnings
        on mostly unresolved or diverged results (None: the kind has no such counts)
    compare(a, b, name_a, name_b) -> dict, compare_text(report, max_points) -> list[str] :
        ``softimpact compare`` of two results of this kind (None: not comparable)
    variables : what every complete result of the kind holds; a file that says it is one
        and lacks them is refused when opened (``api.open_result``)
    result_bytes(scene) -> int : an upper estimate of the result's size (bytes,
        uncompressed) of a kind that is not a sweep (a sweep's plan has its own), checked
        against free memory and disk space before the run (``store.space``)
    needs_attractors : the sweep stops before any chunk when the catalogue is empty
    searches_attractors : runs the attractor search without a [catalogue] section
    plot : its figure (``softimpact plot <kind>``), a PlotSpec
    keys : what each of its ``[analysis]`` keys means (the scene-key reference)
    """

    name: str
    description: str
    read: Callable[[Section, SceneContext], Any]
    plan: Callable[..., str]
    sections: Callable[[Any, SceneContext], Sections] | None = None
    shrink: Callable[[Any, Any], tuple[Any, Any, str]] | None = None
    run: Callable[..., Any] | None = None
    check: Callable[..., dict] | None = None
    summary: Callable[[Any], dict] | None = None
    after_sweep: Callable[..., Any] | None = None
    report: Callable[[Any], str] | None = None
    info_lines: Callable[[Any], list[str]] | None = None
    info_after: Callable[[Any], list[str]] | None = None
    outcome_counts: Callable[[Any], tuple[int, int, int] | None] | None = None
    compare: Callable[..., dict] | None = None
    compare_text: Callable[[dict, int], list[str]] | None = None
    result_bytes: Callable[[Any], int] | None = None
    variables: tuple[str, ...] = ()
    info_catalogue: bool = True
    needs_attractors: bool = False
    searches_attractors: bool = False
    progress_unit: str = "steps"
    options: tuple[str, ...] = field(default=())  # run options it takes (workers, ...)
    # its [analysis] keys: name -> meaning (the scene-key reference is generated from the
    # reader and these; tests/docs/test_key_reference.py fails on a key without one)
    keys: Mapping[str, str] = field(default_factory=dict)
    plot: PlotSpec | None = None

    def figure_function(self) -> Callable[..., Any]:
        """The function drawing a result of this kind (see PlotSpec.draw)."""
        module, _, name = (self.plot.draw or f"softimpact_cli.plot:{self.name}").partition(":")
        return getattr(importlib.import_module(module), name)

    @property
    def sweep(self) -> bool:
        """Chunked, resumable: every initial condition at every grid point."""
        return self.run is None

    def read_sections(self, settings: Any, ctx: SceneContext) -> Sections:
        if self.sections is not None:
            return self.sections(settings, ctx)
        for name in ("grid", "initial_conditions", "catalogue"):
            if name in ctx.doc:
                raise ConfigError(f"{ctx.source}: [{name}]: only for the analyses "
                                  f"{', '.join(SWEEP_KINDS)}; kind is {self.name!r}")
        return Sections(settings)


# ---------------------------------------------------------------- readers kinds share


def forcing_period(values: Mapping[str, Any]) -> float:
    """2 pi / w: the forcing period of a parameter point."""
    return 2.0 * math.pi / float(values["w"])


def read_t0(sec: Section, period: float) -> float:
    """[analysis] t0: a time in T-multiples, at most MAX_T0_PERIODS periods from 0."""
    from ..config.limits import t0_problem

    t0 = sec.multiple("t0", 0.0, "T", period)
    problem = t0_problem(t0, period)
    if problem:
        raise sec.fail("t0", f"{problem}, got {t0!r}")
    return t0


def read_state(sec: Section, key: str, system: System) -> tuple[float, ...]:
    """A state vector: ``system.dim`` finite numbers."""
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


# ---------------------------------------------------------------- the registry


def _load() -> dict[str, AnalysisKind]:
    kinds: dict[str, AnalysisKind] = {}
    for module in MODULES:
        for kind in importlib.import_module(f"{__name__}.{module}").KINDS:
            kinds[kind.name] = kind
    return kinds


_LOADED = _load()
# the order messages and --help list them in; new kinds follow
_ORDER = ("trajectory", "catalogue", "basins", "stability", "dcrit", "bifurcation", "map",
          "tipping", "fatal_shock", "design", "fractality", "lyapunov", "continuation")
KINDS: dict[str, AnalysisKind] = {name: _LOADED[name] for name in _ORDER if name in _LOADED}
KINDS.update({name: kind for name, kind in _LOADED.items() if name not in KINDS})
ANALYSIS_KINDS = tuple(KINDS)
SWEEP_KINDS = tuple(name for name in ANALYSIS_KINDS if KINDS[name].sweep)


def get(name: str) -> AnalysisKind:
    """The kind called ``name`` (a result's ``analysis`` attribute or a scene's kind)."""
    try:
        return KINDS[name]
    except KeyError:
        raise ConfigError(f"analysis kind {name!r}: unknown; one of "
                          f"{', '.join(ANALYSIS_KINDS)}") from None
