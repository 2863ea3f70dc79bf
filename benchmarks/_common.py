"""Helpers shared by the benchmark scripts: the machine line, the load average, the figure
6(d) basin scene, and labelling a list of initial states exactly as a sweep labels them.

Not part of the package: benchmarks measure, they are not tests.
"""

from __future__ import annotations

import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from softimpact_cli.analysis.labels import name_of  # noqa: E402
from softimpact_cli.config import IntegratorSettings  # noqa: E402
from softimpact_cli.kinds.scene import parse_scene  # noqa: E402
from softimpact_cli.sweep import executors  # noqa: E402
from softimpact_cli.sweep.chunks import SweepContext  # noqa: E402

WORKERS = 2  # the development machine has 2 cores

BASIN_SCENE = """\
# figure 6(d): as configs/demo_basins.toml, at the benchmark's resolution
[system]
model = "duffing"

[coupling]
d = 6.0
phi = 0.0
k_c = 8.0
c_c = 10.0

[analysis]
kind = "basins"

[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [{n}, {n}]
fixed = {{v1 = 0.0, v2 = 0.0}}
t0 = 0.0

[output]
path = "results/bench_basin.h5"
"""


STABILITY_SCENE = """\
# figure 14(c)-style basin stability: Duffing, phi = 5.28, d = 10.5, k_c = 8, c_c = 10
[system]
model = "duffing"

[coupling]
d = 10.5
phi = 5.28
k_c = 8.0
c_c = 10.0

[analysis]
kind = "stability"

[initial_conditions]
kind = "random"
box = {{ x1 = [-12.0, 12.0], v1 = [-12.0, 12.0], x2 = [-12.0, 12.0], v2 = [-12.0, 12.0] }}
n = {n}
seed = 15
t0 = 0.0

[output]
path = "results/bench_stability.h5"
"""


def stability_scene(n: int):
    """The figure 14(c)-style basin-stability scene with ``n`` samples."""
    return parse_scene(STABILITY_SCENE.format(n=n), "<bench_stability>")


def load() -> str:
    """The 1, 5 and 15 minute load averages, as text."""
    try:
        a, b, c = os.getloadavg()
        return f"{a:.2f} {b:.2f} {c:.2f}"
    except OSError:
        return "n/a"


def machine() -> str:
    """CPU, core count and the versions that matter for timings."""
    import numba
    import scipy

    import softimpact_cli

    si = getattr(softimpact_cli, "__version__", "?")
    cpu = platform.processor() or platform.machine()
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return (f"{cpu}, {os.cpu_count()} cores (shared machine: other processes may run), "
            f"Python {platform.python_version()}, numpy {np.__version__}, numba "
            f"{numba.__version__}, scipy {scipy.__version__}, softimpact_cli {si}")


def code_version() -> str:
    """The git commit of the package measured, and whether its sources differ from it."""
    def git(*args: str) -> str:
        return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True,
                              check=True).stdout.strip()
    try:
        head = git("rev-parse", "--short", "HEAD")
        dirty = git("status", "--porcelain", "--", "softimpact_cli")
    except (OSError, subprocess.CalledProcessError):
        return "not a git checkout"
    return f"commit {head}" + (" with uncommitted changes in softimpact_cli" if dirty else "")


