"""Critical distances (figures 5, 11) and the bifurcation diagram (figure 7)."""

from __future__ import annotations

import math  # noqa: F401
from functools import partial

import numpy as np

from ...analysis.catalogue import (
    Attractor,
    body_problem,
    combinations,
    right_attractors,
    search_shares,
)
from ...analysis.critical_distance import relative_trace, uncoupled_pair
from ...config import IntegratorSettings
from .. import measures as M
from ..runs import RUNS, MissingRun
from ..verdicts import Measure, agrees
from . import CHECKS, PI, _counted, _names, check

# ------------------------------------------------------------------ critical distances

RK4_STUDY = dict(method="rk4", steps_per_period=1440, locate_switches=False)


def _attractors(ds) -> list:
    """The catalogue's attractors rebuilt from a result (no search rerun)."""
    out = []
    for i, number in enumerate(ds["attractor"].values):
        p = int(ds["attractor_period"].values[i])
        mult = ds["multiplier_re"].values[i] + 1j * ds["multiplier_im"].values[i]
        out.append(Attractor(int(number), p, ds["attractor_points"].values[i, :p].copy(),
                             float(ds["attractor_amplitude"].values[i]),
                             mult[np.isfinite(mult)], float(search_shares(ds)[i]),
                             float(ds["attractor_residual"].values[i])))
    return out


def dcrit_study_method(run, ds, name: str, phi: float, periods: int = 40) -> float:
    """d_crit as the study computes it: the uncoupled pair integrated by plain RK4 at
    T/1440 from the combination's joint orbit, x1 - x2 maximised over the 1440 step points
    of the last joint period (no location of the maximum between steps)."""
    scene = run.scene()
    rk4 = IntegratorSettings(**RK4_STUDY)
    values = dict(scene.values)
    left = _attractors(ds)
    right = right_attractors(body_problem(scene.system, values, rk4), left, phi,
                             scene.system.extra["right_sign"],
                             scene.system.extra["right_phase"])
    combo = next(c for c in combinations(left, right) if c.name == name)
    q = combo.orbit.shape[0]
    problem = uncoupled_pair(scene.system, values, phi, rk4)
    _, g, _ = relative_trace(problem, combo.orbit[0], periods * q, 1440)
    return float(np.max(g[-(1440 * q + 1):-1]))


def _dcrit_value(st, runs, phi: float) -> Measure:
    name = "L1^2 R1-0^2"
    ds = runs("fig05")
    value = M.dcrit_at(ds, name, phi)
    m = Measure(value, f"{value:.5f} ({name}, maximum located on the flow to 1e-12 in time)",
                ("fig05",), tolerance=1e-8)
    same = runs("fig05_rk4")
    diff = abs(M.dcrit_at(same, name, phi) - value)
    m.note = (f"the dcrit analysis ignores the scene's [integrator] (it integrates with its "
              f"own dopri5 rtol 1e-12): fig05 with [integrator] rk4 T/1440 gives a change "
              f"of {diff:.1e}")
    study_way = dcrit_study_method(RUNS["fig05"], ds, name, phi)
    m.alternatives.append(Measure(study_way, f"{study_way:.5f}", ("fig05 + RK4 T/1440 "
                                  "trajectory",), label="the study's method (plain RK4 "
                                  "T/1440, maximum over the step points)"))
    phis, curve = M.dcrit_curve(ds, name)
    at = [p for p, a, b in zip(phis[:-1], curve[:-1], curve[1:], strict=True)
          if (a - st["study"]) * (b - st["study"]) <= 0]
    m.note += ("; softimpact's curve takes the study's value at phi = "
               + ", ".join(f"{p / PI:.4f} pi" for p in at) + " (grid points next to it)"
               if at else "; softimpact's curve never reaches the study's value")
    mirrored = M.dcrit_at(ds, name, (2 * PI - phi) % (2 * PI))
    m.alternatives.append(Measure(mirrored, f"{mirrored:.5f}", ("fig05",),
                                  label="phase sign flipped (phi -> 2 pi - phi)"))
    return m


@check("dcrit_pi_4")
def dcrit_pi_4(st, runs):
    return _dcrit_value(st, runs, PI / 4)


@check("dcrit_3pi_4")
def dcrit_3pi_4(st, runs):
    return _dcrit_value(st, runs, 3 * PI / 4)


@check("dcrit_pi")
def dcrit_pi(st, runs):
    return _dcrit_value(st, runs, PI)


SAME_ORBIT = ("L1^1 R1-0^1", "L1^2 R1-0^2")
MIXED = ("L1^1 R1-0^2", "L1^2 R1-0^1")


