# %% [markdown]
# # How fractal are the basins
#
# `si.measure` takes a basin plane and measures its basin entropy against the box size,
# the uncertainty exponent (with its fit interval) and the Wada property. The measures
# need 100+ cells per side; this tutorial uses a 24 x 24 plane of the single Duffing body
# (figure 3) to show the calls in seconds, not to measure.

# %%
import softimpact_cli as si

plane = si.run("configs/figures/fig03_duffing_single_basins.toml", quick=True)
print(plane["label"].shape)

# %%
measures = si.measure(plane)
print({k: v for k, v in measures.attrs.items() if k.startswith(("entropy", "uncertainty",
                                                               "wada", "basin"))})

# %%
fig = si.plot.fractality(measures)
