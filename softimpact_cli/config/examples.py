"""Minimal commented scenes, one per analysis kind (``softimpact example KIND``).

Each is a complete scene (TOML text) that ``parse_scene`` accepts and that runs as it stands;
the larger ones say how long they take. The full figure scenes are in configs/figures/.
"""

from __future__ import annotations

from ..systems import STOP_LAWS

_COMMON = """\
# Every key not given takes its default (docs/reference/scene-keys.md); unknown keys are errors.
# Run: softimpact sweep THIS_FILE.toml   (then: softimpact info / softimpact plot {plot} ...)
"""

_PAIR = """\
[system]
model = "duffing"          # "duffing" | "bilinear"; c, k1, k2, F, w default to the study's

[coupling]                 # the stop between the bodies (bodies = 2, the default)
d = 6.0                    # gap: contact while x1 - x2 >= d
phi = "5*pi/8"             # phase of the right body's forcing: a number or "a*pi/b"
k_c = 8.0                  # stop stiffness
c_c = 10.0                 # stop damping
law = "paper"              # {laws}
""".format(laws=" | ".join(f'"{law.name}"' for law in STOP_LAWS.values() if law.soft) + "".join(
    f" ({law.name}: {key.name} = {key.default:g})" for law in STOP_LAWS.values() if law.soft
    for key in law.keys))