@check("dcrit_in_phase")
def dcrit_in_phase(st, runs):
    ds = runs("fig05")
    values = [M.dcrit_at(ds, n, 0.0) for n in SAME_ORBIT]
    worst = max(values, key=abs)
    return Measure(worst, "d_crit(0) = " + ", ".join(f"{v:.1e} ({n})" for n, v
                                                     in zip(SAME_ORBIT, values, strict=True)),
                   ("fig05",), tolerance=1e-8)


@check("dcrit_antiphase_overlap")
def dcrit_antiphase_overlap(st, runs):
    ds = runs("fig05")
    amps = [float(a) for a in ds["attractor_amplitude"].values]
    gaps = [abs(M.dcrit_at(ds, n, PI) - 2 * a) for n, a in zip(SAME_ORBIT, amps, strict=True)]
    return Measure(max(gaps) < 1e-3, "d_crit(pi) - 2 x amplitude (the orbits' x-ranges "
                   "touch) = " + ", ".join(f"{g:.1e}" for g in gaps) + " for "
                   + _names(SAME_ORBIT), ("fig05",))


@check("dcrit_lowest")
def dcrit_lowest(st, runs):
    ds = runs("fig05")
    curves = {n: M.dcrit_curve(ds, n)[1] for n in M.combination_names(ds)}
    red = curves["L1^1 R1-0^1"]
    lowest = all(np.all(red <= c + 1e-9) for c in curves.values())
    return Measure(lowest, f"L1^1 R1-0^1 has the lowest d_crit at all {len(red)} phases: "
                   f"{lowest} (its max {red.max():.3f})", ("fig05",))


@check("dcrit_mixed_mirrored")
def dcrit_mixed_mirrored(st, runs):
    ds = runs("fig05")
    phis, a = M.dcrit_curve(ds, MIXED[0])
    _, b = M.dcrit_curve(ds, MIXED[1])
    n = len(phis)
    mirror = max(abs(a[k] - b[(n - k) % n]) for k in range(n))
    near10 = all(8.0 <= c.max() <= 12.0 for c in (a, b))
    return Measure(mirror < 1e-3 and near10,
                   f"max d_crit {a.max():.3f} and {b.max():.3f}; "
                   f"max |d_A(phi) - d_B(2 pi - phi)| = {mirror:.1e}", ("fig05",))


@check("dcrit_biggest_range")
def dcrit_biggest_range(st, runs):
    ds = runs("fig05")
    spans = {n: float(np.ptp(M.dcrit_curve(ds, n)[1])) for n in M.combination_names(ds)}
    top = max(spans, key=spans.get)
    return Measure(top == "L1^2 R1-0^2", "range of d_crit over phi: "
                   + ", ".join(f"{n} {v:.2f}" for n, v in spans.items()), ("fig05",))


@check("dcrit_borders")
def dcrit_borders(st, runs):
    """The lines are borders: following each solution down in d (labels from the
    integrated trajectories, not from d_crit), it keeps its label at every d above its
    d_crit(5pi/8) line and loses it at the first d below."""
    ds, bif = runs("fig05"), runs("fig07")
    parts, ok = [], True
    for name, b in M.branches(bif).items():
        line = M.dcrit_at(ds, name, 5 * PI / 8)
        above = [lab for d, lab in zip(b["d"], b["labels"], strict=True) if d > line]
        below = [lab for d, lab in zip(b["d"], b["labels"], strict=True) if d < line]
        kept = all(lab == name for lab in above)
        lost = bool(below) and below[0] != name
        ok &= kept and lost
        parts.append(f"{name}: d_crit {line:.3f}, kept above {'yes' if kept else 'NO'}, "
                     f"lost below {'yes' if lost else 'NO'}")
    return Measure(ok, "followed down in d at phi = 5pi/8 (d step 0.1): " + "; ".join(parts),
                   ("fig05", "fig07"))


# ------------------------------------------------------------------ bifurcation (fig. 7)

def _branch(runs, name: str, run: str = "fig07") -> dict:
    b = M.branches(runs(run))[name]
    if not b["falls_to"]:
        b["falls_to"] = f"still {b['labels'][-1]} at the diagram's end (d = {b['d'][-1]:g})"
    return b


