# %% [markdown]
# # Basins and how right they are
#
# A basin plane of the coupled Duffing pair (figure 6(d) of the study, at 24 x 24 instead
# of the demo's 100 x 100), its shares, and its measured label error: every sweep reruns a
# sample of its trajectories at tight settings and reports the share that disagrees
# ([How right is a result](../validation/how-right.md)).

# %%
import softimpact_cli as si

basins = si.run("configs/demo_basins.toml", resolution=24)
basins.si.shares()   # each solution's share of the plane with its 95% Wilson interval

# %% [markdown]
# The verification, as `softimpact info` shows it: how many of the rerun sample
# disagree, and the 95% interval of the error share. A plane this small reruns only 50
# trajectories, too few for the interval's upper end to fall below the accepted 0.5%
# when none disagree: the status says what the sample bounds (`--check N` reruns more).

# %%
a = basins.attrs
print(f"verified: {a['verify_status']}, {a['verify_disagreements']} of {a['verify_sample']} "
      f"disagree, 95% interval [{a['verify_ci95_low']:.4f}, {a['verify_ci95_high']:.4f}]")

# %%
fig = si.plot.basins(basins)