def write_report(path: str, lines: list[str]) -> None:
    """Write a benchmark's markdown ``lines`` to ``path`` (its folder made) and print them."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines))
    print("\n".join(lines))


def fmt_time(s: float) -> str:
    """Seconds as '12.3 s', '4.5 min' or '1.2 h'."""
    if s < 120:
        return f"{s:.1f} s"
    if s < 7200:
        return f"{s / 60:.1f} min"
    return f"{s / 3600:.1f} h"


def scene_at(resolution: int):
    """The figure 6(d) basin scene on a ``resolution`` x ``resolution`` grid."""
    return parse_scene(BASIN_SCENE.format(n=resolution), "<bench_basin>")


def label_states(scene, catalogues: dict, names: tuple[str, ...], states,
                 integrator: IntegratorSettings, workers: int = WORKERS,
                 chunks_per_worker: int = 4) -> tuple[list[str], float]:
    """Label ``states`` ((n, 4) array, imposed at t0 = 0) at the scene's parameter point
    with ``integrator``, exactly as a sweep labels (``sweep.chunks.run_chunk`` on a local
    pool of ``workers``). Returns (label names in input order, wall time in s)."""
    states = np.asarray(states, dtype=float)
    ctx = SweepContext(
        model=scene.system.model, bodies=scene.system.bodies, values=dict(scene.values),
        integrator=integrator, grid=scene.grid, states=states, t0=np.zeros(len(states)),
        catalogues=catalogues, names=names, label_tol=scene.analysis.label_tol)
    return label_context(ctx, workers, chunks_per_worker)


def label_context(ctx: SweepContext, workers: int = WORKERS, chunks_per_worker: int = 4
                  ) -> tuple[list[str], float]:
    """Run every trajectory of ``ctx`` (all grid points times all states) through
    ``run_chunk`` on a local pool; (label names in flat order, wall time in s)."""
    n = ctx.grid.size * ctx.states.shape[0]
    size = max(1, -(-n // (chunks_per_worker * workers)))
    chunks = [(i, s, min(s + size, n)) for i, s in enumerate(range(0, n, size))]
    t = time.perf_counter()
    codes = np.empty(n, dtype=np.int64)
    for index, result in executors.LocalExecutor(workers).run(ctx, chunks):
        start = chunks[index][1]
        codes[start:start + len(result["label"])] = result["label"]
    return [name_of(c, ctx.names) for c in codes], time.perf_counter() - t


# ---------------------------------------------------------------- the study's planes

PLANES = {  # name -> (scene file, the grid panel that replaces the scene's [grid])
    "6d": ("configs/demo_basins.toml", None),
    "9": ("configs/figures/fig09_bilinear_single_basins.toml", None),
    "12a": ("configs/figures/fig12_bilinear_basins.toml", {"d": 10.0, "phi": "pi"}),
    "13a": ("configs/figures/fig13_bilinear_basins.toml", {"d": 10.0, "phi": "pi"}),
    "14a": ("configs/figures/fig14ab_bilinear_impacting.toml", {"k_c": 8.0}),
}
FRACTAL_PLANES = ("9", "12a", "13a", "14a")

# The tight reference labels are compared with: dopri5 rtol 1e-11, no capture, no cells.
TIGHT = dict(method="dopri5", rtol=1e-11, atol=1e-13, convergence_tol=1e-9,
             max_periods=6000, capture_tol=0.0, cell_size=0.0)


def plane_scene(name: str, resolution: int, integrator: dict | None = None,
                planes: dict | None = None):
    """Figure plane ``name`` (a key of ``planes``, default PLANES) at ``resolution`` x
    ``resolution``, t0 = 0, with ``integrator`` keys written into its [integrator] section."""
    import tomllib

    from softimpact_cli.config.toml_text import toml_text

    path, panel = (PLANES if planes is None else planes)[name]
    doc = tomllib.loads((ROOT / path).read_text())
    if panel is not None:
        doc.pop("grid", None)
        doc.setdefault("coupling", {}).update(panel)
    doc["initial_conditions"]["resolution"] = [resolution, resolution]
    doc["initial_conditions"].setdefault("t0", 0.0)
    doc["integrator"] = {**doc.get("integrator", {}), **(integrator or {})}
    return parse_scene(toml_text(doc), f"<figure {name}>")


def sample_points(resolution: int, n: int, seed: int = 2024) -> np.ndarray:
    """``n`` distinct random flat indices of a ``resolution`` x ``resolution`` plane, sorted."""
    total = resolution * resolution
    return np.sort(np.random.default_rng(seed).choice(total, min(n, total), replace=False))


def tight_reference(name: str, resolution: int, picks: np.ndarray) -> list[str]:
    """Label names of plane ``name``'s points ``picks`` at TIGHT (2 workers), cached under
    results/bench/ in a file named by a hash of the inputs and of the classifying sources."""
    import hashlib
    import json
    from dataclasses import replace

    from softimpact_cli.kernels.numba_cache import source_hash
    from softimpact_cli.sweep.runner import prepare_inputs

    material = json.dumps([name, resolution, picks.tolist(), TIGHT, source_hash()])
    key = hashlib.sha256(material.encode()).hexdigest()[:16]
    path = ROOT / "results" / "bench" / f"reference_{name}_{key}.json"
    if path.exists():
        return json.loads(path.read_text())
    scene = plane_scene(name, resolution)
    ctx = prepare_inputs(scene, lambda s: None).context
    tight = replace(ctx, integrator=replace(scene.integrator, **TIGHT),
                    states=ctx.states[picks], known=None)
    labels, wall = label_context(tight, WORKERS)
    print(f"    tight reference of figure {name}: {len(picks)} points in {wall:.1f} s",
          flush=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(labels))
    return labels


def label_names(ds) -> list[str]:
    """The label name of every trajectory of a sweep dataset, in flat order."""
    table = dict(zip(ds["label_code"].values.tolist(),
                     (str(x) for x in ds["label_name"].values), strict=True))
    return [table[int(c)] for c in ds["label"].values.reshape(-1)]