def _grid_reading(runs, name: str, what: str) -> list[Measure]:
    """Explanations of a destruction point or impacting range end: read off a diagram's d
    grid (the study's step is not stated) instead of located."""
    out = []
    for run, step in (("fig07", "0.1"), ("fig07_step005", "0.05")):
        b = _branch(runs, name, run)
        if what == "destroyed":
            value = M.first_grid_d(b, lambda n, own=name: n != own)
            said = "first d with impacts"
        else:
            value = M.first_grid_d(b, lambda n, to=b["falls_to"]: n == to)
            said = f"first d on {b['falls_to']}"
        out.append(Measure(value, f"{value:.2f} ({said})", (run,),
                           label=f"read off a d grid of step {step} from 22.5 "
                           "(the study's step is not stated)"))
    return out


def _destroyed(st, runs, name: str) -> Measure:
    b = _branch(runs, name)
    m = Measure(b["destroyed_at"], f"{b['destroyed_at']:.3f} (grazing located by bisection; "
                f"then {b['falls_to']})", ("fig07",), tolerance=1e-3)
    continued = _continuation(runs)
    if continued is not None:  # a cross-check, not an explanation: left out when not made
        graze = M.stable_impacting_leg(continued, name)["grazing"]
        m.runs += ("fig07_continuation",)
        m.note = (f"the continuation of the branch (run fig07_continuation) grazes at "
                  f"{graze:.6f}, {abs(graze - b['destroyed_at']):.0e} from the bisection")
    m.alternatives = _grid_reading(runs, name, "destroyed")
    return m


def _continuation(runs):
    """Figure 7's continuation result, or None when the run is not made (--cached-only)."""
    try:
        return runs("fig07_continuation")
    except MissingRun:
        return None


CONTINUED = "the end of the stable impacting branch by continuation (its fold)"


def _continuation_end(st, runs, name: str) -> Measure:
    """Where the stable impacting orbit born at the grazing ends when it is continued
    (run fig07_continuation): its fold (a multiplier through +1), and whether the study's
    value can be that end (the orbit is stable there: it cannot, unless the study's value
    is the fold within its precision)."""
    leg = M.stable_impacting_leg(runs("fig07_continuation"), name)
    study, precision = float(st["study"]), float(st.get("precision", 0.0))
    ends_in_fold = bool(np.isfinite(leg["fold"]))
    value = leg["fold"] if ends_in_fold else leg["low"]
    what = ("fold, multiplier +1" if ends_in_fold else
            f"no fold: still stable and impacting at the continuation's end ({leg['end']})")
    m = Measure(value, "", ("fig07_continuation",), tolerance=1e-4, label=CONTINUED)
    if agrees("value", study, precision, m):
        verdict = f"the study's {study:g} is that end within its precision"
    elif value <= study <= leg["high"]:
        at = float(np.interp(study, leg["parameter"], leg["modulus"]))
        verdict = (f"at the study's d = {study:g} the impacting orbit is stable (largest "
                   f"|mu| {at:.3f}): the stable branch does not end there")
    else:
        verdict = (f"the study's d = {study:g} is outside the stable impacting range "
                   f"{value:.4f}-{leg['high']:.4f}")
    m.shown = (f"{value:.4f} ({what}; stable and impacting from the grazing at "
               f"{leg['grazing']:.6f} down to it; {verdict})")
    return m


def _impacting_end(st, runs, name: str) -> Measure:
    b = _branch(runs, name)
    lo = min(b["impacting_range"])
    m = Measure(lo, f"{lo:.3f} (impacting range {min(b['impacting_range']):.3f}-"
                f"{max(b['impacting_range']):.3f}, then {b['falls_to']})", ("fig07",),
                tolerance=0.1)
    m.note = "softimpact's range ends are the d grid's (step 0.1): tolerance 0.1"
    m.alternatives = _grid_reading(runs, name, "falls")
    if _continuation(runs) is None:
        m.pending.append("fig07_continuation")
        return m
    continued = _continuation_end(st, runs, name)
    m.alternatives.append(continued)
    if agrees("value", st["study"], float(st.get("precision", 0.0)), m):
        said = "agrees" if agrees("value", st["study"], float(st.get("precision", 0.0)),
                                  continued) else "does not agree"
        m.note += (f"; {continued.label}: {continued.shown} ({said}; run "
                   f"fig07_continuation)")  # a reproduced row shows its note only
    return m


def _impacting_end_and_fall(st, runs, name: str) -> Measure:
    """:func:`_impacting_end`, noting the branch it falls to (the study's: L1^1 R1-0^1)."""
    m = _impacting_end(st, runs, name)
    m.note += f"; it falls to {_branch(runs, name)['falls_to']} (study: L1^1 R1-0^1)"
    return m