EXAMPLES: dict[str, str] = {
    "trajectory": _PAIR + """
[analysis]
kind = "trajectory"        # one trajectory, recorded and classified (about a second)
state = [8.0, 0.0, -4.0, 0.0]   # x1, v1, x2, v2 at t0
periods = 60               # forcing periods integrated
t0 = 0.0                   # start time: a number or "T/4", "3*T/4"

[output]
path = "results/example_trajectory.h5"
""",
    "catalogue": """\
[system]
model = "duffing"
bodies = 2                 # the pair: the right body's attractors follow from the left's

[coupling]
phi = 0.0                  # the combinations' joint orbits are listed at this phase

[analysis]
kind = "catalogue"         # attractors of one body, refined by Newton (seconds)
box = { x = [-12.0, 12.0], v = [-12.0, 12.0] }   # where the starts are drawn
grid = 4                   # a grid x grid lattice of starts ...
random = 20                # ... plus this many random starts
seed = 1

[output]
path = "results/example_catalogue.h5"
""",
    "basins": _PAIR + """
[analysis]
kind = "basins"            # label every start of a plane (about 10 s at 40 x 40)

[grid]                     # optional: any of d, phi, k_c, c_c, t0 (one panel per point)
d = [6.0, 10.0]

[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]        # the other state variables are 0 (or set them in fixed)
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [40, 40]

[catalogue]                # how the labels' attractors are searched
grid = 8
random = 50

[verification]             # every sweep measures its label error (these are the defaults)
share = 0.01               # rerun this fraction of the starts at tight settings,
min_sample = 50            # at least this many, at most max_sample
max_sample = 2000
threshold = 0.005          # over this (95% upper bound), redo the sweep tighter ...
tighten = true             # ... unless false: then keep it and warn

[output]
path = "results/example_basins.h5"
""",
    "stability": _PAIR + """
[analysis]
kind = "stability"         # basin stability: shares of random starts per solution

[grid]
c_c = { start = 2.0, stop = 10.0, num = 3 }   # the parameter the shares are plotted against

[initial_conditions]
kind = "random"
box = { x1 = [-12.0, 12.0], v1 = [-12.0, 12.0], x2 = [-12.0, 12.0], v2 = [-12.0, 12.0] }
n = 200                    # samples per grid point (95% Wilson intervals in the result)
seed = 15
t0 = 0.0                   # or "random": the forcing phase sampled too

[output]
path = "results/example_stability.h5"
""",
    "dcrit": """\
[system]
model = "duffing"

[analysis]
kind = "dcrit"             # d_crit(phi) of every combination (seconds)
traces = ["pi/4"]          # also store x1 - x2 over one period at these phases

[grid]
phi = { start = 0.0, stop = "63*pi/32", num = 64 }   # default: 256 phases over [0, 2 pi)

[output]
path = "results/example_dcrit.h5"
""",
    "bifurcation": """\
[system]
model = "duffing"

[coupling]
phi = "5*pi/8"
k_c = 8.0
c_c = 20.0

[analysis]
kind = "bifurcation"       # follow each non-impacting solution as d decreases (seconds)
start = 22.0
stop = 4.0
step = 0.5
# branches = ["L1^1 R1-0^1"]   # default: every combination of the catalogue
# parameter = "w"          # follow along another parameter (default d): w, F, c, k1, ...

[output]
path = "results/example_bifurcation.h5"
""",
    "map": """\
[system]
model = "duffing"

[coupling]
k_c = 8.0
c_c = 10.0

[analysis]
kind = "map"               # coexisting solutions over two parameters: predicted and found

[grid]                     # two of d, phi, k_c, c_c
d = { start = 2.0, stop = 22.0, num = 6 }
phi = { start = 0.0, stop = "5*pi/3", num = 6 }

[initial_conditions]
kind = "random"
box = { x1 = [-12.0, 12.0], v1 = [-12.0, 12.0], x2 = [-12.0, 12.0], v2 = [-12.0, 12.0] }
n = 50                     # samples per grid point
seed = 3

[output]
path = "results/example_map.h5"
""",
    "tipping": """\
[system]
model = "duffing"

[coupling]
phi = 0.0
k_c = 8.0
c_c = 10.0

[analysis]
kind = "tipping"           # where basins and solutions go when the parameters jump

[grid]                     # exactly two points: before, then after
panels = [{ d = 22.0 }, { d = 6.0 }]

[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [20, 20]

[output]
path = "results/example_tipping.h5"
""",
    "fatal_shock": """\
[system]
model = "duffing"
bodies = 1

[analysis]
kind = "fatal_shock"       # the smallest kick that sends a solution to another attractor
solution = "L1^1"          # a label name of the catalogue
phases = 4                 # phases along its orbit
directions = 16            # shock directions (random for a pair, even angles for a body)
max_shock = 24.0           # largest magnitude scanned ...
scan = 24                  # ... in this many steps, then bisection ...
tol = 1e-3                 # ... to this width

[output]
path = "results/example_fatal_shock.h5"
""",
    "design": """\
[system]
model = "duffing"

[analysis]
kind = "design"            # choose (d, phi, k_c, c_c) so that only the target survives
target = "L1^1 R1-0^1"     # a non-impacting combination of the catalogue
bounds = { d = [3.0, 12.0], phi = [0.0, "2*pi"], k_c = [2.0, 20.0], c_c = [1.0, 20.0] }
candidates = 8             # points screened inside the region
screen_n = 50              # samples per screened point
refine = 2                 # best screened points verified on all n samples
seed = 0

[initial_conditions]       # the basin-stability samples: kind = "random" only
kind = "random"
box = { x1 = [-12.0, 12.0], v1 = [-12.0, 12.0], x2 = [-12.0, 12.0], v2 = [-12.0, 12.0] }
n = 100
seed = 15

[output]
path = "results/example_design.h5"
""",
    "fractality": """\
[system]
model = "bilinear"         # the study's fractal single body (figure 9)
bodies = 1
w = 0.86
F = 0.518

[analysis]
kind = "fractality"        # sweep the plane, then basin entropy, alpha and the Wada test
box_sizes = [2, 3, 4, 5, 6, 8, 10]   # basin-entropy boxes (cells; default 2 .. side/4)
radii = [1, 2, 3, 4, 6]    # uncertainty radii (cells; default ~12 over 1 .. side/10)
wada_radius = 5            # Wada test: fatten the merged boundaries up to 5 cells
wada_tol = 0.05            # ... and call it Wada when at most 5% of one lies farther

[initial_conditions]
kind = "plane"
axes = ["x", "v"]
ranges = [[-2.5, 2.5], [-2.5, 2.5]]
resolution = [40, 40]      # about 20 s; the measures need more (docs: 100+ per side)

[catalogue]
box = { x = [-3.0, 3.0], v = [-3.0, 3.0] }

[output]
path = "results/example_fractality.h5"
""",
    "lyapunov": _PAIR + """
[integrator]
method = "dopri5"          # the variational equations run with an explicit method

[analysis]
kind = "lyapunov"          # Lyapunov exponents, saltation matrices at switches (seconds)
start = "state"            # "state": from `state`; "catalogue": every catalogue solution
state = [8.0, 0.0, -4.0, 0.0]   # x1, v1, x2, v2 at t0
t0 = 0.0
transient = 50             # forcing periods discarded first
periods = 200              # periods averaged, in `segments` equal segments (their spread
segments = 10              #   gives the standard error); periods a multiple of segments
per_period = 8             # Gram-Schmidt re-orthonormalisations per period
saltation = true           # false: tangents not corrected at switches (wrong; to compare)
follow = true              # with [grid]: each value starts from the last one's end state

# [grid]                   # optional: the exponents along ONE parameter (d, phi, k_c, c_c)
# c_c = { start = 10.0, stop = 2.0, num = 17 }

[output]
path = "results/example_lyapunov.h5"
""",
    "continuation": """
[system]
model = "duffing"
bodies = 1
F = 1.0                    # the continued parameter starts at the scene's value

[analysis]
kind = "continuation"      # branches of periodic orbits, stable and unstable (seconds)
parameter = "F"            # d, phi, k_c, c_c (a pair), F, w
low = 0.2                  # followed within [low, high]
high = 3.0
start = "catalogue"        # every catalogue orbit; or "state" with state = [x, v]
step = 0.05                # first arclength step; min_step, max_step bound it
max_step = 0.3
max_points = 400           # per direction
switch_depth = 1           # period doublings switched onto (0: none)
brute_force_step = 0.05    # sweeps up and down from each start, drawn beside (0: none)

[catalogue]
grid = 8
random = 40

[output]
path = "results/example_continuation.h5"
""",
    "atlas": """
[system]
model = "duffing"

[coupling]                 # the catalogue is searched here, inside the rectangle
phi = "5*pi/8"
k_c = 8.0
c_c = 20.0
d = 17.0

[analysis]
kind = "atlas"             # fold, PD, NS and grazing curves in two parameters (seconds)
parameters = ["phi", "d"]  # any two parameters of the model
ranges = { phi = [1.9, 2.0], d = [14.0, 17.0] }
max_period = 1             # curves of orbits of at most this many forcing periods
slices = 0                 # extra seeding runs in d at that many phi values
step = 0.05
max_step = 0.3
max_points = 40            # per direction of each branch and curve

[catalogue]
grid = 4
random = 20

[output]
path = "results/example_atlas.h5"
""",
}


