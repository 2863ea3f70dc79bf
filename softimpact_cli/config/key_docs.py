"""What each scene section and key means: data beside the readers (config/scene.py,
config/sweep.py, config/verification.py), from which the scene-key reference is generated
(``softimpact_cli.kinds.key_reference``). The model parameters' meanings are in the
systems registry (``Parameter.description``), each analysis kind's ``[analysis]`` keys on
its ``AnalysisKind.keys``. A key the reader reads without a meaning here fails a test."""

from __future__ import annotations

SECTIONS: dict[str, str] = {
    "system": "The model and its body parameters (dimensionless, mass 1). The defaults are "
              "the study's values for each model.",
    "coupling": "The soft stop between the two bodies (`bodies = 2` only): the gap, the "
                "forcing phase of the right body, the stop's stiffness, damping and force law.",
    "integrator": "How trajectories are integrated and classified on the stroboscopic "
                  "section (t = n T). Every kind reads it.",
    "analysis": "What to compute: `kind` chooses the analysis, each kind reads its own keys "
                "(one table per kind below).",
    "output": "Where the result goes. Relative paths are relative to the working directory "
              "of the command, not to the scene file.",
    "grid": "Parameters swept by the analysis: each key a value, a list, "
            "`{start, stop, num}` or `{start, stop, step}`; a key not swept takes its value "
            "from `[system]`/`[coupling]`. Or `panels`: a list of parameter points.",
    "initial_conditions": "The starts of a sweep: a plane of two state variables, random "
                          "samples of the full state, or a list of states.",
    "catalogue": "How the one-body attractors behind the labels are searched (a sweep's "
                 "catalogue; cached on disk by its settings).",
    "verification": "How a sweep measures its label error: a share of its trajectories "
                    "rerun at tight settings, compared label by label.",
    "stop": "`model = \"chain\"` only, one `[[stop]]` table per stop: between two bodies "
            "(`between`, `d`) or against a wall (`body`, `wall`, `side`), with its law.",
    "kink": "`model = \"chain\"` only, one `[[kink]]` table per one-sided spring "
            "k (x - x_k), engaged past its position on its side.",
}

