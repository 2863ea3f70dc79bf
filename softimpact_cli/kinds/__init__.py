"""Analysis kinds: one home each, one registry.

Each kind (``[analysis] kind = ...``) is a module of this package declaring an
:class:`AnalysisKind`: its ``[analysis]`` keys and the other sections it reads (the config
side), how ``--quick`` shrinks it, how it runs (a function returning an
``xarray.Dataset``; sweep kinds run through the chunked, resumable ``sweep.runner``), the
plan ``--dry-run`` prints, its ``check`` and its ``info`` summary. The config reader, the
CLI, ``run``, ``check``, ``info`` and the sweep runner look a kind up here; none of them
branches on a kind's name.

Adding a kind: a module here with its settings dataclass and its ``KINDS`` tuple (see
:class:`~.base.AnalysisKind`), its analysis module(s), its figure (named by its
:class:`PlotSpec`), and its line in :data:`REGISTRY`. Nothing else names it: the reader,
``--help``, ``example``, ``run``, ``info``, ``plot`` and ``compare`` ask the registry.

The registry imports a kind's module when the kind is first asked for (``get``,
``KINDS[name]``): a module imports what it runs at its top, and a command that names no
kind (``softimpact --help``) imports none of them.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, Mapping

from ..config.examples import example
from ..config.reader import ConfigError
from .base import (  # noqa: F401  (what a kind declares, named here too)
    AnalysisKind,
    PlotOption,
    PlotSpec,
    SceneContext,
    Sections,
    forcing_period,
    read_state,
    read_t0,
)

# ---------------------------------------------------------------- the registry

# one line per kind, in the order --help and messages list them: its name and the module
# declaring it (a name of this package, or a full module path)
REGISTRY: dict[str, str] = {
    "trajectory": "trajectory",
    "catalogue": "catalogue",
    "basins": "sweeps",
    "stability": "sweeps",
    "dcrit": "dcrit",
    "bifurcation": "bifurcation",
    "map": "sweeps",
    "tipping": "tipping",
    "fatal_shock": "fatal_shock",
    "design": "design",
    "fractality": "fractality",
    "lyapunov": "lyapunov",
    "continuation": "continuation",
    "atlas": "atlas",
}


def _module(name: str):
    module = REGISTRY[name]
    return importlib.import_module(module if "." in module else f"{__name__}.{module}")


class _Kinds(Mapping[str, AnalysisKind]):
    """{name: AnalysisKind} over :data:`REGISTRY`, each module imported when first asked."""

    def __getitem__(self, name: str) -> AnalysisKind:
        if name not in REGISTRY:
            raise KeyError(name)
        for kind in _module(name).KINDS:
            if kind.name == name:
                return kind
        raise LookupError(f"{REGISTRY[name]} declares no kind {name!r}")

    def __iter__(self) -> Iterator[str]:
        return iter(tuple(REGISTRY))

    def __len__(self) -> int:
        return len(REGISTRY)


KINDS: Mapping[str, AnalysisKind] = _Kinds()


def analysis_kinds() -> tuple[str, ...]:
    """Every kind's name, in the registry's order."""
    return tuple(REGISTRY)


def sweep_kinds() -> tuple[str, ...]:
    """The sweep kinds (chunked and resumable: those without a ``run``)."""
    return tuple(name for name in REGISTRY if KINDS[name].sweep)


def __getattr__(name: str):
    # the registry's lists, computed when asked (a toy kind added to REGISTRY shows)
    if name == "ANALYSIS_KINDS":
        return analysis_kinds()
    if name == "SWEEP_KINDS":
        return sweep_kinds()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def example_scene(name: str) -> str:
    """The commented example scene of kind ``name`` (``softimpact example``): the kind's
    own, else the study's in ``config.examples``; KeyError for an unknown kind."""
    kind = KINDS[name]
    return kind.example if kind.example is not None else example(name)


def help_lines(indent: str = "  ") -> list[str]:
    """One line per kind, ``name  description``, in the registry's order (``sweep
    --help``, the README's list)."""
    width = max(len(name) for name in REGISTRY)
    return [f"{indent}{name:{width}s}  {KINDS[name].description}" for name in REGISTRY]


def get(name: str) -> AnalysisKind:
    """The kind called ``name`` (a result's ``analysis`` attribute or a scene's kind)."""
    try:
        return KINDS[name]
    except KeyError:
        raise ConfigError(f"analysis kind {name!r}: unknown; one of "
                          f"{', '.join(analysis_kinds())}") from None
