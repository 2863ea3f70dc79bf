"""Bifurcation diagrams along d: follow each non-impacting solution as the gap closes.

For each starting solution (a combination of the catalogue at the scene's phi), d moves
from ``start`` to ``stop`` in steps; each step starts from the previous step's final
state, as in the study. At each d the trajectory is classified and the last section
points of each body are recorded (the orbit's q points, or the last K points when the
outcome is unresolved).

A non-impacting orbit does not depend on d (the bodies never touch), so it exists exactly
while d > max(x1 - x2) over the orbit. Its destruction is detected between two steps and
located at that grazing value, computed on the combination's Newton-refined joint orbit
by the flow-located maximum of x1 - x2 (see ``critical_distance``): the limit that
bisection on max(x1 - x2) - d = 0 converges to, here to ~1e-10. After it, the followed
state may stay on an impacting solution over a range of d (``impacting_range``) before it
falls to another non-impacting solution (``falls_to``).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config import IntegratorSettings
from ..kernels.codes import CONVERGED, DIVERGED_LABEL, UNRESOLVED_LABEL, label_code_of_status
from .catalogue import Catalogue, label_orbit
from .critical_distance import critical_distance, uncoupled_pair
from .engine import Problem, classify_state, record_trajectory
from .labels import code_of, name_of

UNRESOLVED_POINTS = 30  # section points recorded when no period is found


def d_values(start: float, stop: float, step: float) -> np.ndarray:
    n = int(np.floor(abs(stop - start) / abs(step) + 1e-9)) + 1
    return start + np.sign(stop - start) * abs(step) * np.arange(n)


def follow_branch(system, values: dict, integrator: IntegratorSettings, catalogue: Catalogue,
                  name: str, ds_values: np.ndarray, label_tol: float = 1e-3):
    """Follow one solution along ``ds_values``; returns per-step records and a summary."""
    combo = catalogue.combination(name)
    state = combo.orbit[0].copy()
    names = catalogue.names
    records = []
    destroyed_at = np.nan
    alive = True
    for d in ds_values:
        problem = Problem(system, {**values, "d": float(d)}, integrator)
        cls = classify_state(problem, state, 0.0)
        if cls.status == CONVERGED:
            label = label_orbit(catalogue, cls.orbit, cls.impacting, label_tol)
            code = code_of(label, names)
            points = cls.orbit
            state = cls.orbit[-1].copy()  # the last section point: t = 0 mod T
        else:
            code = label_code_of_status(cls.status)
            traj = record_trajectory(problem, state, 0.0, UNRESOLVED_POINTS, 1)
            points = traj.section_y[1:]
            if np.all(np.isfinite(points[-1])):
                state = points[-1].copy()
        if alive and code != names.index(name):
            alive = False
            # while it lived the branch was the combination's uncoupled orbit: grazing is
            # located on its Newton-refined joint orbit, not on the classifier's estimate
            if records:
                destroyed_at, _ = critical_distance(
                    uncoupled_pair(system, values, values["phi"]), combo.orbit[0],
                    combo.orbit.shape[0])
        records.append({"d": float(d), "code": code, "points": points,
                        "impacting": bool(cls.impacting),
                        "period": cls.period})
    # after destruction: impacting range, then the first non-impacting solution reached
    impacting = [r["d"] for r in records if r["impacting"]]
    after = [r for r in records if np.isfinite(destroyed_at) and r["d"] < destroyed_at]
    falls_to = ""
    impacting_range = [np.nan, np.nan]
    first_run = []
    for r in after:
        if r["impacting"]:
            first_run.append(r["d"])
            continue
        if r["code"] >= 0:
            falls_to = name_of(r["code"], names)
            break
        if r["code"] in (UNRESOLVED_LABEL, DIVERGED_LABEL):
            first_run.append(r["d"])
    if first_run:
        impacting_range = [max(first_run), min(first_run)]
    summary = {"destroyed_at": float(destroyed_at), "falls_to": falls_to,
               "impacting_range": impacting_range, "impacting_d": impacting}
    return records, summary


def bifurcation_dataset(system, values: dict, integrator: IntegratorSettings,
                        catalogue: Catalogue, branches: list[str], ds_values: np.ndarray,
                        progress=None) -> xr.Dataset:
    """Dims (branch, d, point): each body's section displacement per step and branch."""
    max_points = 1
    results = []
    for name in branches:
        records, summary = follow_branch(system, values, integrator, catalogue, name,
                                         ds_values)
        max_points = max(max_points, max(r["points"].shape[0] for r in records))
        results.append((records, summary))
        if progress is not None:
            progress(1)
    nb, nd = len(branches), len(ds_values)
    x1 = np.full((nb, nd, max_points), np.nan)
    x2 = np.full((nb, nd, max_points), np.nan)
    code = np.zeros((nb, nd), dtype=np.int32)
    impacting = np.zeros((nb, nd), dtype=np.int8)
    period = np.zeros((nb, nd), dtype=np.int16)
    for i, (records, _) in enumerate(results):
        for j, r in enumerate(records):
            pts = r["points"]
            x1[i, j, : pts.shape[0]] = pts[:, 0]
            x2[i, j, : pts.shape[0]] = pts[:, 2]
            code[i, j] = r["code"]
            impacting[i, j] = r["impacting"]
            period[i, j] = r["period"]
    names = catalogue.names
    codes = sorted(set(range(len(names))) | set(np.unique(code).tolist()))
    return xr.Dataset(
        {
            "section_x1": (("branch", "d", "point"), x1,
                           {"long_name": "left body's section displacements", "units": "1"}),
            "section_x2": (("branch", "d", "point"), x2,
                           {"long_name": "right body's section displacements", "units": "1"}),
            "label": (("branch", "d"), code, {"long_name": "solution reached (code)"}),
            "impacting": (("branch", "d"), impacting, {"long_name": "1: contact on the orbit"}),
            "period": (("branch", "d"), period, {"units": "forcing periods"}),
            "branch_name": (("branch",), np.array(branches, dtype=object)),
            "destroyed_at": (("branch",), [s["destroyed_at"] for _, s in results],
                             {"long_name": "d where the solution is destroyed (grazing)"}),
            "falls_to": (("branch",), np.array([s["falls_to"] for _, s in results],
                                               dtype=object)),
            "impacting_range": (("branch", "bound"),
                                np.array([s["impacting_range"] for _, s in results]),
                                {"long_name": "d range of impacting states right after "
                                              "destruction (high, low)"}),
            "label_code": (("label_index",), np.array(codes, dtype=np.int32)),
            "label_name": (("label_index",), np.array([name_of(c, names) for c in codes],
                                                      dtype=object)),
        },
        coords={"branch": np.arange(nb), "d": ("d", ds_values, {"units": "1"}),
                "point": np.arange(max_points), "bound": ["high", "low"]},
        attrs={"analysis": "bifurcation"},
    )
