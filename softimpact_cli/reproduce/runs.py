"""The runs the study's statements need: a figure scene of configs/figures/, optionally
changed (start phase t0, integrator, contact law, resolution), run once and cached.

A run's cache file is ``<cache>/<name>-<sha256 of the scene text, 12 hex>.h5``: a run of
the same scene text is reused, a changed scene gets a new file, and an interrupted sweep
resumes from its chunk files (``sweep.run_sweep(resume=True)``).
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import xarray as xr

from ..config import Scene
from ..kinds import get as kind_of
from ..kinds.run import run_scene
from ..kinds.scene import parse_scene, quick
from ..store import open_result, write_result
from ..sweep import run_sweep

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
CACHE = ROOT / "results" / "reproduce"
QUICK_PLANE = 24  # --quick: basin planes at most 24 x 24
QUICK_SAMPLES = 100  # --quick: at most 100 random samples per point


def _literal(value) -> str:
    """A TOML literal of a number, string, bool or list of them."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_literal(v)}" for k, v in value.items()) + " }"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_literal(v) for v in value) + "]"
    return repr(value)


def with_key(text: str, section: str, key: str, value) -> str:
    """``text`` (a scene) with ``[section] key = value``: the key's line replaced when the
    section has it, else added after the section's header, else a new section at the end."""
    line = f"{key} = {_literal(value)}"
    lines = text.splitlines()
    header = f"[{section}]"
    try:
        start = next(i for i, s in enumerate(lines) if s.strip() == header)
    except StopIteration:
        return text.rstrip("\n") + f"\n\n{header}\n{line}\n"
    end = next((i for i in range(start + 1, len(lines)) if lines[i].lstrip().startswith("[")
                and not lines[i].lstrip().startswith("[[") and "=" not in lines[i]),
               len(lines))
    pattern = re.compile(rf"^\s*{re.escape(key)}\s*=")
    for i in range(start + 1, end):
        if pattern.match(lines[i]):
            lines[i] = line
            return "\n".join(lines) + "\n"
    lines.insert(start + 1, line)
    return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class Run:
    """A scene of configs/ (path relative to it) and the keys changed in it: ``changes``
    is a tuple of (section, key, value)."""

    name: str
    scene_file: str
    changes: tuple[tuple[str, str, object], ...] = ()
    note: str = ""
    heavy: bool = field(default=False)
    stand_in: str = ""  # a cheaper run (lower resolution) a table may use while this one
    #                     is not made (--cached-only), saying so in the rows

    def text(self) -> str:
        text = (CONFIGS / self.scene_file).read_text()
        for section, key, value in self.changes:
            text = with_key(text, section, key, value)
        return text

    def scene(self, quick_run: bool = False) -> Scene:
        """The scene; ``quick_run`` shrinks the sweeps (basins, stability) only: the
        catalogues, critical distances and bifurcation diagrams take seconds at full size,
        and their statements name phases and steps a thinned grid would miss."""
        scene = parse_scene(self.text(), f"{self.name} ({self.scene_file})")
        if quick_run and kind_of(scene.analysis.kind).sweep:
            return quick(scene, plane=QUICK_PLANE, samples=QUICK_SAMPLES, axis=None)
        return scene

    def command(self) -> str:
        """The shell command that makes the same result by hand."""
        base = f"softimpact sweep configs/{self.scene_file}"
        if not self.changes:
            return base
        said = ", ".join(f"[{s}] {k} = {_literal(v)}" for s, k, v in self.changes)
        return f"{base} with {said}"


def cache_path(scene: Scene, name: str, cache: Path = CACHE) -> Path:
    digest = hashlib.sha256(scene.text.encode()).hexdigest()[:12]
    return cache / f"{name}-{digest}.h5"


def _complete(path: Path) -> bool:
    if not path.is_file():
        return False
    try:
        with open_result(path) as ds:
            return int(ds.attrs.get("complete", 1)) == 1 and "scene_text" in ds.attrs
    except Exception:  # noqa: BLE001 - an unreadable cache file is redone
        return False


class MissingRun(LookupError):
    """A run that is not in the cache, and the caller asked not to compute it."""

    def __init__(self, name: str):
        super().__init__(name)
        self.name = name


def execute(run: Run, quick_run: bool = False, workers: int | None = None,
            cache: Path = CACHE, echo=lambda s: None, cached_only: bool = False
            ) -> xr.Dataset:
    """The run's result: read from the cache when a complete run of the same scene text is
    there, else computed (a sweep resumes its chunk files) and cached; with
    ``cached_only`` a run not in the cache raises MissingRun."""
    scene = run.scene(quick_run)
    path = cache_path(scene, run.name, cache)
    if _complete(path):
        echo(f"{run.name}: cached {path}")
        return open_result(path).load()
    if cached_only:
        raise MissingRun(run.name)
    cache.mkdir(parents=True, exist_ok=True)
    echo(f"{run.name}: running {run.command()}{' (quick)' if quick_run else ''} -> {path}")
    if kind_of(scene.analysis.kind).sweep:
        resume = path.exists() or path.with_name(path.name + ".parts").exists()
        ds = run_sweep(scene, path, workers=workers, resume=resume, overwrite=not resume,
                       echo=echo)
        return ds.load()

    ds = run_scene(scene, workers=workers)
    write_result(ds, path)
    return ds


