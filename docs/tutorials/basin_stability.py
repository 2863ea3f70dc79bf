# %% [markdown]
# # Basin stability
#
# Basin stability (Menck et al. 2013) is the share of random starts in the full state
# space that reach each solution. Figure 14(c) of the study: the coupled Duffing pair at
# phi = 5.28, d = 10.5, with 4-D starts in [-12, 12]^4 at four start phases t0 (here 100
# samples per point with `quick=True`; the figure uses 1000).

# %%
import softimpact_cli as si

stability = si.run("configs/figures/fig14c_t0_stability.toml", quick=True)
print(stability["label"].dims, stability["label"].shape)
print(list(stability["label_name"].values))

# %% [markdown]
# Each share comes with its 95% Wilson interval; the figure draws them against the swept
# axis (here the start time t0, which changes the shares: state it with every number).

# %%
fig = si.plot.stability(stability)
