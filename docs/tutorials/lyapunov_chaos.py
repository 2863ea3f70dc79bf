# %% [markdown]
# # lyapunov_chaos

# %%
print(1)
