# %% [markdown]
# # Lyapunov exponents and chaos
#
# The full Lyapunov spectrum by Benettin's method on the variational equations, with the
# saltation matrix at every switch. Ueda's oscillator `x'' + 0.05 x' + x^3 = 7.5 cos t` is
# the smooth reference: its largest exponent is positive (published: 0.0999, -0.1499).

# %%
import softimpact_cli as si

ueda = si.run("configs/lyapunov_ueda.toml")
print({name: float(ueda[name].values.ravel()[0]) for name in ueda.data_vars
       if "exponent" in name and ueda[name].size})

# %%
fig = si.plot.lyapunov(ueda)

# %% [markdown]
# Attractors that are not periodic are named by a second stage of the sweep (chaotic or
# quasi-periodic, numbered, with their exponents): see
# [Attractors that are not periodic](../howto/nonperiodic.md).
