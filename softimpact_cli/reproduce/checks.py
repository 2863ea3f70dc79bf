"""One function per kind of statement: it reads the runs it needs (``runs(name)`` returns
a result dataset) and returns softimpact's :class:`~.verdicts.Measure`, with the
candidate explanations it tried as alternatives. The study's numbers come from the
statement (``st``), softimpact's from the runs; nothing here is typed in from either."""

from __future__ import annotations

import math

import numpy as np

from ..labels import parse_label
from . import measures as M
from .runs import MissingRun
from .verdicts import Measure

CHECKS = {}
PI = math.pi


def check(name: str):
    def register(fn):
        CHECKS[name] = fn
        return fn
    return register


def _names(names) -> str:
    return ", ".join(names) if names else "none"


def _pct(x: float) -> str:
    return f"{100 * x:.1f}%"


def _share_text(values, cis, n) -> str:
    return " / ".join(f"{_pct(v)} [{_pct(lo)}, {_pct(hi)}]" for v, (lo, hi)
                      in zip(values, cis, strict=True)) + f" (95% Wilson, n = {n})"


# ------------------------------------------------------------------ parameters, rules

STUDY_DUFFING = {"k1": 1.0, "k2": 0.01, "c": 0.05, "F": 1.0, "w": 1.3, "k_c": 8.0, "c_c": 10.0}
STUDY_BILINEAR = {"k1": 1.0, "k2": 29.0, "c": 0.02, "F": 0.518, "w": 0.86, "d1": 1.26,
                  "k_c": 8.0, "c_c": 10.0}


def _defaults(model: str, study: dict) -> Measure:
    from ..config import parse_scene

    scene = parse_scene(f'[system]\nmodel = "{model}"\n[analysis]\nkind = "dcrit"\n')
    values = dict(scene.values)
    wrong = {k: values.get(k) for k, v in study.items() if values.get(k) != v}
    shown = ", ".join(f"{k} = {values.get(k)}" for k in study)
    return Measure(not wrong, f"defaults: {shown}" + (f"; differ: {wrong}" if wrong else ""),
                   ("defaults of a scene with only [system] model",))


@check("duffing_parameters")
def duffing_parameters(st, runs):
    return _defaults("duffing", STUDY_DUFFING)


@check("bilinear_parameters")
def bilinear_parameters(st, runs):
    m = _defaults("bilinear", STUDY_BILINEAR)
    m.note = "the scenes of figures 9-12, 14(a, b), 15(a) state w = 0.86, F = 0.518"
    return m


@check("rk4_available")
def rk4_available(st, runs):
    from ..config import parse_scene

    scene = parse_scene('[system]\nmodel = "duffing"\n[analysis]\nkind = "dcrit"\n'
                        '[integrator]\nmethod = "rk4"\nsteps_per_period = 1440\n'
                        'locate_switches = false\n')
    i = scene.integrator
    ok = i.resolved_method == "rk4" and i.steps_per_period == 1440 and not i.locate_switches
    return Measure(ok, "[integrator] method = \"rk4\", steps_per_period = 1440, "
                   "locate_switches = false is accepted (softimpact's default is 'auto')",
                   ("scene parse",))


@check("gcd_rule")
def gcd_rule(st, runs):
    from math import gcd

    ds = runs("fig10")
    names = M.combination_names(ds)
    two_five = [n for n in names if parse_label(n).period == 2
                and parse_label(n).right_period == 5]
    ok = (gcd(2, 5) == 1 and 2 * 5 // gcd(2, 5) == 10 and gcd(4, 6) == 2
          and len(two_five) == 1 and {"L2^1 R2-0^1", "L2^1 R2-1^1"} <= set(names))
    try:
        parse_label("L2^1 R5-1^2")
        rejects = False
    except ValueError:
        rejects = True
    return Measure(ok and rejects,
                   f"(2,5): {len(two_five)} combination ({_names(two_five)}), joint period "
                   f"{int(ds['combination_period'].values[names.index(two_five[0])])}"
                   if two_five else "(2,5): none",
                   ("fig10",), note="softimpact's names obey s < gcd(pl, pr) (it rejects "
                   "'L2^1 R5-1^2'); (4,6) gives s = 0, 1 by the same rule")


# ------------------------------------------------------------------ catalogues

@check("duffing_two_period1")
def duffing_two_period1(st, runs):
    ds = runs("fig04")
    periods = M.attractor_periods(ds)
    amps = [float(a) for a in ds["attractor_amplitude"].values]
    ok = periods == [1, 1] and abs(amps[0] - amps[1]) > 0.1 * max(amps)
    return Measure(ok, f"{len(periods)} attractors, periods {periods}, amplitudes "
                   + ", ".join(f"{a:.4f}" for a in amps), ("fig04",))


