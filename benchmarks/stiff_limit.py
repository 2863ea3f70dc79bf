"""The stiff limit (issue 33, item 4): a soft wall with k_c -> infinity and c_c set for the
rigid wall's restitution tends to the rigid law, the distance of its stroboscopic orbit
falling as k_c^(-1/2) (the contact lasts pi / sqrt(k_c)).

    .venv/bin/python benchmarks/stiff_limit.py [--out results/stiff_limit.png]

The impact oscillator x'' + 2 zeta x' + x = cos(w t) (zeta = 0.05, w = 0.8) with a wall
at sigma = A / 2: the rigid wall (r = 0.8) has a stable period-1 single-impact orbit; the
soft wall (law "paper", on its exact piecewise-linear flow) k_c in 1e2 .. 1e6, c_c =
2 zeta_c sqrt(k_c) with zeta_c = -ln r / sqrt(pi^2 + ln^2 r), started on the rigid orbit's
section point and run until its own point repeats. Plots the distance (inf-norm of (x, v)
at t = 0 mod T) against k_c on log-log axes with the slope -1/2 drawn through the stiffest
point, and prints the distances and the slope fitted over k_c >= 1e3.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from softimpact_cli.analysis.engine import Problem, record_trajectory  # noqa: E402
from softimpact_cli.kinds.scene import parse_scene  # noqa: E402

ZETA, W, R = 0.05, 0.8, 0.8
SIGMA = 0.5 / np.sqrt((1.0 - W * W) ** 2 + (2.0 * ZETA * W) ** 2)
ZETA_C = -np.log(R) / np.sqrt(np.pi ** 2 + np.log(R) ** 2)
STIFFNESS = np.logspace(2.0, 6.0, 9)
PERIODS = 80
FIT_FROM = 1e3


def problem(stop: str, integrator: str = "") -> Problem:
    """The oscillator with the wall stop's law keys ``stop`` (TOML lines)."""
    scene = parse_scene(f'[system]\nmodel = "chain"\nbodies = 1\nc = {2 * ZETA}\nk1 = 1.0\n'
                        f'F = 1.0\nphi = "pi/2"\nw = {W}\n\n[[stop]]\nbody = 1\n'
                        f'wall = {float(SIGMA)!r}\nside = "right"\n{stop}\n\n'
                        '[analysis]\nkind = "trajectory"\nstate = [0.0, 0.0]\nperiods = 1\n'
                        + integrator, "<stiff_limit>")
    return Problem(scene.system, scene.values, scene.integrator)


def settled(p: Problem, state: np.ndarray) -> np.ndarray:
    """The section point after PERIODS periods from ``state``; it must have settled."""
    sections = record_trajectory(p, state, 0.0, PERIODS, 1).section_y
    if np.max(np.abs(sections[-1] - sections[-2])) > 1e-9:
        raise RuntimeError("the period-1 orbit did not settle in PERIODS periods")
    return sections[-1]


def distances() -> tuple[np.ndarray, np.ndarray]:
    """(the rigid orbit's section point (2,), distance of each soft orbit (len STIFFNESS,))."""
    rigid = settled(problem(f'law = "rigid"\nr = {R}',
                            '\n[integrator]\nmethod = "dopri5"\nrtol = 1e-12\natol = 1e-13\n'),
                    np.zeros(2))
    out = [np.max(np.abs(settled(problem(f'law = "paper"\nk_c = {float(k)!r}\n'
                                         f'c_c = {float(2.0 * ZETA_C * np.sqrt(k))!r}'),
                                 rigid) - rigid))
           for k in STIFFNESS]
    return rigid, np.array(out)


def fitted_slope(distance: np.ndarray) -> float:
    """The log-log slope over k_c >= FIT_FROM (below it the contact is not short against
    the period: 1e2 and 3e2 lie off the asymptote)."""
    tail = STIFFNESS >= FIT_FROM
    return float(np.polyfit(np.log(STIFFNESS[tail]), np.log(distance[tail]), 1)[0])


def figure(distance: np.ndarray):
    slope = fitted_slope(distance)
    fig, ax = plt.subplots(figsize=(5.0, 3.6))
    ax.loglog(STIFFNESS, distance, "o-", label=f"soft wall (slope {slope:.3f} for $k_c \\geq$ 1e3)")
    ax.loglog(STIFFNESS, distance[-1] * (STIFFNESS / STIFFNESS[-1]) ** -0.5, "k--",
              label=r"$k_c^{-1/2}$")
    ax.set_xlabel(r"contact stiffness $k_c$")
    ax.set_ylabel("distance of the stroboscopic orbit\nfrom the rigid wall's")
    ax.set_title(rf"stiff limit: $\zeta$ = {ZETA}, $\omega$ = {W}, wall $A/2$, r = {R}",
                 fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig, slope


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(ROOT / "results" / "stiff_limit.png"))
    args = ap.parse_args(argv)
    rigid, distance = distances()
    fig, slope = figure(distance)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"rigid orbit at t = 0: x = {rigid[0]:.10f}, v = {rigid[1]:.10f}")
    for k, d in zip(STIFFNESS, distance, strict=True):
        print(f"k_c = {k:9.3g}: distance {d:.3e}")
    print(f"fitted slope {slope:.3f} for k_c >= {FIT_FROM:g} (theory -1/2) -> {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