def example(kind: str) -> str:
    """The commented example scene of analysis ``kind`` (KeyError if there is none)."""
    header = _COMMON.format(plot=kind)
    if kind == "design":
        header = header.replace("softimpact sweep", "softimpact design")
    return header + EXAMPLES[kind]

CHAIN_EXAMPLE = """\
# A chain of forced oscillators with stops (softimpact example chain): any number of
# bodies (1..8), kinks and stops, declared here; no compilation per model.
# Run: softimpact sweep THIS_FILE.toml   (then: softimpact plot trajectory RESULT.h5 -o FIG.png)
[system]
model = "chain"
bodies = 3                 # 1..8; the state is x1, v1, x2, v2, x3, v3
m = 1.0                    # per-body keys: one number (every body) or a list of one per body
c = 0.05                   # viscous damping
k1 = 1.0                   # restoring force k1 x + k2 x^3 (+ k_xp x^p: k_x2, k_x4 .. k_x9)
k2 = 0.01
F = 1.0                    # forcing F sin(w t + phi), one w for every body
phi = [0.0, "5*pi/8", "5*pi/4"]   # numbers or "a*pi/b"
w = 1.3

[[stop]]                   # a stop between two bodies: contact while x1 - x2 >= d
between = [1, 2]
d = 2.0
law = "paper"              # {laws}
k_c = 8.0
c_c = 10.0

[[stop]]
between = [2, 3]
d = 2.0
law = "no-tension"         # k_c, c_c: 8 and 10 unless given

[[stop]]                   # a wall: contact while x3 >= wall ("right") or x3 <= wall ("left")
body = 3
wall = 1.5
side = "right"
law = "hunt-crossley"

[[kink]]                   # a one-sided spring k (x - x_k), engaged past x on its side
body = 1
side = "left"              # engaged while x1 <= x ("left") or x1 >= x ("right")
x = -1.5
k = 4.0

[analysis]
kind = "trajectory"
state = [1.5, 0.0, -0.5, 1.0, -2.0, 0.0]
periods = 60

[output]
path = "results/example_chain.h5"
""".format(laws=" | ".join(f'"{law.name}"' for law in STOP_LAWS.values()))

MODEL_EXAMPLES: dict[str, str] = {"chain": CHAIN_EXAMPLE}  # softimpact example MODEL