@check("duffing_combinations")
def duffing_combinations(st, runs):
    names = M.combination_names(runs("fig04"))
    return Measure(names, _names(names), ("fig04",))


@check("duffing_phase_lag")
def duffing_phase_lag(st, runs):
    ds = runs("fig04")
    curve = ds["attractor_curve"].values  # (attractor, sample, (x, v))
    peaks = [int(np.nanargmax(c[:, 0])) for c in curve]
    n = int(np.sum(np.isfinite(curve[0, :, 0])))
    lag = abs(peaks[0] - peaks[1]) / max(n, 1)
    lag = min(lag, 1 - lag)
    return Measure(lag > 0.01, f"the maxima of x on the two period-1 orbits are "
                   f"{lag:.3f} T apart at phi = 0", ("fig04",))


@check("bilinear_periods")
def bilinear_periods(st, runs):
    periods = M.attractor_periods(runs("fig10"))
    names = [f"period {p}" for p in sorted(periods)]
    return Measure(names, _names(names), ("fig10",))


def _left_period(st, runs, p):
    names = [n for n in M.combination_names(runs("fig10")) if parse_label(n).period == p]
    return Measure(names, _names(names), ("fig10",))


@check("bilinear_left_period2")
def bilinear_left_period2(st, runs):
    return _left_period(st, runs, 2)


@check("bilinear_left_period5")
def bilinear_left_period5(st, runs):
    return _left_period(st, runs, 5)


@check("bilinear_state_count")
def bilinear_state_count(st, runs):
    names = M.combination_names(runs("fig10"))
    return Measure(len(names), f"{len(names)} states: {_names(names)}", ("fig10",))


@check("fig11_third_label")
def fig11_third_label(st, runs):
    names = M.combination_names(runs("fig11"))
    label = st["study"][0]
    try:
        parse_label(label)
        legal = True
    except ValueError:
        legal = False
    m = Measure([n for n in names if n == label] or ["(no such state)"],
                f"softimpact has no {label} (gcd(2, 5) = 1 allows only s = 0): its states "
                f"with left L2^1 and right period 5: "
                f"{_names([n for n in names if n.startswith('L2^1 R5')])}", ("fig11",))
    typo = [n for n in names if n.startswith("L2^1 R5-0^2")]
    m.alternatives.append(Measure(
        [label] if (not legal and typo) else [], "the label breaks the study's own gcd rule "
        "(s < gcd(2, 5) = 1) and the one state it can mean, L2^1 R5-0^2, is in the "
        "catalogue: a typo for L2^1 R5-0^2", ("fig11", "labels.parse_label"),
        label="typo (gcd rule)"))
    return m


@check("fig13_periods")
def fig13_periods(st, runs):
    periods = M.attractor_periods(runs("fig13_catalogue"))
    names = [f"period {p}" for p in sorted(periods)]
    return Measure(names, _names(names), ("fig13_catalogue",))


@check("fig13_caption_force")
def fig13_caption_force(st, runs):
    a = sorted(M.attractor_periods(runs("fig13_catalogue")))
    b = sorted(M.attractor_periods(runs("fig13_catalogue_F0602")))
    na = len(M.combination_names(runs("fig13_catalogue")))
    nb = len(M.combination_names(runs("fig13_catalogue_F0602")))
    return Measure(a == b and na == nb,
                   f"F = 0.603: periods {a}, {na} states; F = 0.602: periods {b}, {nb} states"
                   " (the caption's value gives the same attractors: the two are "
                   "indistinguishable at the level of the figure)",
                   ("fig13_catalogue", "fig13_catalogue_F0602"))


@check("fig13_state_count")
def fig13_state_count(st, runs):
    names = M.combination_names(runs("fig13_catalogue"))
    return Measure(len(names), f"{len(names)} states", ("fig13_catalogue",))


# ------------------------------------------------------------------ critical distances

RK4_STUDY = dict(method="rk4", steps_per_period=1440, locate_switches=False)


def _attractors(ds) -> list:
    """The catalogue's attractors rebuilt from a result (no search rerun)."""
    from ..analysis.catalogue import Attractor

    out = []
    for i, number in enumerate(ds["attractor"].values):
        p = int(ds["attractor_period"].values[i])
        mult = ds["multiplier_re"].values[i] + 1j * ds["multiplier_im"].values[i]
        out.append(Attractor(int(number), p, ds["attractor_points"].values[i, :p].copy(),
                             float(ds["attractor_amplitude"].values[i]),
                             mult[np.isfinite(mult)], float(ds["attractor_share"].values[i]),
                             float(ds["attractor_residual"].values[i])))
    return out


