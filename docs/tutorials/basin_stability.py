# %% [markdown]
# # basin_stability

# %%
print(1)
