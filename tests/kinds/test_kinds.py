"""Every analysis kind end to end on a tiny result: info, info --json, plot, compare.

The results are built once per module, in process (click's CliRunner), so that the
numba kernels load once. A fast subset (trajectory, catalogue, basins) runs unmarked.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main

PAIR = """
[system]
model = "duffing"
[coupling]
d = 10.5
phi = 5.28
"""
CATALOGUE = """
[catalogue]
grid = 4
random = 12
"""
RANDOM_IC = """
[initial_conditions]
kind = "random"
box = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}
n = 6
seed = 1
"""
SCENES = {
    "trajectory": PAIR + """
[analysis]
kind = "trajectory"
state = [3.0, 0.0, -3.0, 0.0]
periods = 10
samples_per_period = 16
""",
    "catalogue": """
[system]
model = "duffing"
[analysis]
kind = "catalogue"
box = {x = [-12, 12], v = [-12, 12]}
grid = 4
random = 12
""",
    "basins": PAIR + CATALOGUE + """
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12, 12], [-12, 12]]
resolution = 4
""",
    "stability": PAIR + CATALOGUE + RANDOM_IC + """
[analysis]
kind = "stability"
[grid]
c_c = [5.0, 10.0]
""",
    "dcrit": """
[system]
model = "duffing"
[analysis]
kind = "dcrit"
[grid]
phi = [0.5, 2.0, 4.0]
""" + CATALOGUE,
    "bifurcation": """
[system]
model = "duffing"
[coupling]
phi = "5*pi/8"
[analysis]
kind = "bifurcation"
start = 22.0
stop = 20.0
step = 1.0
""" + CATALOGUE,
    "map": """
[system]
model = "duffing"
[analysis]
kind = "map"
[grid]
d = [2.0, 22.0]
phi = [0.0, "pi"]
""" + RANDOM_IC + CATALOGUE,
    "design": """
[system]
model = "duffing"
[analysis]
kind = "design"
target = "L1^1 R1-0^1"
bounds = {d = [3.0, 10.0], phi = ["pi/2", "3*pi/2"], k_c = [4.0, 12.0]}
candidates = 4
screen_n = 12
refine = 2
robust_n = 12
phi_points = 24
[initial_conditions]
kind = "random"
box = {x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}
n = 24
seed = 15
[catalogue]
grid = 6
random = 20
""",
    "lyapunov": PAIR + """
[analysis]
kind = "lyapunov"
state = [-9.7384, 0.5832, 1.3324, -1.7490]
transient = 2
periods = 8
segments = 4
[grid]
c_c = [10.0, 9.0]
""",
}
FAST = ("trajectory", "catalogue", "basins", "lyapunov")
COMPARABLE = ("basins", "stability", "map", "dcrit", "bifurcation")


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """{kind: result path}, each computed on first use."""
    tmp = tmp_path_factory.mktemp("kinds")
    made = {}

    def get(kind: str):
        if kind not in made:
            scene = tmp / f"{kind}.toml"
            scene.write_text(SCENES[kind])
            out = tmp / f"{kind}.h5"
            proc = run("sweep", scene, "-o", out, "-q", "--workers", 1)
            assert proc.exit_code == 0, proc.output
            made[kind] = out
        return made[kind]

    return get


def kinds(fast: bool):
    return [k if k in FAST or not fast else pytest.param(k, marks=pytest.mark.slow)
            for k in SCENES]


@pytest.mark.parametrize("kind", kinds(fast=True))
def test_info_plot_compare(kind, results, tmp_path):
    out = results(kind)
    text = run("info", out)
    assert text.exit_code == 0, text.output
    assert text.output.startswith(f"analysis                     {kind}\n") or kind == "design"
    assert "{'" not in text.output and "[{" not in text.output  # no Python reprs
    summary = json.loads(run("info", out, "--json").output)
    assert summary["analysis"] == kind and summary["complete"] in (1, True)
    figure = tmp_path / "x.png"
    drawn = run("plot", kind, out, "-o", figure)
    assert drawn.exit_code == 0, drawn.output
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    same = run("compare", out, out)
    if kind in COMPARABLE:
        assert same.exit_code == 0, same.output
        report = json.loads(run("compare", out, out, "--json").output)
        assert report["failed"] == []
        assert report.get("label_changed", 0) == 0 and report.get("max_d_change", 0) == 0
        assert report.get("max_share_change", 0) == 0
    else:
        assert same.exit_code == 2
        assert same.output.count("\n") == 1 and "compare" in same.output


@pytest.mark.parametrize("kind", list(SCENES))
def test_dry_run_prints_the_plan_and_writes_nothing(kind, tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(SCENES[kind])
    out = tmp_path / "r.h5"
    proc = run("sweep", scene, "-o", out, "--dry-run")
    assert proc.exit_code == 0, proc.output
    assert proc.output.startswith(f"{kind}: ") and f"output: {out}" in proc.output
    if kind in ("basins", "stability", "map"):
        assert "trajectories in" in proc.output
    if kind == "bifurcation":
        assert "x 3 steps of d" in proc.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


EMPTY = ('model = "duffing"\n', 'model = "duffing"\nk2 = -1.0\nF = 5.0\n')  # all diverge


@pytest.mark.parametrize("kind", ["dcrit", "bifurcation", "map"])
def test_empty_catalogue_stops_in_one_line_before_any_file(kind, tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(SCENES[kind].replace(*EMPTY))
    out = tmp_path / "r.h5"
    proc = run("sweep", scene, "-o", out, "-q", "--workers", 1)
    assert proc.exit_code == 2, proc.output
    assert proc.output.count("\n") == 1 and "Traceback" not in proc.output
    assert "catalogue: no attractor found (28 samples: 28 diverged, 0 unresolved); " \
           f"{kind} needs at least one" in proc.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_empty_catalogue_basins_still_run(tmp_path):
    """Every trajectory diverges: a legitimate basins result (all labels 'diverged')."""
    scene = tmp_path / "s.toml"
    scene.write_text(SCENES["basins"].replace(*EMPTY))
    out = tmp_path / "r.h5"
    proc = run("sweep", scene, "-o", out, "-q", "--workers", 1)
    assert proc.exit_code == 0, proc.output
    summary = json.loads(run("info", out, "--json").output)
    assert summary["status"]["diverged"] == 16


def test_design_dry_run_with_target(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(SCENES["design"])
    proc = run("design", scene, "--target", "L1^2 R1-0^2", "-o", tmp_path / "r.h5",
               "--dry-run")
    assert proc.exit_code == 0, proc.output
    assert proc.output.startswith("design: target L1^2 R1-0^2; 4 candidates")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]