def dcrit_study_method(run, ds, name: str, phi: float, periods: int = 40) -> float:
    """d_crit as the study computes it: the uncoupled pair integrated by plain RK4 at
    T/1440 from the combination's joint orbit, x1 - x2 maximised over the 1440 step points
    of the last joint period (no location of the maximum between steps)."""
    from ..analysis.catalogue import body_problem, combinations, right_attractors
    from ..analysis.critical_distance import relative_trace, uncoupled_pair
    from ..config import IntegratorSettings

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
    from .runs import RUNS

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
    near10 = all(9.0 <= c.max() <= 11.0 for c in (a, b))
    return Measure(mirror < 1e-6 and near10,
                   f"max d_crit {a.max():.3f} and {b.max():.3f}; "
                   f"max |d_A(phi) - d_B(2 pi - phi)| = {mirror:.1e}", ("fig05",),
                   note="'around d = 10' read as a maximum within [9, 11]")


@check("dcrit_biggest_range")
def dcrit_biggest_range(st, runs):
    ds = runs("fig05")
    spans = {n: float(np.ptp(M.dcrit_curve(ds, n)[1])) for n in M.combination_names(ds)}
    top = max(spans, key=spans.get)
    return Measure(top == "L1^2 R1-0^2", "range of d_crit over phi: "
                   + ", ".join(f"{n} {v:.2f}" for n, v in spans.items()), ("fig05",))


@check("dcrit_borders")
def dcrit_borders(st, runs):
    ds, bif = runs("fig05"), runs("fig07")
    gaps = {n: abs(b["destroyed_at"] - M.dcrit_at(ds, n, 5 * PI / 8))
            for n, b in M.branches(bif).items()}
    return Measure(max(gaps.values()) < 1e-3,
                   "following each solution down in d at phi = 5pi/8, it is destroyed where "
                   "d crosses its d_crit line: |destroyed_at - d_crit| = "
                   + ", ".join(f"{g:.1e}" for g in gaps.values()), ("fig05", "fig07"))


# ------------------------------------------------------------------ bifurcation (fig. 7)

def _branch(runs, name: str, run: str = "fig07") -> dict:
    return M.branches(runs(run))[name]


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
                f"falls to {b['falls_to']})", ("fig07",), tolerance=1e-3)
    m.alternatives = _grid_reading(runs, name, "destroyed")
    return m


def _impacting_end(st, runs, name: str) -> Measure:
    b = _branch(runs, name)
    lo = min(b["impacting_range"])
    m = Measure(lo, f"{lo:.3f} (impacting range {min(b['impacting_range']):.3f}-"
                f"{max(b['impacting_range']):.3f}, then {b['falls_to']})", ("fig07",),
                tolerance=0.1)
    m.note = "softimpact's range ends are the d grid's (step 0.1): tolerance 0.1"
    m.alternatives = _grid_reading(runs, name, "falls")
    return m


@check("destroyed_L12R102")
def destroyed_l12r102(st, runs):
    return _destroyed(st, runs, "L1^2 R1-0^2")


@check("destroyed_L11R102")
def destroyed_l11r102(st, runs):
    return _destroyed(st, runs, "L1^1 R1-0^2")


@check("destroyed_L12R101")
def destroyed_l12r101(st, runs):
    return _destroyed(st, runs, "L1^2 R1-0^1")


@check("destroyed_L11R101")
def destroyed_l11r101(st, runs):
    m = _destroyed(st, runs, "L1^1 R1-0^1")
    m.note = f"then {_branch(runs, 'L1^1 R1-0^1')['falls_to']}"
    return m


@check("impacting_end_L12R102")
def impacting_end_l12r102(st, runs):
    return _impacting_end(st, runs, "L1^2 R1-0^2")


@check("impacting_end_L11R102")
def impacting_end_l11r102(st, runs):
    m = _impacting_end(st, runs, "L1^1 R1-0^2")
    m.note += f"; it falls to {_branch(runs, 'L1^1 R1-0^2')['falls_to']} (study: L1^1 R1-0^1)"
    return m


@check("impacting_end_L12R101")
def impacting_end_l12r101(st, runs):
    m = _impacting_end(st, runs, "L1^2 R1-0^1")
    m.note += f"; it falls to {_branch(runs, 'L1^2 R1-0^1')['falls_to']} (study: L1^1 R1-0^1)"
    return m


@check("falls_to_L12R102")
def falls_to_l12r102(st, runs):
    to = _branch(runs, "L1^2 R1-0^2")["falls_to"]
    return Measure([to], to, ("fig07",))


