"""Documented check: each catalogue scene is stable under doubling the sampled initial
conditions and halving the tolerances (same attractors, periods, points to 1e-8).

    .venv/bin/python benchmarks/catalogue_stability.py
"""

from dataclasses import replace
from pathlib import Path

import numpy as np

from softimpact_cli.analysis.catalogue import sample_states
from softimpact_cli.kinds.scene import load_scene
from softimpact_cli.store.catalogues import build_catalogue

SCENES = ["fig04_duffing_catalogue.toml", "fig10_bilinear_catalogue.toml",
          "fig13_bilinear_catalogue.toml"]


def run(scene, grid, random, integrator):
    a = scene.analysis
    states = sample_states(a.box, grid, random, a.seed)
    return build_catalogue(scene.system, dict(scene.values), integrator, states, a.t0,
                           a.match_tol)


def main() -> int:
    failures = 0
    for name in SCENES:
        scene = load_scene(Path(__file__).parents[1] / "configs" / name)
        a, s = scene.analysis, scene.integrator
        base = run(scene, a.grid, a.random, s)
        tighter = replace(s, rtol=s.rtol / 2, atol=s.atol / 2,
                          convergence_tol=s.convergence_tol / 2)
        double = run(scene, int(round(a.grid * np.sqrt(2))), 2 * a.random, tighter)
        same = [x.name for x in base.attractors] == [x.name for x in double.attractors]
        dist = max((float(np.max(np.abs(x.points - y.points)))
                    for x, y in zip(base.attractors, double.attractors, strict=False)),
                   default=0.0)
        ok = same and dist < 1e-8 and len(base.combinations) == len(double.combinations)
        failures += not ok
        print(f"{name}: {base.n_samples} -> {double.n_samples} samples, attractors "
              f"{[x.name for x in base.attractors]} vs {[x.name for x in double.attractors]}, "
              f"max point difference {dist:.1e}, combinations {len(base.combinations)} vs "
              f"{len(double.combinations)}: {'stable' if ok else 'CHANGED'}")
    return failures


if __name__ == "__main__":
    raise SystemExit(main())
