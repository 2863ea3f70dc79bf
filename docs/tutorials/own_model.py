# %% [markdown]
# # Your own model
#
# A model is data: `model = "chain"` declares any number of bodies (1 to 8) in a line,
# each with its own mass, damping, stiffness and forcing, joined by stops (between two
# bodies or against a wall) and one-sided springs (kinks). Nothing is compiled per model:
# one right-hand side serves every chain ([Models](../howto/models.md)). Run from the
# repository root (`.venv/bin/python docs/tutorials/own_model.py`); the commands run as
# `python -m softimpact_cli` (in a shell: `.venv/bin/softimpact`).
#
# ## A chain from the example
#
# `softimpact example chain > my_chain.toml` writes a commented scene: three bodies, two
# stops between neighbours, a wall stop on the right of body 3 and a kink on body 1, each
# stop with another law (paper, no-tension, Hunt-Crossley); each of them is reached.

# %%
import subprocess
import sys

import matplotlib.pyplot as plt
import numpy as np

import softimpact_cli as si


def softimpact(*args: str) -> int:
    """Run `softimpact ARGS` as a shell would; print its output; return its exit status."""
    run = subprocess.run([sys.executable, "-m", "softimpact_cli", *args],
                         capture_output=True, text=True)
    print((run.stdout + run.stderr).strip())
    return run.returncode


example = subprocess.run([sys.executable, "-m", "softimpact_cli", "example", "chain"],
                         capture_output=True, text=True, check=True).stdout
print(example)
with open("my_chain.toml", "w") as scene:          # softimpact example chain > my_chain.toml
    scene.write(example)

# %% [markdown]
# - **Per-body keys** in `[system]` (`m`, `c`, `k1`, `k2`, `F`, `phi`, and `k_x2`,
#   `k_x4` .. `k_x9` for further powers) take one number (every body) or a list of one
#   per body: here `phi` is a list, the rest one number each.
# - **Each `[[stop]]`** has its own law (`"paper"`, `"no-tension"`, `"hunt-crossley"`,
#   the same laws as the presets' `[coupling]`), `k_c` and `c_c` (defaults 8 and 10).
#   `between = [i, j]` is a stop between two bodies, in contact while `x_i - x_j >= d`;
#   `body = i` with `wall` and `side` is a wall stop, in contact while `x_i >= wall`
#   (`"right"`) or `x_i <= wall` (`"left"`).
#
# ## The model is data
#
# A dry run reads and checks the whole scene, prints the plan and stops: nothing is
# compiled or integrated.

# %%
softimpact("sweep", "my_chain.toml", "--dry-run")

# %% [markdown]
# A stop naming a body the chain does not have ends with one line naming the file, the
# stop and what is allowed, exit status 2, before anything runs:

# %%
with open("bad_chain.toml", "w") as scene:
    scene.write(example.replace("between = [2, 3]", "between = [2, 4]"))
print("exit status:", softimpact("sweep", "bad_chain.toml"))

# %% [markdown]
# ## A preset is a member of the family
#
# The coupled Duffing pair is a chain of two bodies with one stop: `k2 = 0.01` on both,
# the phase `phi` on the right one, the stop's gap `d` (the other keys' defaults are the
# pair's). From the same start, it gives the same orbit as `model = "duffing"`
# (`configs/trajectory_duffing.toml`: d = 6, phi = 5 pi / 8):

# %%
duffing_as_chain = """
[system]
model = "chain"
bodies = 2
k2 = 0.01
phi = [0.0, "5*pi/8"]

[[stop]]
between = [1, 2]
d = 6.0

[analysis]
kind = "trajectory"
state = [8.0, 0.0, -4.0, 0.0]
periods = 120
"""
as_chain = si.run(duffing_as_chain)
preset = si.run("configs/trajectory_duffing.toml")
for name, result in (("chain ", as_chain), ("preset", preset)):
    print(name, result.attrs["outcome"], "| period", result.attrs["period"],
          "| orbit point", np.round(result["orbit"].values[0], 6))