@check("fig07_branch_count")
def fig07_branch_count(st, runs):
    b = M.branches(runs("fig07"))
    return Measure(len(b), f"{len(b)} branches: {_names(list(b))}", ("fig07",))


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
        parts.append(f"{n}: impacting {lo:.2f}-{hi:.2f}, then {v['falls_to']}")
        ok &= ends
    return Measure(ok, "; ".join(parts), ("fig07",), note="the last solution, L1^1 R1-0^1, "
                   "can only fall to an impacting one (S35)")


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


# ------------------------------------------------------------------ plane basins

def _plane(runs, run: str, **where) -> dict:
    return M.point_at(M.plane_points(runs(run)), **where)


def _found_text(p: dict) -> str:
    sol, imp = M.found(p)
    parts = [f"{n} {_pct(p['counts'][n] / p['n'])}" for n in sol + imp]
    return f"{len(sol)} non-impacting" + (f" + {len(imp)} impacting" if imp else "") + \
        f" ({', '.join(parts)}; {p['n']} starts)"


def _count(run: str, with_dcrit: tuple | None = None, **where):
    """Number of solutions found on the plane at a grid point (non-impacting and
    impacting); with_dcrit = (dcrit run, d, phi) adds what the critical distances predict
    there, and at -phi."""
    def fn(st, runs):
        p = _plane(runs, run, **where)
        sol, imp = M.found(p)
        m = Measure(len(sol) + len(imp), _found_text(p), (run,))
        if with_dcrit:
            m.alternatives += _predicted(runs, *with_dcrit, count=True)
        return m
    return fn


def _names_found(run: str, with_dcrit: tuple | None = None, **where):
    def fn(st, runs):
        p = _plane(runs, run, **where)
        sol, imp = M.found(p)
        m = Measure(sol + imp, _found_text(p), (run,))
        if with_dcrit:
            m.alternatives += _predicted(runs, *with_dcrit, count=False)
        return m
    return fn


def _predicted(runs, dcrit_run: str, d: float, phi: float, count: bool) -> list[Measure]:
    ds = runs(dcrit_run)
    out = []
    for label, at in (("existence predicted by d_crit at phi", phi),
                      ("existence predicted by d_crit at -phi (phase sign flipped)",
                       (2 * PI - phi) % (2 * PI))):
        names = M.survivors(ds, d, at)
        out.append(Measure(len(names) if count else names, f"{len(names)}: {_names(names)}",
                           (dcrit_run,), label=label))
    return out


FIG12 = "fig12_dcrit"
for _key, _fn in {
    "fig06a_count": _count("fig06", d=22.0, phi=0.0),
    "fig06c_count": _count("fig06", d=10.5, phi=5.28),
    "fig06d_count": _count("fig06", d=6.0, phi=0.0),
    "fig06e_count": _count("fig06", d=9.0, phi=0.573 * PI),
    "fig06f_count": _count("fig06", d=5.0, phi=PI),
    "fig06b_names": _names_found("fig06", d=15.0, phi=PI),
    "fig06c_names": _names_found("fig06", d=10.5, phi=5.28),
    "fig12a_count": _count("fig12", (FIG12, 10.0, PI), d=10.0, phi=PI),
    "fig12b_count": _count("fig12", (FIG12, 1.332, 0.60916), d=1.332, phi=0.60916),
    "fig12b_names": _names_found("fig12", (FIG12, 1.332, 0.60916), d=1.332, phi=0.60916),
    "fig12c_count": _count("fig12", (FIG12, 1.0, 0.36424), d=1.0, phi=0.36424),
    "fig12c_names": _names_found("fig12", (FIG12, 1.0, 0.36424), d=1.0, phi=0.36424),
    "fig12d_count": _count("fig12", (FIG12, 2.448, PI), d=2.448, phi=PI, c_c=2.0),
    "fig12d_names": _names_found("fig12", (FIG12, 2.448, PI), d=2.448, phi=PI, c_c=2.0),
    "fig13a_count": _count("fig13", ("fig13_dcrit_points", 10.0, PI), d=10.0, phi=PI),
    "fig13b_count": _count("fig13", ("fig13_dcrit_points", 2.0, 0.4), d=2.0, phi=0.4),
}.items():
    CHECKS[_key] = _fn


@check("fig06_no_impacting")
def fig06_no_impacting(st, runs):
    points = M.plane_points(runs("fig06"))
    imp = [(p["d"], M.share(p, "impacting (all)")[0]) for p in points]
    return Measure(all(s == 0 for _, s in imp), "impacting share per panel: "
                   + ", ".join(f"d={d:g}: {_pct(s)}" for d, s in imp), ("fig06",))


