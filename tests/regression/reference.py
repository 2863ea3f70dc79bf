"""Results of every example scene, stored from main before a refactor and compared after.

``python -m tests.regression.reference write`` runs every scene of ``configs/`` (and
``configs/figures/``) at ``--quick`` resolution, plus figure 6(d)'s plane at 60 x 60, and
stores each result's data variables in ``tests/data/reference/<scene>.npz``;
``test_reference.py`` reruns them and compares. Integer variables (labels, statuses,
periods, counters) must be identical; floating-point ones equal to a relative 1e-9 (a
different CPU may round differently in compiled code; on the machine that wrote the
references, ``python -m tests.regression.reference compare`` reports bitwise equality).
"""

from __future__ import annotations

import hashlib
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
STORE = ROOT / "tests" / "data" / "reference"

# Scenes run with other options than --quick. chaos_fig14c_basins: about 8% of its starts
# go through the second stage (42 of 512 at 16 x 16), each for up to 4000 more periods,
# and its verification redid the sweep in a CI run at --quick (24 x 24: 54 s); 16 x 16
# without verification guards the same sweep and second stage in 9 s.
OPTIONS = {"chaos_fig14c_basins": ("--resolution", "16", "--no-verify")}
# design_duffing, design_bilinear and fatal_shock_duffing_6d were rewritten when --quick
# began shrinking those kinds (6 candidates on 50 samples, 2 refined, 4 shock directions;
# 4 phases x 16 directions), by the same analysis code: the new fatal shocks are the old
# result's even phases x first 16 directions bit for bit; the designs' screened points
# are among the old ones, the reference point's and the pick's counts on all samples,
# the catalogue, d_crit curves and region identical (design_duffing's pick moved).

# (name, scene, extra CLI options)
SCENES = tuple(
    [(p.stem, p, OPTIONS.get(p.stem, ("--quick",)))
     for p in sorted((ROOT / "configs").glob("*.toml"))]
    + [(p.stem, p, OPTIONS.get(p.stem, ("--quick",)))
       for p in sorted((ROOT / "configs" / "figures").glob("*.toml"))]
    + [("fig06d_plane_60", ROOT / "configs" / "demo_basins.toml", ("--resolution", "60"))]
)
# attributes that change from run to run (times, paths, machine) are not results
VOLATILE = ("wall", "time", "started", "finished", "host", "python", "command", "version",
            "commit", "output", "executor", "workers", "chunk", "plan", "session", "resumed",
            "cpu", "numba", "platform", "source", "scene_text", "scene_file", "duration")


def run_scene(scene: Path, options: tuple[str, ...], out: Path):
    """Run one scene through the CLI (in this process) and open its result."""
    import xarray as xr
    from click.testing import CliRunner

    from softimpact_cli.cli import main

    result = CliRunner().invoke(main, ["sweep", str(scene), "-o", str(out), "--overwrite",
                                       "-q", "--workers", "2", *options])
    if result.exit_code != 0:
        raise RuntimeError(f"{scene.name}: exit {result.exit_code}: {result.output}")
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        return ds.load()


def arrays_of(ds) -> dict[str, np.ndarray]:
    """The result's data variables and coordinates as plain arrays."""
    out = {}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        values = np.asarray(var.values)
        if values.dtype.kind == "O":
            values = values.astype(str)
        out[str(name)] = values
    return out


# Variables renamed since the references were written (stored name -> name now): the
# same results under a clearer name, compared under the new one. attractor_share: each
# attractor's share of the one-body search, which read like a basin share (issue 31.12).
RENAMED = {"attractor_share": "attractor_search_share"}


def load_stored(name: str) -> dict[str, np.ndarray]:
    """The stored reference of scene ``name``, its variables under today's names."""
    with np.load(STORE / f"{name}.npz") as f:
        return {RENAMED.get(k, k): f[k] for k in f.files}


def digest(values: np.ndarray) -> str:
    return hashlib.sha256(np.ascontiguousarray(values).tobytes()).hexdigest()[:16]


def differences(stored: dict, now: dict, rtol: float = 1e-9) -> list[str]:
    """What differs between two results' arrays (empty when they agree)."""
    problems = []
    for name in sorted(set(stored) | set(now)):
        if name not in now or name not in stored:
            problems.append(f"{name}: only in {'stored' if name in stored else 'new'} result")
            continue
        a, b = stored[name], now[name]
        if a.shape != b.shape:
            problems.append(f"{name}: shape {a.shape} -> {b.shape}")
        elif a.dtype.kind in "fc":
            if not np.allclose(a, b, rtol=rtol, atol=0.0, equal_nan=True):
                bad = int(np.sum(~np.isclose(a, b, rtol=rtol, atol=0.0, equal_nan=True)))
                problems.append(f"{name}: {bad} of {a.size} values differ beyond {rtol:g}")
        elif not np.array_equal(a, b):
            bad = int(np.sum(a != b)) if a.shape == b.shape else a.size
            problems.append(f"{name}: {bad} of {a.size} values differ")
    return problems


def write(names: list[str] | None = None) -> None:
    STORE.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, options in SCENES:
            if names and name not in names:
                continue
            ds = run_scene(scene, options, Path(tmp) / f"{name}.h5")
            np.savez_compressed(STORE / f"{name}.npz", **arrays_of(ds))
            print(f"{name}: {len(ds.data_vars)} variables stored", flush=True)


def compare(names: list[str] | None = None) -> int:
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, options in SCENES:
            if names and name not in names:
                continue
            now = arrays_of(run_scene(scene, options, Path(tmp) / f"{name}.h5"))
            stored = load_stored(name)
            problems = differences(stored, now)
            bitwise = all(digest(stored[k]) == digest(now[k]) for k in stored if k in now)
            failed += bool(problems)
            print(f"{name}: {'; '.join(problems) or 'identical'}"
                  f"{' (bitwise)' if bitwise and not problems else ''}", flush=True)
    return failed


if __name__ == "__main__":
    command, *names = sys.argv[1:] or ["compare"]
    sys.exit(write(names) if command == "write" else compare(names))
