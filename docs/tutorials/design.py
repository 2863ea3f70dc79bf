# %% [markdown]
# # design

# %%
print(1)
