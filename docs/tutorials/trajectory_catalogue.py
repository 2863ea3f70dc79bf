# %% [markdown]
# # Trajectory and catalogue
#
# One trajectory of the coupled Duffing pair, classified on the stroboscopic section, then
# the attractors of one body and the pair's combinations. Run from the repository root
# (`.venv/bin/python docs/tutorials/trajectory_catalogue.py`); paths such as
# `configs/...` and `results/...` are relative to the working directory.

# %%

import softimpact_cli as si

trajectory = si.run("configs/trajectory_duffing.toml")   # an xarray.Dataset, no file
print(trajectory.attrs["outcome"], "| period", trajectory.attrs["period"], "T",
      "| impacting:", bool(trajectory.attrs["impacting"]))

# %% [markdown]
# The same figure as `softimpact plot trajectory RESULT.h5`, on axes of your own:

# %%
fig = si.plot.trajectory(trajectory)
fig.set_size_inches(9, 4)

# %% [markdown]
# ## The catalogue
#
# `kind = "catalogue"` searches the attractors of one body from a grid plus random
# starts, refines each by Newton shooting and lists every combination of the pair with
# its name `L{p}^{n} R{p}-{s}^{n}` ([names](../howto/catalogue.md)). `quick=True` is the
# CLI's `--quick`.

# %%
catalogue = si.run("configs/fig04_duffing_catalogue.toml", quick=True)
print("attractors:", list(catalogue["attractor_name"].values))
print("combinations:", list(catalogue["combination_name"].values))
fig = si.plot.catalogue(catalogue)