T_HALF = (("initial_conditions", "t0", "T/2"),)
STAND_IN = 50  # plane side of the heavy basin runs' stand-ins
RK4 = (("integrator", "method", "rk4"), ("integrator", "steps_per_period", 1440),
       ("integrator", "locate_switches", False))

RUN_LIST = (
    # cheap: catalogues, critical distances, the bifurcation diagram
    Run("fig04", "fig04_duffing_catalogue.toml"),
    Run("fig10", "fig10_bilinear_catalogue.toml"),
    Run("fig13_catalogue", "fig13_bilinear_catalogue.toml"),
    Run("fig13_catalogue_F0602", "fig13_bilinear_catalogue.toml",
        (("system", "F", 0.602),), "the figure 13 caption's F = 0.602"),
    Run("fig05", "figures/fig05_duffing_dcrit.toml"),
    Run("fig05_rk4", "figures/fig05_duffing_dcrit.toml", RK4,
        "[integrator] as the study's plain RK4 T/1440"),
    Run("fig06_dcrit", "figures/fig05_duffing_dcrit.toml",
        (("grid", "phi", [5.28, 2 * math.pi - 5.28, 0.573 * math.pi,
                          2 * math.pi - 0.573 * math.pi]),),
        "d_crit at the phases of figure 6 (c, e) and their negatives"),
    Run("fig11", "figures/fig11_bilinear_dcrit.toml"),
    Run("fig12_dcrit", "figures/fig11_bilinear_dcrit.toml",
        (("grid", "phi", [0.60916, 0.36424, "pi", 2 * math.pi - 0.60916, 2 * math.pi - 0.36424]),),
        "d_crit at the phases of figure 12 and their negatives"),
    Run("fig13_dcrit", "figures/fig11_bilinear_dcrit.toml",
        (("system", "w", 0.928), ("system", "F", 0.603),
         ("grid", "phi", {"start": 0.0, "stop": "255*pi/128", "num": 256})),
        "figure 13's parameters (w = 0.928, F = 0.603)"),
    Run("fig13_dcrit_points", "figures/fig11_bilinear_dcrit.toml",
        (("system", "w", 0.928), ("system", "F", 0.603),
         ("grid", "phi", [0.4, 2 * math.pi - 0.4, "pi"])),
        "figure 13's parameters at the phases of its panels"),
    Run("fig07", "figures/fig07_duffing_bifurcation.toml"),
    Run("fig07_step005", "figures/fig07_duffing_bifurcation.toml",
        (("analysis", "step", 0.05),), "d stepped by 0.05"),
    Run("fig07_continuation", "continuation/fig07_duffing_continuation.toml",
        note="figure 7's solutions continued in d: grazing, stable and unstable impacting "
        "orbits, folds"),
    Run("fig14c_t0", "figures/fig14c_t0_stability.toml"),
    Run("fig14d_t0", "figures/fig14c_t0_stability.toml", (("coupling", "c_c", 2.0),),
        "figure 14(d): c_c = 2"),
    Run("fig14c_random_t0", "figures/fig14c_random_t0_stability.toml"),
    Run("fig14a_stability", "figures/fig15a_bilinear_stability.toml",
        (("grid", "k_c", [8.0, 20.0]),), "figure 15(a)'s scene at k_c = 8 and 20 only "
        "(figure 14(a, b))"),
    # heavy: full-resolution basins and basin stability, each with a 50 x 50 stand-in
    *(run for name, scene, changes, note in (
        ("fig07_basins", "fig07_duffing_basins", (), ""),
        ("fig07_basins_t0half", "fig07_duffing_basins", T_HALF, "start at t0 = T/2"),
        ("fig14cd", "fig14cd_duffing_impacting", (), ""),
        ("fig14cd_t0half", "fig14cd_duffing_impacting", T_HALF, "start at t0 = T/2"),
        ("fig06", "fig06_duffing_basins", (), ""),
        ("fig13", "fig13_bilinear_basins", (), ""),
        ("fig03", "fig03_duffing_single_basins", (), ""),
        ("fig09", "fig09_bilinear_single_basins", (), ""),
        ("fig12", "fig12_bilinear_basins", (), ""),
        ("fig14ab", "fig14ab_bilinear_impacting", (), ""),
        ("fig14ab_t0half", "fig14ab_bilinear_impacting", T_HALF, "start at t0 = T/2"),
    ) for run in (
        Run(name, f"figures/{scene}.toml", changes, note, heavy=True,
            stand_in=f"{name}_r{STAND_IN}"),
        Run(f"{name}_r{STAND_IN}", f"figures/{scene}.toml",
            (*changes, ("initial_conditions", "resolution", [STAND_IN, STAND_IN])),
            ", ".join(filter(None, [note, f"{STAND_IN} x {STAND_IN} plane"]))))),
    Run("fig03_wide_r50", "figures/fig03_duffing_single_basins.toml",
        (("initial_conditions", "ranges", [[-12.0, 12.0], [-40.0, 40.0]]),
         ("initial_conditions", "resolution", [STAND_IN, STAND_IN])),
        f"velocities in [-40, 40] (the study's window is not stated), {STAND_IN} x "
        f"{STAND_IN} plane"),
    Run("fig15b", "figures/fig15b_duffing_stability.toml", heavy=True),
    Run("fig15b_t0half", "figures/fig15b_duffing_stability.toml", T_HALF,
        "start at t0 = T/2", heavy=True),
    Run("fig15a", "figures/fig15a_bilinear_stability.toml", heavy=True),
)
RUNS = {run.name: run for run in RUN_LIST}