print("largest difference of the dense states:",
      f"{abs(as_chain['state'].values - preset['state'].values).max():.1e}")

# %% [markdown]
# ## A trajectory of the chain
#
# `si.run` (or `softimpact sweep my_chain.toml`) integrates the three bodies for 60
# periods and classifies the end on the stroboscopic section. The result counts contact
# onsets per period over all stops (`section_contacts`), and holds each stop's largest
# compression on the final orbit (`stop_max_penetration`, dim `stop`; >= 0: the stop is
# in contact there, < 0: its smallest clearance), located on the flow, not on samples.

# %%
chain = si.run("my_chain.toml")
print(chain.attrs["outcome"], "| period", chain.attrs["period"], "T",
      "| contacts on the orbit:", chain.attrs["contacts_on_orbit"],
      "| contact onsets in the record:", int(chain["section_contacts"].sum()))

x = chain["state"].values[:, 0::2]                   # x1, x2, x3 (the state is x1, v1, ...)
for stop, between, deepest in zip(chain["stop"].values, chain["stop_between"].values,
                                  chain["stop_max_penetration"].values, strict=True):
    print(f"stop {stop} ({between}): max compression on the orbit {deepest:+.4f}")
assert (chain["stop_max_penetration"].values >= 0).all()   # every stop engages

periods = chain["time"].values / chain.attrs["forcing_period"]
last = periods >= periods[-1] - 4                    # the last 4 periods: on the orbit
fig, ax = plt.subplots(figsize=(9, 3.5))
for body in range(3):
    ax.plot(periods[last], x[last, body], lw=1.2, label=f"x{body + 1}")
ax.axhline(1.5, color="k", lw=1, ls="--", label="wall of stop 3")
ax.set(xlabel="t / T", ylabel="displacement", title="the chain's period-1 orbit")
ax.legend(loc="lower right", ncol=4, fontsize="small")

# %% [markdown]
# How the solutions of a chain are named: the names are defined for any number of bodies
# ([names](../howto/catalogue.md)): `L{p}^{n} R{p}-{s}^{n}` for a pair, one token per body
# for three or more (`B1:P2^1 B2:P1-0^2 B3:P2-1^1`: each body on its own attractor, with
# its shift), and `impacting P{p}` for a periodic solution in contact, as this one is. A
# chain's trajectory carries no name (a trajectory builds no catalogue of its bodies'
# attractors; the sweep kinds below do): the tool reports the outcome, the period in
# forcing periods and the contacts on the orbit, as printed above (`softimpact plot
# trajectory` titles it "converged: period 1 T").
#
# ## Basins and basin stability
#
# The sweep kinds run on a chain too: its catalogue is each body's attractors searched
# alone and their products, named as above, each stop's critical value deciding which
# survive; a basin plane takes any two state coordinates by name or index (the others
# fixed), basin stability random starts in the 2n-dimensional box. A dry run prints the
# plan of a basin plane of this chain over (x1, v2):

# %%
basins = example[:example.index("[analysis]")] + """[analysis]
kind = "basins"

[initial_conditions]
kind = "plane"
axes = ["x1", "v2"]
ranges = [[-3.0, 3.0], [-3.0, 3.0]]
resolution = [40, 40]
fixed = {x2 = 0.0, x3 = 0.0}

[output]
path = "results/chain_basins.h5"
"""
with open("chain_basins.toml", "w") as scene:
    scene.write(basins)
print("exit status:", softimpact("sweep", "chain_basins.toml", "--dry-run"))

# %% [markdown]
# ## Further
#
# - Every key of `[system]`, `[[stop]]` and `[[kink]]`, with its type, default and range:
#   the [scene-key reference](../reference/scene-keys.md#stop).
# - The equations of the presets and of a chain, the stop laws, the limits (at most 16
#   switching surfaces; when the exact flow applies): [Models](../howto/models.md).