@check("fig06a_outside_own_basin")
def fig06a_outside_own_basin(st, runs):
    ds = runs("fig06")
    points = M.plane_points(ds)
    panel = points.index(M.point_at(points, d=22.0, phi=0.0))
    label, axes, table = M.plane_labels(ds, panel)
    ic_dims = str(ds.attrs.get("ic_dims", "")).split()
    names = M.combination_names(ds)
    orbits = ds["combination_orbit"].values
    variables = [str(v) for v in ds["variable"].values]
    outside = []
    for i, name in enumerate(names):
        pts = orbits[i][np.all(np.isfinite(orbits[i]), axis=1)]
        own = 0
        for p in pts:
            idx = tuple(int(np.argmin(np.abs(ax - p[variables.index(dim)])))
                        for ax, dim in zip(axes, ic_dims, strict=True))
            own += table.get(int(label[idx]), "") == name
        if own == 0:
            outside.append(name)
    return Measure(len(outside), f"{len(outside)} of {len(names)} attractors have no "
                   f"stroboscopic point (projected on v1 = v2 = 0) inside their own basin: "
                   f"{_names(outside)}", ("fig06",))


def _impacting_share(run_name: str, d: float):
    def fn(st, runs):
        def one(run):
            p = _plane(runs, run, d=d)
            s, ci = M.share(p, "impacting (all)")
            return Measure(s, _share_text([s], [ci], p["n"]) + " at t0 = "
                           + ("T/2" if "t0half" in run else "0"), (run,), ci=[ci])
        m = one(run_name)
        m.note = "plane shares: Wilson interval over the plane's cells (a stand-in for " \
            "the resolution error)"
        try:
            alt = one(run_name + "_t0half")
            alt.label = "start at t0 = T/2"
            m.alternatives.append(alt)
        except MissingRun as missing:
            m.note += f"; t0 = T/2 not tried yet (needs run {missing.name})"
        return m
    return fn


CHECKS["fig07_impacting_8_2"] = _impacting_share("fig07_basins", 8.2)
CHECKS["fig07_impacting_10_25"] = _impacting_share("fig07_basins", 10.25)
CHECKS["fig07_impacting_16_25"] = _impacting_share("fig07_basins", 16.25)


@check("fig07_impacting_small")
def fig07_impacting_small(st, runs):
    b = M.branches(runs("fig07"))
    widths = [max(v["impacting_range"]) - min(v["impacting_range"]) for n, v in b.items()
              if n != "L1^1 R1-0^1"]
    shares = [M.share(p, "impacting (all)")[0] for p in M.plane_points(runs("fig07_basins"))]
    ok = max(widths) < 1.0 and max(shares) < 0.5
    return Measure(ok, "impacting ranges after destruction "
                   + ", ".join(f"{w:.2f}" for w in widths) + "; impacting basin shares "
                   + ", ".join(_pct(s) for s in shares), ("fig07", "fig07_basins"),
                   note="'small' read as < 1 in d, 'not dominant' as < 50% of the plane")


def _coexist(run: str, want: bool, **where):
    def fn(st, runs):
        p = _plane(runs, run, **where)
        sol, imp = M.found(p)
        ok = bool(sol) and (bool(imp) == want)
        return Measure(ok, _found_text(p), (run,))
    return fn


CHECKS["fig14a_coexist"] = _coexist("fig14ab", True, k_c=8.0)
CHECKS["fig14b_only_nonimpacting"] = _coexist("fig14ab", False, k_c=20.0)
CHECKS["fig14c_coexist"] = _coexist("fig14cd", True, c_c=10.0)
CHECKS["fig14d_only_nonimpacting"] = _coexist("fig14cd", False, c_c=2.0)


@check("fig09_period2_dominant")
def fig09_period2_dominant(st, runs):
    p = M.plane_points(runs("fig09"))[0]
    shares = {n: c / p["n"] for n, c in p["counts"].items()}
    two = sum(v for n, v in shares.items() if n.startswith("L2^"))
    five = sum(v for n, v in shares.items() if n.startswith("L5^"))
    return Measure(two > five, f"period 2: {_pct(two)}, period 5: {_pct(five)} of "
                   f"{p['n']} starts", ("fig09",))


def _boundary(run: str):
    ds = run
    label, _, _ = M.plane_labels(ds, 0)
    return M.boundary_dimension(label)


@check("duffing_smooth_boundary")
def duffing_smooth_boundary(st, runs):
    dim = _boundary(runs("fig03"))
    return Measure(dim < 1.2, f"box-counting dimension of the basin boundary {dim:.2f} "
                   "(1 for a smooth curve; < 1.2 taken as smooth)", ("fig03",))


