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

Any other parameter can be followed the same way (``parameter``: w for a frequency
response, F, c, ...; one body too): see :func:`follow_branch` for how the steps are named
and where a branch ends.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..config import IntegratorSettings
from ..config.axes import axis_units, catalogue_axes
from ..kernels.codes import CONVERGED, DIVERGED_LABEL, UNRESOLVED_LABEL, label_code_of_status
from .catalogue import Catalogue, label_orbit
from .critical_distance import critical_distance, uncoupled_pair
from .engine import Problem, classify_state, record_trajectory
from .labels import code_of, name_of

UNRESOLVED_POINTS = 30  # section points recorded when no period is found
def orbit_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Largest difference between two orbits' section points (q, dim), over the cyclic
    shifts of ``b`` the closest (the same orbit may be entered at another point)."""
    return min(float(np.max(np.abs(a - np.roll(b, k, axis=0)))) for k in range(b.shape[0]))


def d_values(start: float, stop: float, step: float) -> np.ndarray:
    n = int(np.floor(abs(stop - start) / abs(step) + 1e-9)) + 1
    return start + np.sign(stop - start) * abs(step) * np.arange(n)


def follow_branch(system, values: dict, integrator: IntegratorSettings, catalogue: Catalogue,
                  name: str, ds_values: np.ndarray, label_tol: float = 1e-3,
                  parameter: str = "d"):
    """Follow one solution as ``parameter`` takes ``ds_values`` (d by default); returns
    per-step records and a summary.

    Along d (or k_c, c_c, the law's keys) a non-impacting orbit does not change, and each
    step is named by the catalogue. Along a parameter the catalogue depends on (the body's,
    phi: ``config.axes.catalogue_axes``) the orbit moves away from the catalogue's, so the
    branch keeps its name by continuity while the state stays on a non-impacting orbit of
    the branch's period; it is destroyed at the first step where it does not (located to
    the step; along d, at grazing). A jump past a fold onto another orbit of the same
    period is found by comparing the branches followed together (:func:`resolve_jumps`).
    """
    orbit = catalogue.orbits[name]
    state = orbit[0].copy()
    names = catalogue.names
    own = names.index(name)
    by_continuity = parameter in catalogue_axes(system)
    records = []
    destroyed_at = np.nan
    destroyed_step = None
    alive = True
    for d in ds_values:
        problem = Problem(system, {**values, parameter: float(d)}, integrator)
        cls = classify_state(problem, state, 0.0)
        if cls.status == CONVERGED:
            label = label_orbit(catalogue, cls.orbit, cls.impacting, label_tol)
            code = code_of(label, names)
            if (by_continuity and alive and cls.period == orbit.shape[0]
                    and not cls.impacting):
                code = own
            points = cls.orbit
            state = cls.orbit[-1].copy()  # the last section point: t = 0 mod T
        else:
            code = label_code_of_status(cls.status)
            traj = record_trajectory(problem, state, 0.0, UNRESOLVED_POINTS, 1)
            points = traj.section_y[1:]
            if np.all(np.isfinite(points[-1])):
                state = points[-1].copy()
        if alive and code != own:
            alive = False
            destroyed_step = len(records)
            # while it lived the branch was the combination's uncoupled orbit: grazing is
            # located on its Newton-refined joint orbit, not on the classifier's estimate
            if records and parameter == "d":
                destroyed_at, _ = critical_distance(
                    uncoupled_pair(system, values, values["phi"]), orbit[0], orbit.shape[0])
            elif records:
                destroyed_at = float(d)
        records.append({"d": float(d), "code": code, "points": points,
                        "impacting": bool(cls.impacting),
                        "period": cls.period})
    return records, summarise(records, float(destroyed_at), destroyed_step, parameter,
                              names)


def summarise(records: list[dict], destroyed_at: float, destroyed_step: int | None,
              parameter: str, names: tuple[str, ...]) -> dict:
    """A followed branch's destruction point, then its impacting range and the first
    non-impacting solution it falls to."""
    impacting = [r["d"] for r in records if r["impacting"]]
    if parameter == "d":
        after = [r for r in records if np.isfinite(destroyed_at) and r["d"] < destroyed_at]
    else:
        after = records[destroyed_step:] if np.isfinite(destroyed_at) else []
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
    return {"destroyed_at": float(destroyed_at), "falls_to": falls_to,
            "impacting_range": impacting_range, "impacting_d": impacting,
            "destroyed_step": destroyed_step}


def _same_orbit(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    return a.shape == b.shape and orbit_distance(a, b) <= tol * max(
        1.0, float(np.max(np.abs(b))))


def _moved(records: list[dict], j: int) -> float:
    """How far a branch's orbit moved from step j - 1 to step j."""
    prev, now = records[j - 1]["points"], records[j]["points"]
    return orbit_distance(now, prev) if prev.shape == now.shape else np.inf


