"""Scenes: a TOML file becomes a validated, frozen :class:`~softimpact_cli.config.Scene`.

``config`` reads the sections every scene has ([system], [coupling], [integrator],
[output]) and knows no kind; here the scene's kind (the registry) reads [analysis] and
the sections it uses ([grid], [initial_conditions], [catalogue], [verification]), and
``quick`` asks the kind what ``--quick`` reduces.
"""

from __future__ import annotations

import os
from dataclasses import replace

from ..config.chain_scene import CHAIN
from ..config.reader import ConfigError, Section
from ..config.scene import (
    QUICK_AXIS,
    QUICK_PLANE,
    QUICK_SAMPLES,
    Scene,
    SceneContext,
    copy_sections,
    read_common,
    read_output,
    read_scene_file,
    settle_method,
)
from ..config.verification import VerificationSettings, read_verification
from . import KINDS, sweep_kinds
from .base import AnalysisKind, Sections

__all__ = ["load_scene", "parse_scene", "quick"]


def _read_analysis(sec: Section, ctx: SceneContext):
    """The [analysis] keys of the scene's kind (each kind reads its own)."""
    kind = sec.choice("kind", "trajectory", tuple(KINDS))  # the registry, at call time
    if ctx.system.model == CHAIN:
        refusal = chain_refusal(kind, ctx.doc)
        if refusal:
            raise ConfigError(f"{ctx.source}: [analysis] kind = {kind!r}: {refusal}")
    analysis = KINDS[kind].read(sec, ctx)
    sec.finish()
    return analysis


# What a chain (model = "chain", systems/chain.py) can run today, and why the others cannot
# yet: said in one line when the scene is read, before anything runs.
CHAIN_KINDS = ("trajectory", "lyapunov", "dcrit", "bifurcation", "catalogue", "basins",
               "stability", "map", "continuation", "fractality", "fatal_shock", "tipping",
               "design")
CHAIN_REFUSALS = {
    "atlas": ("it seeds its bifurcation curves from a pair's combinations and continues "
              "them in two of the pair's parameters; on a chain, kind \"continuation\" "
              "finds the folds, period doublings and Neimark-Sacker points of its orbits "
              "along any one parameter by name, kind \"dcrit\" where a stop starts to touch "
              "each non-impacting product (its grazing) against any parameter, kind "
              "\"design\" where only one product survives, and kind \"map\" which "
              "attractors coexist over two parameters"),
}


def chain_refusal(kind: str, doc: dict) -> str | None:
    """Why ``kind`` cannot run on a chain (None: it can)."""
    if kind not in CHAIN_KINDS:
        why = CHAIN_REFUSALS.get(kind, "it is written for the presets")
        return (f"not yet for model = \"chain\" ({why}); a chain runs kind "
                + " or ".join(map(repr, CHAIN_KINDS)))
    return None


def _read_sections(kind: AnalysisKind, settings, ctx: SceneContext) -> Sections:
    """[grid], [initial_conditions], [catalogue] as the kind reads them (refused when it
    reads none)."""
    if kind.sections is not None:
        return kind.sections(settings, ctx)
    for name in ("grid", "initial_conditions", "catalogue"):
        if name in ctx.doc:
            raise ConfigError(f"{ctx.source}: [{name}]: only for the analyses "
                              f"{', '.join(sweep_kinds())}; kind is {kind.name!r}")
    return Sections(settings)


def _read_verification(source: str, doc: dict, kind: str) -> VerificationSettings | None:
    """[verification] of a sweep kind (its defaults when absent); refused elsewhere."""
    if KINDS[kind].sweep:
        return read_verification(source, doc)
    if "verification" in doc:
        raise ConfigError(f"{source}: [verification]: only for the analyses "
                          f"{', '.join(sweep_kinds())} (sweeps of labelled trajectories); "
                          f"kind is {kind!r}")
    return None


def parse_scene(text: str, source: str = "<string>") -> Scene:
    """Validate a scene given as TOML text; ``source`` names it in error messages."""
    doc, text, system, values, integrator, ctx = read_common(text, source)
    analysis = _read_analysis(Section(source, "analysis", doc.get("analysis", {})), ctx)
    output = read_output(source, doc)
    read = _read_sections(KINDS[analysis.kind], analysis, ctx)
    analysis, grid = read.analysis, read.grid
    initial, catalogue = read.initial_conditions, read.catalogue
    integrator, text = settle_method(source, doc, text, system, values, grid, integrator)
    return Scene(source=source, text=text, system=system, values=values,
                 integrator=integrator, analysis=analysis, output=output,
                 sections=copy_sections(doc), grid=grid,
                 initial_conditions=initial, catalogue=catalogue,
                 verification=_read_verification(source, doc, analysis.kind))


def load_scene(path: str | os.PathLike) -> Scene:
    """Read and validate the scene file at ``path``."""
    return parse_scene(read_scene_file(path), str(path))


def quick(scene: Scene, plane: int = QUICK_PLANE, samples: int = QUICK_SAMPLES,
          flag: str = "--quick", axis: int | None = QUICK_AXIS) -> Scene:
    """The scene at lower resolution (CI, previews): planes at most ``plane`` per axis, at
    most ``samples`` random samples and, unless ``axis`` is None, at most ``axis`` values
    per swept grid axis (endpoints kept; explicit panels stay), and what the kind's
    ``shrink`` reduces (phases of a d_crit curve, steps of a bifurcation diagram). The
    stored scene text says so (its hash differs)."""
    ic = scene.initial_conditions
    if ic is not None and ic.kind == "plane":
        ic = replace(ic, resolution=tuple(min(r, plane) for r in ic.resolution))
    elif ic is not None and ic.kind == "random":
        ic = replace(ic, n=min(ic.n, samples))
    grid, analysis = scene.grid, scene.analysis
    note = f"planes at most {plane} x {plane}, at most {samples} random samples"
    if axis is not None:
        note += f", at most {axis} values per swept grid axis"
        shrink = KINDS[analysis.kind].shrink
        if shrink is not None:
            analysis, grid, more = shrink(analysis, grid, axis)
            note += more
    if ic is scene.initial_conditions and grid is scene.grid and analysis is scene.analysis:
        return scene
    return replace(scene, initial_conditions=ic, grid=grid, analysis=analysis,
                   text=scene.text + f"\n# {flag}: {note}\n")