def _velocity_rows(ds, code_name: str) -> np.ndarray:
    label, _, table = M.plane_labels(ds, 0)
    ic_dims = str(ds.attrs.get("ic_dims", "")).split()
    codes = [c for c, n in table.items() if n.startswith(code_name)]
    hit = np.isin(label, codes)
    return hit.mean(axis=ic_dims.index("x"))  # share per velocity


@check("fig03_velocity_rows")
def fig03_velocity_rows(st, runs):
    rows = _velocity_rows(runs("fig03"), "L1^1")
    return Measure(rows.min() == 0.0 and rows.max() == 1.0,
                   f"share of L1^1 per velocity row: {_pct(rows.min())} to {_pct(rows.max())}",
                   ("fig03",))


@check("fig09_velocity_rows")
def fig09_velocity_rows(st, runs):
    ds = runs("fig09")
    rows = _velocity_rows(ds, "L2^")
    dim = _boundary(ds)
    ok = rows.min() > 0.0 and rows.max() < 1.0
    return Measure(ok, f"share of the period-2 basin per velocity row: {_pct(rows.min())} "
                   f"to {_pct(rows.max())} (no row without either attractor); boundary "
                   f"box-counting dimension {dim:.2f}", ("fig09",),
                   note="'no qualitative change' read as: no velocity row where one "
                   "attractor is absent")


@check("reduced_to_one")
def reduced_to_one(st, runs):
    single = []
    for run in ("fig06", "fig12", "fig13"):
        try:
            points = M.plane_points(runs(run))
        except MissingRun:
            if run == "fig06":  # figure 6(f) is the study's example: needed
                raise
            continue
        for p in points:
            sol, imp = M.found(p)
            if len(sol) + len(imp) == 1:
                single.append(f"{run} d={p['d']:g} phi={p['phi']:.4g}: {sol[0] if sol else imp[0]}")
    return Measure(bool(single), "; ".join(single) or "no panel with a single solution",
                   ("fig06", "fig12", "fig13"))


@check("stop_parameters_eliminate")
def stop_parameters_eliminate(st, runs):
    b = _plane(runs, "fig14ab", k_c=20.0)
    d = _plane(runs, "fig14cd", c_c=2.0)
    sb, sd = M.share(b, "impacting (all)")[0], M.share(d, "impacting (all)")[0]
    return Measure(sb == 0 and sd == 0, f"impacting share: bilinear k_c = 20 {_pct(sb)}, "
                   f"Duffing c_c = 2 {_pct(sd)} (plane, t0 = 0)", ("fig14ab", "fig14cd"))


# ------------------------------------------------------------------ basin stability

def _stability(runs, run: str, **where) -> dict:
    points = M.stability_points(runs(run))
    for p in points:
        if all(p.get(k) == v if isinstance(v, str) else abs(float(p[k]) - v) < 1e-6
               for k, v in where.items()):
            return p
    raise KeyError(f"{run}: no point at {where}")


def _shares(p: dict, groups: list[str]) -> tuple[list[float], list[tuple[float, float]]]:
    values, cis = [], []
    for g in groups:
        s, ci = M.share(p, g)
        values.append(s)
        cis.append(ci)
    return values, cis


def _share_measure(p: dict, groups: list[str], run: str, label: str = "") -> Measure:
    values, cis = _shares(p, groups)
    return Measure(values if len(values) > 1 else values[0],
                   _share_text(values, cis, p["n"]), (run,), ci=cis, label=label)


DUFFING_C = ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^2", "impacting (all)"]
DUFFING_D = ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^2"]
T0S = (("T/4", 0.25), ("T/2", 0.5), ("3T/4", 0.75))


def _t0_values(runs, run: str) -> dict:
    """{t0 label: point} of a stability run over t0 (fig14c_t0 and fig14d_t0)."""
    from .runs import RUNS

    ds = runs(run)
    period = 2 * PI / float(RUNS[run].scene().values["w"])
    out = {}
    for p in M.stability_points(ds):
        frac = float(p["t0"]) / period
        out[next((s for s, f in T0S if abs(f - frac) < 1e-6), "0" if frac < 1e-9
                 else f"{frac:.3f} T")] = p
    return out


def _menck(runs, c_c: float, groups: list[str]) -> Measure:
    m = _share_measure(_stability(runs, "fig15b", c_c=c_c), groups, "fig15b")
    m.shown += ", t0 = 0"
    t0s = "fig14c_t0" if c_c == 10.0 else "fig14d_t0"
    for key, p in _t0_values(runs, t0s).items():
        if key != "0":
            m.alternatives.append(_share_measure(p, groups, t0s, label=f"start at t0 = {key}"))
    if c_c == 10.0:
        p = M.stability_points(runs("fig14c_random_t0"))[0]
        m.alternatives.append(_share_measure(p, groups, "fig14c_random_t0",
                                             label="t0 uniform in [0, T) per sample"))
    return m


