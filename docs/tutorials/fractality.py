# %% [markdown]
# # fractality

# %%
print(1)
