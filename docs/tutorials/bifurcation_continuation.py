# %% [markdown]
# # bifurcation_continuation

# %%
print(1)