# the figure 7 branches: where each is destroyed, and where its impacting stretch ends
CHECKS.update({
    "destroyed_L12R102": partial(_destroyed, name="L1^2 R1-0^2"),
    "destroyed_L11R102": partial(_destroyed, name="L1^1 R1-0^2"),
    "destroyed_L12R101": partial(_destroyed, name="L1^2 R1-0^1"),
    "destroyed_L11R101": partial(_destroyed, name="L1^1 R1-0^1"),
    "impacting_end_L12R102": partial(_impacting_end, name="L1^2 R1-0^2"),
    "impacting_end_L11R102": partial(_impacting_end_and_fall, name="L1^1 R1-0^2"),
    "impacting_end_L12R101": partial(_impacting_end_and_fall, name="L1^2 R1-0^1"),
})


@check("falls_to_L12R102")
def falls_to_l12r102(st, runs):
    to = _branch(runs, "L1^2 R1-0^2")["falls_to"]
    return Measure([to], to, ("fig07",))


@check("fig07_branch_count")
def fig07_branch_count(st, runs):
    return _counted(list(M.branches(runs("fig07"))), "branches", "fig07")


@check("fig07_three_after_first")
def fig07_three_after_first(st, runs):
    b = M.branches(runs("fig07"))
    first = max(v["destroyed_at"] for v in b.values())
    alive = [n for n, v in b.items() if v["destroyed_at"] < first]
    return Measure(len(alive), f"{len(alive)} below d = {first:.3f}: {_names(alive)}",
                   ("fig07",))


@check("fig07_transients")
def fig07_transients(st, runs):
    b = M.branches(runs("fig07"))
    parts = []
    ok = True
    for n, v in b.items():
        lo, hi = min(v["impacting_range"]), max(v["impacting_range"])
        has = np.isfinite(lo) and hi > lo - 1e-12
        ends = not M.is_impacting(v["falls_to"]) or n == "L1^1 R1-0^1"
        ok &= bool(has)
        parts.append(f"{n}: impacting {lo:.2f}-{hi:.2f}, then "
                     f"{v['falls_to'] or 'still impacting at the end'}")
        ok &= ends
    m = Measure(ok, "; ".join(parts), ("fig07",), note="the last solution, L1^1 R1-0^1, "
                "can only fall to an impacting one (S35)")
    ds = _continuation(runs)
    if ds is not None:
        legs = {n: M.stable_impacting_leg(ds, n) for n in b}
        m.runs += ("fig07_continuation",)
        m.note += "; continued in d (run fig07_continuation): " + "; ".join(
            f"{n}: stable impacting {leg['high']:.4f}-{leg['low']:.4f}, "
            + (f"ends in a fold at {leg['fold']:.4f}" if np.isfinite(leg["fold"]) else
               f"still stable at the continuation's end ({leg['end']})")
            for n, leg in legs.items())
    return m


@check("fig07_settles_nonimpacting")
def fig07_settles_nonimpacting(st, runs):
    b = M.branches(runs("fig07"))
    settled = [n for n, v in b.items() if M.is_solution(v["falls_to"])]
    return Measure(bool(settled), f"{len(settled)} of {len(b)} branches pass impacting "
                   f"transients and settle on a non-impacting solution: {_names(settled)}",
                   ("fig07",))


@check("fig07_below_red_line")
def fig07_below_red_line(st, runs):
    b = M.branches(runs("fig07"))
    last = [v["labels"][-1] for v in b.values()]
    d_last = float(next(iter(b.values()))["d"][-1])
    plane = M.plane_points(runs("fig07_basins"))
    coexist = [p for p in plane if M.found(p)[0] and M.found(p)[1]]
    ok = all(M.is_impacting(n) for n in last) and len(coexist) == len(plane)
    return Measure(ok, f"at d = {d_last:.2f} every branch is on {_names(sorted(set(last)))}; "
                   f"impacting and non-impacting coexist at {len(coexist)} of {len(plane)} "
                   "basin planes of figure 7", ("fig07", "fig07_basins"))




@check("fig13_each_eliminable")
def fig13_each_eliminable(st, runs):
    ds = runs("fig13_dcrit")
    tops = {n: float(M.dcrit_curve(ds, n)[1].max()) for n in M.combination_names(ds)}
    lowest = min(tops, key=tops.get)
    return Measure(len(tops) > 0 and tops[lowest] > 0.0,
                   f"every one of the {len(tops)} states has d_crit > 0 at some phi (so a d "
                   f"below it destroys it); the smallest maximum is {tops[lowest]:.3f} "
                   f"({lowest})", ("fig13_dcrit",))
