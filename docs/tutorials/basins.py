# %% [markdown]
# # basins

# %%
print(1)
