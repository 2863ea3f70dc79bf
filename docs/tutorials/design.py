# %% [markdown]
# # Design
#
# Choose (d, phi, k_c, c_c) so that only a target solution survives: the critical
# distances give the region where the target fits and every other combination would
# collide; candidates inside it are screened and verified by basin stability
# ([Designing for one solution](../howto/design.md)). `quick=True` shrinks the samples.

# %%
import softimpact_cli as si

design = si.run("configs/design_duffing.toml", quick=True)
roles = [str(r) for r in design["role"].values]   # best, runner-up, screened, perturbed, ...
best = roles.index("best")
print("target:", design.attrs["target"])
print("pick:", {a: round(float(design[f"point_{a}"].values[best]), 3)
                for a in ("d", "phi", "k_c", "c_c")})
groups = [str(g) for g in design["group"].values]
print("target share at the pick:", round(float(design["share"].values[best][groups.index(
    design.attrs["target"])]), 3), "of", int(design["n_samples"].values[best]), "samples")

# %%
fig = si.plot.design(design)