KEYS: dict[str, dict[str, str]] = {
    "system": {
        "model": 'the restoring force: "duffing" (cubic spring) or "bilinear" (a second '
                 'spring engaging beyond d1); or "chain": bodies, kinks and stops declared '
                 "in the scene",
        "bodies": "1: the left body alone (no stop); 2: the coupled pair; a chain: 1..8",
        "m": "chain: the mass of each body (one number, or a list of one per body; the "
             "other body keys too)",
        **{f"k_x{p}": f"chain: the coefficient of x^{p} in each body's restoring force"
           for p in (2, 4, 5, 6, 7, 8, 9)},
    },
    "stop": {
        "between": "[i, j]: a stop between bodies i and j, in contact while x_i - x_j >= d",
        "d": "the gap of a stop between bodies",
        "body": "a wall stop's body",
        "wall": "a wall stop's position",
        "side": '"right": contact while x_body >= wall; "left": while x_body <= wall',
        "law": 'the stop force law: "paper", "no-tension" or "hunt-crossley" (as [coupling] '
               'law), or "rigid" (impacts with restitution r, chattering and sticking)',
        "k_c": "the stop's stiffness (soft laws)",
        "c_c": "the stop's damping (soft laws)",
        "exponent": "hunt-crossley: the exponent n",
        "r": "rigid: the coefficient of restitution in [0, 1], v_rel+ = -r v_rel-",
    },
    "kink": {
        "body": "the body the spring acts on",
        "side": '"left": engaged while x_body <= x; "right": while x_body >= x',
        "x": "the position past which the spring engages",
        "k": "the spring's stiffness",
    },
    "coupling": {
        "law": 'the stop force F_C of the compression delta = x1 - x2 - d: "paper" '
               "(k_c delta + c_c delta', the damper may pull), \"no-tension\" (never "
               'pulls), "hunt-crossley" (k_c delta^n + c_c delta^n delta\')',
    },
    "integrator": {
        "method": '"rk4" (fixed step), "dopri5" (adaptive explicit), "rodas4" or its alias '
                  '"stiff" (L-stable Rosenbrock), "auto" (dopri5, switching to rodas4 where '
                  'stiff), "exact" (the exact flow of a piecewise-linear system); unset: '
                  '"exact" for a bilinear model with a linear stop law, else "auto"',
        "steps_per_period": "rk4: the fixed step is T / steps_per_period (the study: 1440)",
        "locate_switches": "locate every contact and spring switch to tolerance; false: the "
                           "study's plain scheme (rk4 only)",
        "rtol": "relative tolerance of the adaptive methods (setting it keeps a bilinear "
                'scene on "auto")',
        "atol": "absolute tolerance of the adaptive methods",
        "max_periods": 'budget of forcing periods before a trajectory is "unresolved"',
        "max_orbit_period": "largest period (in forcing periods) the classifier looks for",
        "convergence_tol": "section points repeating to this (scaled by max(1, |y|)) make "
                           "a converged periodic orbit",
        "capture_tol": "sweeps: a trajectory this close to a known stable orbit is captured "
                       "by it (0: off)",
        "capture_hits": "... for this many consecutive periods",
        "cell_size": "sweeps: side of the recurrence cells on the section (0: off); a "
                     "trajectory staying in one label's cells is labelled early",
        "cell_hits": "... after this many consecutive periods in that label's cells",
        "divergence_bound": '|state| beyond this is "diverged"',
        "max_steps_per_period": "step budget per forcing period before a trajectory stops "
                                "with a status",
        "max_switches_per_period": "switch budget per forcing period (chattering stops "
                                   "with TOO_MANY_SWITCHES)",
        "section_periods": "sweeps: follow an unresolved trajectory this many more periods "
                           "to name its attractor (chaotic, quasi-periodic, long period; "
                           "0: off)",
        "section_cell": "cell side of the second stage, in state units (x, v)",
        "section_recurrences": 'consecutive revisits of known cells that mean "settled" '
                               "(Attractors.jl: 100)",
        "section_locate": "section points kept as a non-periodic attractor's cells and cloud",
        "section_max_period": "longest period the second stage looks for",
        "section_lyapunov_periods": "periods averaged for each non-periodic attractor's "
                                    "Lyapunov spectrum",
        "section_zero_exponent": "|lambda1| at most this (1/time) is quasi-periodic, above "
                                 "it chaotic",
    },
    "analysis": {
        "kind": "the analysis; each kind reads its own keys, listed below",
    },
    "output": {
        "path": "the result file (HDF5/netCDF); a value ending in \"/\" names a directory "
                "holding <scene stem>.h5. `-o` overrides it",
    },
    "grid": {
        "panels": "explicit parameter points instead of swept axes: a list of tables like "
                  "{d = 10.0, phi = \"pi\"} (each a panel of the figure)",
        "t0": "swept: the start time (the forcing phase at the start), a number or "
              '"a*T/b"',
    },
    "initial_conditions": {
        "kind": '"plane" (a grid over two state variables), "random" (uniform samples in '
                'a box of the full state) or "list" (given states)',
        "axes": "plane: the two state variables spanning it",
        "ranges": "plane: [low, high] of each axis",
        "resolution": "plane: cells per axis [n1, n2]",
        "fixed": "plane: the other state variables' values (default 0), e.g. {v1 = 0.0}",
        "box": "random: {x1 = [lo, hi], v1 = [lo, hi], ...} over every state variable",
        "n": "random: the number of samples",
        "seed": "random: seed of the samples",
        "states": "list: the states, each [x1, v1, x2, v2] (x, v for one body)",
        "t0": 'start time of every trajectory: a number, "a*T/b", or "random" (uniform in '
              "[0, T) per sample, random kind only)",
    },
    "catalogue": {
        "box": "where the starts of the one-body search are drawn: {x = [lo, hi], v = "
               "[lo, hi]}",
        "grid": "a grid x grid lattice of starts ...",
        "random": "... plus this many random starts",
        "seed": "seed of the random starts",
        "match_tol": "two orbits closer than this on the section are one attractor",
    },
    "verification": {
        "share": "fraction of the trajectories rerun at tight settings ...",
        "min_sample": "... at least this many ...",
        "max_sample": "... at most this many (never more than the sweep has)",
        "threshold": "accepted upper end of the 95% interval of the label-error share",
        "tighten": "over the threshold: redo the whole sweep at tighter settings",
        "seed": "seed of the random sample",
        "enabled": 'false: the result is recorded as "not verified"',
        "pilot": "large sweeps: choose the loosest safe tolerance first (the tolerance pilot)",
        "pilot_sample": "trajectories the tolerance pilot compares",
    },
}
