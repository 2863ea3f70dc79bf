# %% [markdown]
# # Design
#
# Choose (d, phi, k_c, c_c) so that only a target solution survives: the critical
# distances give the region where the target fits and every other combination would
# collide; candidates inside it are screened and verified by basin stability
# ([Designing for one solution](../howto/design.md)). The full design of the gallery
# (`configs/design_duffing.toml`: 48 candidates, 1000 samples) takes a few minutes; this
# one screens 4 candidates on 30 samples, in seconds. A scene can be a dict with the
# sections and keys of a scene file, checked the same way.

# %%
import softimpact_cli as si

scene = {
    "system": {"model": "duffing"},
    "analysis": {"kind": "design", "target": "L1^1 R1-0^1",
                 "bounds": {"d": [3.0, 12.0], "phi": [0.0, "2*pi"], "k_c": [2.0, 20.0],
                            "c_c": [1.0, 20.0]},
                 "candidates": 4, "screen_n": 30, "refine": 1, "robust_n": 20,
                 "phi_points": 90, "shock_directions": 0, "seed": 0},
    "initial_conditions": {"kind": "random", "n": 60, "seed": 15,
                           "box": {"x1": [-12.0, 12.0], "v1": [-12.0, 12.0],
                                   "x2": [-12.0, 12.0], "v2": [-12.0, 12.0]}},
}
design = si.run(scene)
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
