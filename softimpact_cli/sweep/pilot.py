"""The tolerance pilot: before a large sweep, choose the loosest tolerance that labels a
random pilot sample exactly as the verification's tight reference does.

The default tolerance (rtol 1e-8) is what the study's fractal bilinear planes need; a
smooth Duffing plane labels every point the same at rtol 1e-5, about six times faster
(``benchmarks/bench_targets.py``). Which one a scene needs, only the scene can say, so
a sweep of at least ``MIN_TOTAL_RATIO`` x ``pilot_sample`` trajectories first reruns
``pilot_sample`` random trajectories (disjoint from the verification sample, so that
the verification stays an unbiased measure of the chosen setting) at
``sweep.check.tightened`` settings, then at each candidate rtol of ``CANDIDATES``
looser than the scene's, loosest first (atol scaled with it, capture and cells as the
scene has them). The sweep runs at the first candidate that

- finds the same attractors (the one-body search and the pair's combinations, by name,
  built at the candidate's settings), and
- labels every pilot trajectory as the reference does,

or at the scene's own settings when none does. Zero disagreements in 400 pilot
trajectories still allows an error near 0.5% (the chance of seeing none at 0.5% is
13%); the verification after the sweep measures the chosen setting on its own sample
and tightens the whole sweep when it is over the threshold, so the pilot only chooses
where to start.

The pilot is skipped (and says why) when the scene sets rtol or atol by hand, runs the
fixed-step RK4 method, or is smaller than the threshold above (there the pilot would
cost more than it could save). The choice goes into the scene text the result stores,
so a resumed run, which repeats the pilot (it is deterministic), finds the same scene.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np

from ..config import IntegratorSettings, Scene
from .check import rerun_labels, rerun_named, sample_indices, tightened
from .runner import prepare_catalogues

CANDIDATES = (1e-5, 1e-6, 1e-7)  # rtol, loosest first; only those looser than the scene's
MIN_TOTAL_RATIO = 50  # pilot only sweeps of at least this many times pilot_sample


@dataclass(frozen=True)
class Trial:
    """One candidate on the pilot sample: ``disagreements`` with the reference labels
    (None when its attractor search differed: ``names_differ``), its wall time (s)."""

    rtol: float
    atol: float
    disagreements: int | None
    wall_s: float
    names_differ: bool = False

    @property
    def passed(self) -> bool:
        return not self.names_differ and self.disagreements == 0


def candidate(s: IntegratorSettings, rtol: float) -> IntegratorSettings:
    """``s`` at ``rtol``, atol scaled by the same factor (the scene's atol/rtol kept)."""
    return replace(s, rtol=rtol, atol=s.atol * rtol / s.rtol)


def skip_reason(scene: Scene, total: int) -> str | None:
    """Why the pilot does not run for ``scene`` of ``total`` trajectories (None: it runs)."""
    settings = scene.verification
    if settings is None or not settings.pilot:
        return "[verification] pilot = false"
    by_hand = [k for k in ("rtol", "atol") if k in scene.sections.get("integrator", {})]
    if by_hand:
        return f"[integrator] {' and '.join(by_hand)} set by hand"
    traits = scene.integrator.traits
    if not traits.tolerance:
        return (f"fixed-step {scene.integrator.resolved_method} has no tolerance"
                if traits.fixed_step else "the exact flow has no tolerance")
    if not [r for r in CANDIDATES if r > scene.integrator.rtol]:
        return f"no candidate looser than rtol {scene.integrator.rtol:g}"
    if total < MIN_TOTAL_RATIO * settings.pilot_sample:
        return (f"{total} trajectories < {MIN_TOTAL_RATIO} x pilot_sample "
                f"({settings.pilot_sample}): the pilot would cost more than it saves")
    return None


def pilot_indices(total: int, pilot: int, verification: int, seed: int) -> np.ndarray:
    """``pilot`` flat indices drawn with ``seed + 1`` from those the verification (its
    ``verification`` indices drawn with ``seed``) does not rerun, sorted."""
    taken = sample_indices(total, verification, seed)
    free = np.setdiff1d(np.arange(total), taken, assume_unique=True)
    rng = np.random.default_rng(seed + 1)
    return np.sort(rng.choice(free, size=min(pilot, free.size), replace=False))


def choose_tolerance(scene: Scene, verification_sample: int | None = None, executor=None,
                     echo: Callable[[str], None] = lambda s: None) -> tuple[Scene, dict]:
    """(the scene to sweep, the ``pilot_*`` attributes recording why).

    ``verification_sample``: the size the verification will rerun (``--check N``;
    default from [verification]), whose indices the pilot avoids.
    """
    total = scene.grid.size * scene.initial_conditions.count
    reason = skip_reason(scene, total)
    if reason is not None:
        return scene, {"pilot_status": f"not run ({reason})"}
    settings = scene.verification
    started = time.perf_counter()
    n_verify = min(verification_sample or settings.sample_size(total), total)
    picks = pilot_indices(total, settings.pilot_sample, n_verify, settings.seed)
    catalogues, names = prepare_catalogues(scene)
    reference = tightened(scene.integrator)
    echo(f"tolerance pilot: {picks.size} trajectories at rtol {reference.rtol:g} "
         f"(reference) and at rtol {', '.join(f'{r:g}' for r in _looser(scene))}")
    ref_labels, ref_wall, ref_named = rerun_named(scene, reference, catalogues, names, picks,
                                                  executor)  # trials keep its attractor numbers
    trials: list[Trial] = []
    chosen = scene.integrator
    for rtol in _looser(scene):
        trial_settings = candidate(scene.integrator, rtol)
        trial_scene = replace(scene, integrator=trial_settings)
        t = time.perf_counter()
        trial_catalogues, trial_names = prepare_catalogues(trial_scene)
        if trial_names != names:
            trials.append(Trial(rtol, trial_settings.atol, None, time.perf_counter() - t,
                                names_differ=True))
        else:
            labels, _ = rerun_labels(trial_scene, trial_settings, trial_catalogues, names,
                                     picks, executor, ref_named)
            trials.append(Trial(rtol, trial_settings.atol, int((labels != ref_labels).sum()),
                                time.perf_counter() - t))
        echo(f"tolerance pilot: rtol {rtol:g}: {_trial_text(trials[-1], picks.size)}")
        if trials[-1].passed:
            chosen = trial_settings
            break
    attrs = {"pilot_status": ("chose rtol " f"{chosen.rtol:g}" if chosen is not
                              scene.integrator else
                              f"kept rtol {scene.integrator.rtol:g} (no looser candidate "
                              "agreed)"),
             "pilot_sample": int(picks.size), "pilot_reference_rtol": reference.rtol,
             "pilot_reference_wall_s": ref_wall, "pilot_rtol": chosen.rtol,
             "pilot_atol": chosen.atol, "pilot_wall_s": time.perf_counter() - started,
             "pilot_trials": json.dumps([asdict(t) for t in trials])}
    echo(f"tolerance pilot: {attrs['pilot_status']} ({attrs['pilot_wall_s']:.1f} s)")
    return chosen_scene(scene, chosen), attrs


def chosen_scene(scene: Scene, chosen: IntegratorSettings) -> Scene:
    """``scene`` at the pilot's choice; its stored text records it (its hash differs)."""
    if chosen == scene.integrator:
        return scene
    return replace(scene, integrator=chosen,
                   text=scene.text + f"\n# tolerance pilot: rtol {chosen.rtol:g}, "
                                     f"atol {chosen.atol:g}\n")


def scene_as_run(scene: Scene, attrs) -> Scene:
    """The scene a stored result was swept with, from its ``pilot_*`` attributes (a
    verification resumed after a kill must judge the settings the sweep ran at)."""
    if "pilot_rtol" not in attrs or float(attrs["pilot_rtol"]) == scene.integrator.rtol:
        return scene
    return chosen_scene(scene, replace(scene.integrator, rtol=float(attrs["pilot_rtol"]),
                                       atol=float(attrs["pilot_atol"])))


def _looser(scene: Scene) -> list[float]:
    return [r for r in CANDIDATES if r > scene.integrator.rtol]


def pilot_trial_text(trial: Mapping[str, Any], sample: int) -> str:
    """How one candidate of the pilot did, e.g. ``0 of 400 disagree (1.2 s)``."""
    if trial["names_differ"]:
        return "its attractor search found other attractors"
    return f"{trial['disagreements']} of {sample} disagree ({trial['wall_s']:.1f} s)"


def _trial_text(trial: Trial, sample: int) -> str:
    return pilot_trial_text(asdict(trial), sample)
