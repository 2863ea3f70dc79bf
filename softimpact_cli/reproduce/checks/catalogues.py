"""Parameters, the shift rule and the attractor catalogues (figures 3, 4, 9, 10, 13)."""

from __future__ import annotations

import math  # noqa: F401
from math import gcd

import numpy as np

from ...analysis.labels import parse_label
from ...kinds.scene import parse_scene
from .. import measures as M
from ..verdicts import Measure
from . import _counted, _names, check

# ------------------------------------------------------------------ parameters, rules



def _defaults(model: str, study: dict) -> Measure:
    scene = parse_scene(f'[system]\nmodel = "{model}"\n[analysis]\nkind = "dcrit"\n')
    values = {"M": 1.0, **scene.values}  # mass 1: the models are written for M = 1
    wrong = {k: values.get(k) for k, v in study.items() if values.get(k) != v}
    shown = ", ".join(f"{k} = {values.get(k)}" for k in study)
    return Measure(not wrong, f"defaults: {shown}" + (f"; differ: {wrong}" if wrong else ""),
                   ("defaults of a scene with only [system] model",))


@check("duffing_parameters")
def duffing_parameters(st, runs):
    return _defaults("duffing", st["study"])


@check("bilinear_parameters")
def bilinear_parameters(st, runs):
    m = _defaults("bilinear", st["study"])
    m.note = "the scenes of figures 9-12, 14(a, b), 15(a) state w = 0.86, F = 0.518"
    return m


@check("rk4_available")
def rk4_available(st, runs):
    scene = parse_scene('[system]\nmodel = "duffing"\n[analysis]\nkind = "dcrit"\n'
                        '[integrator]\nmethod = "rk4"\nsteps_per_period = 1440\n'
                        'locate_switches = false\n')
    i = scene.integrator
    ok = i.traits.fixed_step and i.steps_per_period == 1440 and not i.locate_switches
    return Measure(ok, "[integrator] method = \"rk4\", steps_per_period = 1440, "
                   "locate_switches = false is accepted (softimpact's default is 'auto')",
                   ("scene parse",))


@check("gcd_rule")
def gcd_rule(st, runs):
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
    return _counted(M.combination_names(runs("fig10")), "states", "fig10")


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
    """The caption's F = 0.602 against the text's 0.603: the statement is an inconsistency
    of the study; the explanation tried is that it is a typo without consequence (both
    forces give the same attractors and states)."""
    a = sorted(M.attractor_periods(runs("fig13_catalogue")))
    b = sorted(M.attractor_periods(runs("fig13_catalogue_F0602")))
    na = len(M.combination_names(runs("fig13_catalogue")))
    nb = len(M.combination_names(runs("fig13_catalogue_F0602")))
    m = Measure(False, "the scenes use the text's F = 0.603 (the caption's 0.602 differs)",
                ("fig13_catalogue",))
    m.alternatives.append(Measure(
        a == b and na == nb, f"F = 0.603: periods {a}, {na} states; F = 0.602: periods "
        f"{b}, {nb} states", ("fig13_catalogue", "fig13_catalogue_F0602"),
        label="a typo without consequence (same attractors and states at both forces)"))
    return m


@check("fig13_state_count")
def fig13_state_count(st, runs):
    names = M.combination_names(runs("fig13_catalogue"))
    return Measure(len(names), f"{len(names)} states", ("fig13_catalogue",))


