# %% [markdown]
# # Bifurcation and continuation
#
# Two ways to follow solutions as a parameter moves. A **bifurcation** run (brute force)
# follows each non-impacting solution as the gap d closes, each step from the previous
# end state, and locates where it is destroyed (grazing). A **continuation** run follows
# branches of periodic orbits, stable and unstable, by pseudo-arclength and finds folds
# and other bifurcation points.

# %%
import softimpact_cli as si

diagram = si.run("configs/figures/fig07_duffing_bifurcation.toml", quick=True)
print(diagram.attrs["analysis"], "over d:", float(diagram["d"].min()), "..",
      float(diagram["d"].max()))
fig = si.plot.bifurcation(diagram)

# %% [markdown]
# The single Duffing body against the forcing amplitude F: the small and the large
# period-1 orbit are one branch folding twice, the middle part (a saddle) unstable.

# %%
branches = si.run("configs/continuation/duffing_fold_F.toml")
print(branches.attrs["analysis"], "| branches:", branches.sizes.get("branch"))
fig = si.plot.continuation(branches)
