# %% [markdown]
# # Batch runs and CI
#
# On a cluster or in CI, the command line is the interface: `--quick` shrinks every
# scene, `--dry-run` prints the plan and stops, exit statuses say what happened
# ([Batch runs and CI](../howto/batch-ci.md)). From Python, the same commands run as
# `python -m softimpact_cli` (in a shell: `.venv/bin/softimpact`).

# %%
import subprocess
import sys


def softimpact(*args: str) -> int:
    """Run `softimpact ARGS` as a shell would; print its output; return its exit status."""
    run = subprocess.run([sys.executable, "-m", "softimpact_cli", *args],
                         capture_output=True, text=True)
    print((run.stdout + run.stderr).strip())
    return run.returncode


softimpact("sweep", "configs/figures/map_duffing_d_phi.toml", "--quick", "--dry-run")

# %% [markdown]
# A bad key ends with one line naming the file and the key, and exit status 2:

# %%
with open("bad.toml", "w") as scene:
    scene.write('[system]\nmodel = "duffing"\n[integrator]\nrtoll = 1e-8\n')
print("exit status:", softimpact("sweep", "bad.toml"))

# %% [markdown]
# A run and its comparison with a stored baseline: `compare` exits 1 when labels differ
# beyond its threshold, so a CI job fails on a changed result.

# %%
softimpact("sweep", "configs/trajectory_duffing.toml", "-o", "results/new.h5", "-q")
softimpact("sweep", "configs/trajectory_duffing.toml", "-o", "results/baseline.h5", "-q")
print("exit status:", softimpact("compare", "results/new.h5", "results/baseline.h5"))