def _plane_shares(runs, c_c: float, groups: list[str]) -> Measure:
    m = _share_measure(_plane(runs, "fig14cd", c_c=c_c), groups, "fig14cd")
    m.shown += ", t0 = 0"
    m.note = "plane shares: Wilson interval over the plane's cells"
    try:
        m.alternatives.append(_share_measure(_plane(runs, "fig14cd_t0half", c_c=c_c), groups,
                                             "fig14cd_t0half", label="start at t0 = T/2"))
    except MissingRun as missing:
        m.note += f"; t0 = T/2 not tried yet (needs run {missing.name})"
    return m


@check("fig14c_plane_shares")
def fig14c_plane_shares(st, runs):
    return _plane_shares(runs, 10.0, DUFFING_C)


@check("fig14d_plane_shares")
def fig14d_plane_shares(st, runs):
    return _plane_shares(runs, 2.0, DUFFING_D)


@check("fig14c_menck_shares")
def fig14c_menck_shares(st, runs):
    return _menck(runs, 10.0, DUFFING_C)


@check("fig14d_menck_shares")
def fig14d_menck_shares(st, runs):
    return _menck(runs, 2.0, DUFFING_D)


@check("fig14a_plane_share")
def fig14a_plane_share(st, runs):
    m = _share_measure(_plane(runs, "fig14ab", k_c=8.0), ["non-impacting (sum)"], "fig14ab")
    try:
        m.alternatives.append(_share_measure(_plane(runs, "fig14ab_t0half", k_c=8.0),
                                             ["non-impacting (sum)"], "fig14ab_t0half",
                                             label="start at t0 = T/2"))
    except MissingRun as missing:
        m.note = f"t0 = T/2 not tried yet (needs run {missing.name})"
    return m


@check("fig14a_menck_share")
def fig14a_menck_share(st, runs):
    return _share_measure(_stability(runs, "fig15a", k_c=8.0), ["non-impacting (sum)"],
                          "fig15a")


@check("bilinear_agreement")
def bilinear_agreement(st, runs):
    plane = M.share(_plane(runs, "fig14ab", k_c=8.0), "non-impacting (sum)")
    menck = M.share(_stability(runs, "fig15a", k_c=8.0), "non-impacting (sum)")
    overlap = plane[1][0] <= menck[1][1] and menck[1][0] <= plane[1][1]
    return Measure(overlap, f"figure 14(a): plane {_pct(plane[0])}, basin stability "
                   f"{_pct(menck[0])} [{_pct(menck[1][0])}, {_pct(menck[1][1])}]: intervals "
                   f"{'overlap' if overlap else 'do not overlap'}", ("fig14ab", "fig15a"))


@check("fig14b_both_full")
def fig14b_both_full(st, runs):
    plane = M.share(_plane(runs, "fig14ab", k_c=20.0), "non-impacting (sum)")[0]
    menck = M.share(_stability(runs, "fig15a", k_c=20.0), "non-impacting (sum)")[0]
    return Measure(plane == 1.0 and menck == 1.0, f"plane {_pct(plane)}, basin stability "
                   f"{_pct(menck)}", ("fig14ab", "fig15a"))


@check("duffing_method_difference")
def duffing_method_difference(st, runs):
    diffs = []
    for c_c, groups in ((10.0, DUFFING_C), (2.0, DUFFING_D)):
        plane = _shares(_plane(runs, "fig14cd", c_c=c_c), groups)[0]
        menck = _shares(_stability(runs, "fig15b", c_c=c_c), groups)[0]
        diffs += [abs(a - b) for a, b in zip(plane, menck, strict=True)]
    worst = max(diffs)
    return Measure(worst, f"largest |plane - basin stability| over figure 14(c, d): "
                   f"{_pct(worst)} (both at t0 = 0)", ("fig14cd", "fig15b"),
                   tolerance=0.03, note="tolerance 3 points: the Wilson half-width at "
                   "N = 1000")


@check("fig15_settings")
def fig15_settings(st, runs):
    from .runs import RUNS

    parts, ok = [], True
    for name, box, axis, lo, hi in (("fig15a", 2.0, "k_c", 5.0, 20.0),
                                    ("fig15b", 12.0, "c_c", 1.0, 11.0)):
        scene = RUNS[name].scene()
        ic = scene.initial_conditions
        values = scene.grid.axes[axis]
        arr = ic.array()
        ok &= ic.count == 1000 and np.all(np.abs(arr) <= box) and \
            (values[0], values[-1]) == (lo, hi)
        parts.append(f"{name}: N = {ic.count}, samples in [-{box:g}, {box:g}]^4, "
                     f"{axis} {values[0]:g}..{values[-1]:g} ({len(values)} points)")
    return Measure(bool(ok), "; ".join(parts), ("fig15a", "fig15b scenes"))


