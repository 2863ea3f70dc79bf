"""What a kind declares: :class:`AnalysisKind`, its :class:`PlotSpec` and options, and the
readers kinds share.

A hook of a kind (``run``, ``summary``, ``compare``...) is a function or a
``"module:function"`` string, imported when first called: the registry is read by every
command (``--help`` lists the kinds) and must not import the analyses, the store or
matplotlib that a kind's hooks use.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from typing import Any

from ..config.limits import t0_problem
from ..config.reader import Section
from ..config.scene import SceneContext, forcing_period
from ..systems import System

__all__ = ["HOOKS", "AnalysisKind", "PlotOption", "PlotSpec", "SceneContext", "Sections",
           "forcing_period", "hook", "read_state", "read_t0"]

# the fields of AnalysisKind that may be "module:function" strings
HOOKS = ("read", "plan", "sections", "shrink", "run", "check", "summary", "report", "info_lines",
         "info_after", "outcome_counts", "compare", "compare_text")


class _Deferred:
    """A ``"module:function"`` hook, imported when first called."""

    def __init__(self, target: str):
        self.target = target
        self._function: Callable[..., Any] | None = None

    def __call__(self, *args, **kwargs):
        if self._function is None:
            self._function = hook(self.target)
        return self._function(*args, **kwargs)

    def __repr__(self) -> str:
        return f"<hook {self.target}>"


def hook(target: str) -> Callable[..., Any]:
    """The function a ``"module:function"`` string names (imported now)."""
    module, _, name = target.partition(":")
    return getattr(importlib.import_module(module), name)


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
        against free memory and disk space before the run (``config.space``)
    plot : its figure (``softimpact plot <kind>``), a PlotSpec
    keys : what each of its ``[analysis]`` keys means (the scene-key reference)
    example : its minimal commented scene (``softimpact example <kind>``; None: the
        study's kinds keep theirs in ``config.examples``)
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
    report: Callable[[Any], str] | None = None
    info_lines: Callable[[Any], list[str]] | None = None
    info_after: Callable[[Any], list[str]] | None = None
    outcome_counts: Callable[[Any], tuple[int, int, int] | None] | None = None
    compare: Callable[..., dict] | None = None
    compare_text: Callable[[dict, int], list[str]] | None = None
    result_bytes: Callable[[Any], int] | None = None
    variables: tuple[str, ...] = ()
    info_catalogue: bool = True
    progress_unit: str = "steps"
    options: tuple[str, ...] = field(default=())  # run options it takes (workers, ...)
    # its [analysis] keys: name -> meaning (the scene-key reference is generated from the
    # reader and these; tests/docs/test_key_reference.py fails on a key without one)
    keys: Mapping[str, str] = field(default_factory=dict)
    plot: PlotSpec | None = None
    example: str | None = None

    def __post_init__(self) -> None:
        for f in fields(self):  # "module:function" hooks: imported when first called
            value = getattr(self, f.name)
            if f.name in HOOKS and isinstance(value, str):
                object.__setattr__(self, f.name, _Deferred(value))

    def figure_function(self) -> Callable[..., Any]:
        """The function drawing a result of this kind (see PlotSpec.draw)."""
        return hook(self.plot.draw or f"softimpact_cli.plot:{self.name}")

    @property
    def sweep(self) -> bool:
        """Chunked, resumable: every initial condition at every grid point."""
        return self.run is None



# ---------------------------------------------------------------- readers kinds share


def read_t0(sec: Section, period: float) -> float:
    """[analysis] t0: a time in T-multiples, at most MAX_T0_PERIODS periods from 0."""
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


def read_start(sec: Section, system: System, starts: tuple[str, ...], *, at: str = "",
               unused: str = "") -> tuple[str, tuple[float, ...] | None]:
    """[analysis] start (one of ``starts``, the first the default) and, with start =
    'state', its required state (``read_state``); a state with start = 'catalogue' is an
    error. ``at`` ends the missing-state message (" at t = 0"), ``unused`` the
    unused-state one (" (why)")."""
    start = sec.choice("start", starts[0], starts)
    if start == "state":
        if not sec.has("state"):
            raise sec.fail("state", f"is required with start = 'state': the initial "
                                    f"{', '.join(system.state_names)}{at}")
        return start, read_state(sec, "state", system)
    if sec.has("state"):
        raise sec.fail("state", f"not used with start = 'catalogue'{unused}")
    return start, None
