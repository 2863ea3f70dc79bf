# %% [markdown]
# # batch_ci

# %%
print(1)