def resolve_jumps(followed: list[tuple[list[dict], dict]], names: tuple[str, ...],
                  branches: list[str], values: np.ndarray, parameter: str,
                  tol: float = 1e-3) -> None:
    """Branches named by continuity that reach the same orbit at a step: one of them
    jumped there (past a fold of its own, onto a solution that coexisted). The one whose
    orbit moved more since the step before jumped: from that step on it is named after
    the other, is destroyed there (to the step) and falls to it; the summaries are
    redone. A single branch followed alone cannot tell a jump from a steep stretch."""
    own = [names.index(b) for b in branches]
    for j in range(1, len(values)):
        for i in range(len(followed)):
            for k in range(len(followed)):
                ri, rk = followed[i][0][j], followed[k][0][j]
                if (k == i or ri["code"] != own[i] or rk["code"] != own[k]
                        or not _same_orbit(ri["points"], rk["points"], tol)):
                    continue

                jumper, stayer = (i, k) if _moved(followed[i][0], j) > \
                    _moved(followed[k][0], j) else (k, i)
                records = followed[jumper][0]
                for r in records[j:]:
                    if r["code"] == own[jumper]:
                        r["code"] = own[stayer]
                followed[jumper] = (records, summarise(records, float(values[j]), j,
                                                       parameter, names))


def name_by_other_branches(followed: list[tuple[list[dict], dict]], names: tuple[str, ...],
                           branches: list[str], parameter: str, tol: float = 1e-3) -> None:
    """Along a parameter the catalogue depends on, a step that left its branch lands on an
    orbit the catalogue (of the scene's values) cannot name; when another followed branch
    is on that orbit at that step, the step takes its name, and the summaries are redone
    (``falls_to``)."""
    for i, (records, summary) in enumerate(followed):
        changed = False
        for j, r in enumerate(records):
            if 0 <= r["code"] < len(names) or r["impacting"] or r["period"] < 1:
                continue
            for k, (others, _) in enumerate(followed):
                o = others[j]
                own = names.index(branches[k])
                if k != i and o["code"] == own and _same_orbit(r["points"], o["points"], tol):
                    r["code"], changed = own, True
                    break
        if changed:
            followed[i] = (records, summarise(records, summary["destroyed_at"],
                                              summary["destroyed_step"], parameter, names))


def bifurcation_dataset(system, values: dict, integrator: IntegratorSettings,
                        catalogue: Catalogue, branches: list[str], ds_values: np.ndarray,
                        progress=None, parameter: str = "d") -> xr.Dataset:
    """Dims (branch, parameter, point): a pair's section displacements of both bodies
    (``section_x1``, ``section_x2``), one body's displacement and velocity
    (``section_x1``, ``section_v1``), per step of ``parameter`` and branch."""
    max_points = 1
    results = []
    for name in branches:
        records, summary = follow_branch(system, values, integrator, catalogue, name,
                                         ds_values, parameter=parameter)
        max_points = max(max_points, max(r["points"].shape[0] for r in records))
        results.append((records, summary))
        if progress is not None:
            progress(1)
    if parameter in catalogue_axes(system):
        resolve_jumps(results, catalogue.names, branches, ds_values, parameter)
        name_by_other_branches(results, catalogue.names, branches, parameter)
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
            x2[i, j, : pts.shape[0]] = pts[:, 2 if system.bodies == 2 else 1]
            code[i, j] = r["code"]
            impacting[i, j] = r["impacting"]
            period[i, j] = r["period"]
    names = catalogue.names
    codes = sorted(set(range(len(names))) | set(np.unique(code).tolist()))
    p = parameter
    second = ("section_x2", "right body's section displacements") if system.bodies == 2 \
        else ("section_v1", "the body's section velocities")
    where = "grazing" if p == "d" else "to the step: the first step without it"
    return xr.Dataset(
        {
            "section_x1": (("branch", p, "point"), x1,
                           {"long_name": "left body's section displacements", "units": "1"}),
            second[0]: (("branch", p, "point"), x2, {"long_name": second[1], "units": "1"}),
            "label": (("branch", p), code, {"long_name": "solution reached (code)"}),
            "impacting": (("branch", p), impacting, {"long_name": "1: contact on the orbit"}),
            "period": (("branch", p), period, {"units": "forcing periods"}),
            "branch_name": (("branch",), np.array(branches, dtype=object)),
            "destroyed_at": (("branch",), [s["destroyed_at"] for _, s in results],
                             {"long_name": f"{p} where the solution is destroyed ({where})"}),
            "falls_to": (("branch",), np.array([s["falls_to"] for _, s in results],
                                               dtype=object)),
            "impacting_range": (("branch", "bound"),
                                np.array([s["impacting_range"] for _, s in results]),
                                {"long_name": f"{p} range of impacting states right after "
                                              "destruction (high, low)"}),
            "label_code": (("label_index",), np.array(codes, dtype=np.int32)),
            "label_name": (("label_index",), np.array([name_of(c, names) for c in codes],
                                                      dtype=object)),
        },
        coords={"branch": np.arange(nb), p: (p, ds_values, {"units": axis_units(p)}),
                "point": np.arange(max_points), "bound": ["high", "low"]},
        attrs={"analysis": "bifurcation", "parameter": p},
    )
