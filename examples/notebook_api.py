"""softimpact from Python (a notebook or a script), top to bottom in a few seconds.

    .venv/bin/python examples/notebook_api.py [FOLDER]

writes FOLDER/basins.png and FOLDER/basins.h5 (default: a new temporary folder) and
prints what it found. Each step is a notebook cell; the sizes are small so that it runs
in seconds (tests/test_examples_api.py runs it). In a notebook, show a figure with
``display(fig)`` or draw on axes from ``plt.subplots()``: softimpact never changes the
matplotlib backend.
"""

import sys
import tempfile
from pathlib import Path

from matplotlib.figure import Figure

import softimpact_cli as si

folder = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="si-"))

# A scene from a dict: the sections and keys of a scene file, checked the same way (a
# mistake raises si.ConfigError with the one-line message the CLI prints).
pair = {"system": {"model": "duffing"},
        "coupling": {"d": 6.0, "phi": 0.0, "k_c": 8.0, "c_c": 10.0}}
scene = si.load_scene({**pair, "analysis": {"kind": "trajectory", "state": [8.0, 0.0, -4.0, 0.0],
                                            "periods": 60}})

# What softimpact can compute: every analysis kind with its one-line help.
print(f"kinds: {len(si.kinds())} ({', '.join(si.kinds())})")

# One trajectory, classified: an xarray.Dataset, no file written.
trajectory = si.run(scene)
print(f"trajectory: {trajectory.attrs['outcome']}, period {trajectory.attrs['period']} T")

# The pair as a System at one parameter point: where does one start go (the label a
# basins sweep gives it)? Other parameter values give a new System; nothing recompiles.
system = si.System({**pair, "catalogue": {"grid": 4, "random": 20}})
start = [8.0, 0.0, -4.0, 0.0]
here, wider = system.classify(start), system.with_(d=8.0).classify(start)
print(f"classify: {here.label} (period {here.period}) at d = 6, "
      f"{wider.label} (period {wider.period}) at d = 8")

# The attractors of one body and the pair's combinations at phi = 0.
catalogue = si.run({"system": {"model": "duffing"}, "coupling": {"phi": 0.0},
                    "analysis": {"kind": "catalogue", "grid": 4, "random": 20, "seed": 1}})
print(f"catalogue: {catalogue.sizes['attractor']} attractors, "
      f"{catalogue.sizes['combination']} combinations")

# A small basins plane, in memory (the dataset its result file would hold).
plane = {**pair, "analysis": {"kind": "basins"},
         "initial_conditions": {"kind": "plane", "axes": ["x1", "x2"],
                                "ranges": [[-12.0, 12.0], [-12.0, 12.0]],
                                "resolution": [16, 16]},
         "catalogue": {"grid": 4, "random": 20}}
basins = si.run(plane, workers=1)
# ds.si: each label's share of the plane with its 95% Wilson interval, as a table
shares = basins.si.shares()
print(shares.to_string(index=False))
print("basin shares: " + ", ".join(f"{row.label} {row.share:.2f}"
                                   for row in shares.itertuples() if row.count))

# Figures on your own axes: the basins beside the trajectory's phase portrait.
fig = Figure(figsize=(10, 5), layout="constrained")
left, right = fig.subplots(1, 2)
si.plot.basins(basins, ax=left)
right.plot(trajectory["state"].values[:, 0], trajectory["state"].values[:, 1], lw=0.5)
right.set(xlabel="$x_1$", ylabel=r"$\dot x_1$", title="trajectory, body 1")
fig.savefig(folder / "basins.png", dpi=80)

# A resumable run writes the result file (``softimpact sweep``): after an interruption,
# the same call with resume=True finishes it; si.open_result reads it back.
si.sweep(plane, folder / "basins.h5", overwrite=True, workers=1)
stored = si.open_result(folder / "basins.h5")
assert (stored["label"].values == basins["label"].values).all()
print(f"wrote {folder / 'basins.png'} and {folder / 'basins.h5'}")
