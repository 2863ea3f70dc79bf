# %% [markdown]
# # trajectory_catalogue

# %%
print(1)