def _nonimpacting_reached(run: str):
    def fn(st, runs):
        names = set()
        for p in M.stability_points(runs(run)):
            names |= {n for n, c in p["counts"].items() if c > 0 and M.is_solution(n)}
        return Measure(len(names), f"{len(names)} reached: {_names(sorted(names))}", (run,))
    return fn


CHECKS["fig15a_nonimpacting_count"] = _nonimpacting_reached("fig15a")
CHECKS["fig15b_nonimpacting_count"] = _nonimpacting_reached("fig15b")


def _curve(runs, run: str, axis: str, group: str):
    points = M.stability_points(runs(run))
    return [(p[axis], *M.share(p, group)) for p in points]


@check("fig15a_over_75")
def fig15a_over_75(st, runs):
    curve = _curve(runs, "fig15a", "k_c", "non-impacting (sum)")
    low = min(curve, key=lambda c: c[1])
    return Measure(low[1] > st["study"], f"lowest non-impacting share {_pct(low[1])} "
                   f"[{_pct(low[2][0])}, {_pct(low[2][1])}] at k_c = {low[0]:g}", ("fig15a",))


@check("fig15a_full_above")
def fig15a_full_above(st, runs):
    curve = _curve(runs, "fig15a", "k_c", "non-impacting (sum)")
    above = [c for c in curve if c[0] > st["study"]]
    full = [c[0] for c in curve if c[1] == 1.0]
    ok = bool(above) and all(c[1] == 1.0 for c in above)
    return Measure(ok, "100% at k_c = " + (", ".join(f"{k:g}" for k in full) or "none")
                   + f" (grid step {curve[1][0] - curve[0][0]:g})", ("fig15a",))


@check("fig15a_fluctuations")
def fig15a_fluctuations(st, runs):
    curve = _curve(runs, "fig15a", "k_c", "non-impacting (sum)")
    s = np.array([c[1] for c in curve])
    jumps = np.abs(np.diff(s))
    half = np.mean([(c[2][1] - c[2][0]) / 2 for c in curve])
    ok = half <= 2 * st["study"]
    return Measure(ok, f"median step-to-step change {_pct(np.median(jumps))}, largest "
                   f"{_pct(jumps.max())}; mean 95% Wilson half-width {_pct(half)}",
                   ("fig15a",), note="'around 2%' compared with the sampling half-width "
                   "(within twice 2%)")


@check("fig15b_impacting_max")
def fig15b_impacting_max(st, runs):
    curve = _curve(runs, "fig15b", "c_c", "impacting (all)")
    top = max(curve, key=lambda c: c[1])
    m = Measure(top[2][0] <= st["study"], f"largest impacting share {_pct(top[1])} "
                f"[{_pct(top[2][0])}, {_pct(top[2][1])}] at c_c = {top[0]:g} (t0 = 0)",
                ("fig15b",))
    return m


@check("fig15b_no_impacting_low")
def fig15b_no_impacting_low(st, runs):
    curve = _curve(runs, "fig15b", "c_c", "impacting (all)")
    low = [c for c in curve if c[0] < st["study"]]
    return Measure(bool(low) and all(c[1] == 0.0 for c in low), "impacting share at c_c = "
                   + ", ".join(f"{c[0]:g}: {_pct(c[1])}" for c in low), ("fig15b",))


@check("fig15b_sum_constant")
def fig15b_sum_constant(st, runs):
    curve = _curve(runs, "fig15b", "c_c", "non-impacting (sum)")
    s = np.array([c[1] for c in curve])
    return Measure(np.ptp(s) <= 0.1, f"non-impacting sum from {_pct(s.min())} to "
                   f"{_pct(s.max())} over c_c", ("fig15b",),
                   note="'nearly constant' read as a range within 10 points")


@check("fig13_each_eliminable")
def fig13_each_eliminable(st, runs):
    ds = runs("fig13_dcrit")
    tops = {n: float(M.dcrit_curve(ds, n)[1].max()) for n in M.combination_names(ds)}
    lowest = min(tops, key=tops.get)
    return Measure(len(tops) > 0 and tops[lowest] > 0.0,
                   f"every one of the {len(tops)} states has d_crit > 0 at some phi (so a d "
                   f"below it destroys it); the smallest maximum is {tops[lowest]:.3f} "
                   f"({lowest})", ("fig13_dcrit",))
