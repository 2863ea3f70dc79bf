"""Error against run time of a sweep: rerun a random sample of its trajectories at
tighter settings and compare the labels.

Tightened settings: rtol and atol / 100, convergence_tol / 10, twice the period budget,
4x the RK4 steps, no capture near known orbits, no recurrence cells. The share of labels
that changes is the estimated label error (the default verification of every sweep,
``sweep.verification``, and ``softimpact check`` of a sweep kind are built on it). Each
report carries both wall times and their ratio.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from ..analysis.impacting import impacting_number
from ..analysis.labels import impacting_code, name_of
from ..config import IntegratorSettings, Scene, forcing_period
from .executors import LocalExecutor
from .merge import impacting_numbering
from .runner import prepare_catalogues, sweep_context
from .second_stage import relabel, unpack


def tightened(s: IntegratorSettings) -> IntegratorSettings:
    """The reference settings; capture and recurrence cells off, so that their error is
    measured too."""
    return replace(s, rtol=max(s.rtol / 100, 1e-14), atol=s.atol / 100,
                   convergence_tol=s.convergence_tol / 10, max_periods=2 * s.max_periods,
                   steps_per_period=4 * s.steps_per_period, capture_tol=0.0, cell_size=0.0)


def shortcuts(s: IntegratorSettings) -> bool:
    """Whether ``s`` labels some trajectories early: capture near known orbits or cells."""
    return s.capture_tol > 0.0 or s.cell_size > 0.0


def without_shortcuts(s: IntegratorSettings) -> IntegratorSettings:
    return replace(s, capture_tol=0.0, cell_size=0.0)


def sample_indices(total: int, sample: int, seed: int) -> np.ndarray:
    """``min(sample, total)`` distinct flat indices of a sweep's trajectories (plan
    order), drawn at random with ``seed``, sorted."""
    rng = np.random.default_rng(seed)
    return np.sort(rng.choice(total, size=min(sample, total), replace=False))


def rerun_labels(scene: Scene, settings: IntegratorSettings, catalogues: dict,
                 names: tuple[str, ...], picks: np.ndarray, executor=None, result=None
                 ) -> tuple[np.ndarray, float]:
    """(label codes, wall s) of the trajectories at flat indices ``picks`` run at
    ``settings``, each in a one-trajectory chunk (so recurrence cells never carry over
    from one to the next), on ``executor`` (default: this process). Attractors that are
    not periodic are named after ``result``'s where they match (``second_stage``)."""
    labels, wall, _ = rerun_named(scene, settings, catalogues, names, picks, executor, result)
    return labels, wall


def rerun_named(scene: Scene, settings: IntegratorSettings, catalogues: dict,
                names: tuple[str, ...], picks: np.ndarray, executor=None, result=None):
    """``rerun_labels`` and the table of the attractors that are not periodic it named
    (``second_stage.relabel``): pass it as ``result`` to a rerun compared with this one,
    so that the same attractor takes the same number in both."""
    ic = scene.initial_conditions
    t0 = ic.random_t0(forcing_period(scene.values)) if ic.t0 is None else None
    context = sweep_context(replace(scene, integrator=settings), catalogues, names, t0)
    chunks = [(j, int(i), int(i) + 1) for j, i in enumerate(picks)]
    labels = np.empty(len(picks), dtype=np.int64)
    start = time.perf_counter()
    by_flat: dict[int, int] = {}
    recurrent = []
    impacting = {}  # j -> section points of the impacting orbit it reached
    for j, chunk in (executor or LocalExecutor(1)).run(context, chunks):
        labels[j] = chunk["label"][0]
        by_flat[int(picks[j])] = j
        recurrent += unpack(chunk)
        if impacting_number(labels[j]) is not None:
            impacting[j] = next(iter(chunk["orbits"].values()))[1]
    if impacting:  # numbered as the result numbered them, else in flat order
        numbering = impacting_numbering(context)
        seed_numbering(numbering, result)
        n_ic = context.states.shape[0]
        for j in sorted(impacting, key=lambda j: picks[j]):
            pts = impacting[j]
            labels[j] = impacting_code(len(pts), numbering.number(int(picks[j]) // n_ic, pts))
    table = None
    if recurrent:  # name the second stage's sets (flat order), as the result was named
        flat_labels = np.zeros(max(by_flat) + 1, dtype=np.int64)
        table = relabel(context, flat_labels, {}, recurrent, tuple(scene.system.state_names),
                        result)
        for r in recurrent:
            labels[by_flat[r.flat]] = flat_labels[r.flat]
    return labels, time.perf_counter() - start, table if table is not None else result


def seed_numbering(numbering, result) -> None:
    """Number the impacting orbits of a stored ``result`` (its ``attractor_points`` per
    label and grid point) in ``numbering`` first, so that a rerun names them as it did."""
    if result is None or "attractor_points" not in result or "label_code" not in result:
        return
    codes = result["label_code"].values
    points = result["attractor_points"].values
    points = points.reshape(len(codes), -1, *points.shape[-2:])
    numbered = sorted((impacting_number(c)[::-1], i) for i, c in enumerate(codes)
                      if impacting_number(c) is not None)
    for (number, period), i in numbered:
        for point in range(points.shape[1]):
            pts = points[i, point, :period]
            if np.all(np.isfinite(pts)):
                numbering.seed(point, pts, number)


def label_changes(before: np.ndarray, after: np.ndarray, names: tuple[str, ...]
                  ) -> dict[str, int]:
    """{"A -> B": count} of the positions where the label codes differ."""
    changes: dict[str, int] = {}
    for a, b in zip(before[before != after], after[before != after], strict=True):
        key = f"{name_of(a, names)} -> {name_of(b, names)}"
        changes[key] = changes.get(key, 0) + 1
    return changes


def check_sweep(scene: Scene, sample: int, seed: int, result=None, executor=None) -> dict:
    """Labels at the scene's settings (``result``'s stored labels when given) against
    labels at ``tightened`` settings, on ``sample`` random trajectories."""
    catalogues, names = prepare_catalogues(scene)
    total = scene.grid.size * scene.initial_conditions.count
    picks = sample_indices(total, sample, seed)
    named = result  # whose attractor numbers the reruns keep
    if result is not None:
        scene_labels = result["label"].values.ravel()[picks]
        scene_wall = float(result.attrs["wall_s"]) * picks.size / total
    else:
        scene_labels, scene_wall, named = rerun_named(scene, scene.integrator, catalogues,
                                                      names, picks, executor)
    tight_labels, tight_wall = rerun_labels(scene, tightened(scene.integrator), catalogues,
                                            names, picks, executor, named)
    changed = scene_labels != tight_labels
    report = {}
    if result is not None and shortcuts(scene.integrator) and changed.any():
        # the same settings without capture or cells: tells their error from the
        # tolerance's (nothing to tell when no label changed)
        alone, _ = rerun_labels(scene, without_shortcuts(scene.integrator), catalogues, names,
                                picks, executor, named)
        report["changed_alone"] = int((alone != tight_labels).sum())
    return {**report, "kind": "labels", "sample": int(picks.size),
            "changed": int(changed.sum()),
            "changed_share": float(changed.mean()) if picks.size else 0.0,
            "changes": label_changes(scene_labels, tight_labels, names),
            "wall_s": scene_wall, "tight_wall_s": tight_wall,
            "wall_ratio": tight_wall / max(scene_wall, 1e-12)}
