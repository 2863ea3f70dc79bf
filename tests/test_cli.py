"""The command line: end to end on a small scene, and one clean line for every user error."""

import json
import subprocess
import sys
from pathlib import Path

import pytest
import xarray as xr

SCENE = """
[system]
model = "duffing"
[coupling]
d = 3.0
phi = "pi"
[integrator]
max_periods = 400
[analysis]
kind = "trajectory"
state = [3.0, 0.0, -3.0, 0.0]
periods = 20
samples_per_period = 32
[output]
path = "{out}"
"""


def run_cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "softimpact_cli", *args], capture_output=True,
                          text=True, cwd=cwd)


@pytest.fixture(scope="module")
def trajectory_result(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("traj")
    out = tmp / "traj.h5"
    scene = tmp / "scene.toml"
    scene.write_text(SCENE.format(out=out))
    proc = run_cli("sweep", str(scene))
    assert proc.returncode == 0, proc.stderr
    return scene, out


def test_sweep_writes_readable_trajectory(trajectory_result):
    _, out = trajectory_result
    with xr.open_dataset(out) as ds:
        assert ds.sizes["section"] == 21 and ds.sizes["variable"] == 4
        assert ds.sizes["time"] == 20 * 32 + 1
        assert ds.attrs["outcome"] in ("converged", "unresolved")
        assert "[coupling]" in ds.attrs["scene_text"]
        assert ds.attrs["complete"] == 1 and ds.attrs["wall_s"] > 0
        assert ds["section_contacts"].sum() > 0  # the start overlaps the stop: contact
        # the dense samples at t = nT coincide with the stroboscopic points
        st = ds["state"].values[::32]
        assert abs(st - ds["section_state"].values).max() < 1e-9


def test_info_json(trajectory_result):
    _, out = trajectory_result
    proc = run_cli("info", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    info = json.loads(proc.stdout)
    assert info["analysis"] == "trajectory" and info["model"] == "duffing"
    assert info["outcome"] == "converged" and info["period"] >= 1
    assert {"contacts_on_orbit", "wall_s", "scene"} <= set(info)


def test_plot_trajectory(trajectory_result, tmp_path):
    _, out = trajectory_result
    fig = tmp_path / "fig.png"
    proc = run_cli("plot", "trajectory", str(out), "-o", str(fig))
    assert proc.returncode == 0, proc.stderr
    assert fig.stat().st_size > 10_000


def test_existing_result_needs_overwrite(trajectory_result):
    scene, out = trajectory_result
    before = out.stat().st_mtime_ns
    proc = run_cli("sweep", str(scene))
    assert proc.returncode == 2 and "--overwrite" in proc.stderr
    assert out.stat().st_mtime_ns == before


def _assert_clean_error(proc, *fragments):
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert "Traceback" not in proc.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


BAD_SCENES = {
    "unknown_key.toml": ("[system]\nmodel='duffing'\ndamping=0.1\n", "[system] damping"),
    "misspelt.toml": ("[system]\nmodel='duffing'\n[coupeling]\nd=1\n", "[coupeling]"),
    "negative_damping.toml": ("[system]\nmodel='duffing'\n[coupling]\nc_c=-1\n",
                              "[coupling] c_c"),
    "nan.toml": ("[system]\nmodel='duffing'\nk1=nan\n", "[system] k1"),
    "bad_phi.toml": ("[system]\nmodel='duffing'\n[coupling]\nphi='5*pie/8'\n", "[coupling] phi"),
    "bad_exponent.toml": ("[system]\nmodel='duffing'\n[coupling]\nlaw='hunt-crossley'\n"
                          "exponent=0.5\n", "[coupling] exponent"),
    "exponent_of_paper.toml": ("[system]\nmodel='duffing'\n[coupling]\nexponent=1.5\n",
                               "[coupling] exponent"),
}


@pytest.mark.parametrize("name", sorted(BAD_SCENES))
def test_bad_scene_one_line_exit_2_nothing_written(tmp_path, name):
    text, key = BAD_SCENES[name]
    out = tmp_path / "out.h5"
    scene = tmp_path / name
    scene.write_text(text + f"[output]\npath='{out}'\n")
    proc = run_cli("sweep", str(scene))
    _assert_clean_error(proc, str(scene), key)
    assert list(tmp_path.iterdir()) == [scene]


def test_missing_scene_file(tmp_path):
    proc = run_cli("sweep", str(tmp_path / "missing.toml"))
    _assert_clean_error(proc, "missing.toml", "no such scene file")


def test_unwritable_output(tmp_path):
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    scene = tmp_path / "s.toml"
    scene.write_text("[system]\nmodel='duffing'\n[analysis]\nstate=[1,0,0,0]\n"
                     f"[output]\npath='{blocker}/out.h5'\n")
    proc = run_cli("sweep", str(scene))
    _assert_clean_error(proc, "s.toml", "[output] path", "cannot write")
    proc = run_cli("sweep", str(scene), "-o", str(blocker / "x.h5"))
    _assert_clean_error(proc, "-o/--output", "cannot write")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "s.toml"]


def test_info_on_missing_or_foreign_file(tmp_path):
    _assert_clean_error(run_cli("info", str(tmp_path / "x.h5")), "no such result file")
    junk = tmp_path / "junk.h5"
    junk.write_text("not hdf5")
    _assert_clean_error(run_cli("info", str(junk)), "junk.h5", "not a softimpact result")


def test_library_run_imports_neither_click_nor_matplotlib(tmp_path):
    code = (
        "import sys\n"
        "from softimpact_cli.kinds.scene import parse_scene\n"
        "from softimpact_cli.kinds.run import run_scene\n"
        "scene = parse_scene(\"[system]\\nmodel='duffing'\\nbodies=1\\n[analysis]\\n"
        "state=[1.0, 0.0]\\nperiods=2\\n\")\n"
        "run_scene(scene)\n"
        "bad = [m for m in ('matplotlib', 'click', 'h5py') if m in sys.modules]\n"
        "assert not bad, bad\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=Path(__file__).parent)
    assert proc.returncode == 0, proc.stderr


# ------------------------------------------------------------------ stiff stops (issue 7)

STIFF_SCENE = """
[system]
model = "duffing"
[coupling]
d = 1.0
phi = "pi"
k_c = 1e6
c_c = {c_c}
[integrator]
method = "{method}"
max_periods = 200
[analysis]
kind = "trajectory"
state = [2.0, 0.0, -2.0, 0.0]
periods = 3
samples_per_period = 16
"""


def test_stiff_stop_rk4_warns_and_diverges_auto_converges(tmp_path):
    """k_c = 1e6 (Duffing pair, phi = pi, d = 1): RK4 at T/1440 is warned about, then
    reports diverged; --strict refuses to start; the default method converges, and info
    says how many steps each of its methods took."""
    from softimpact_cli.kinds.results import describe  # what `softimpact info` prints

    scene = tmp_path / "rk4.toml"
    scene.write_text(STIFF_SCENE.format(c_c=1e3, method="rk4"))
    out = tmp_path / "rk4.h5"
    proc = run_cli("sweep", str(scene), "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    assert "warning" in proc.stderr and "method 'stiff'" in proc.stderr
    with xr.open_dataset(out) as ds:
        assert ds.attrs["outcome"] == "diverged"
    strict = tmp_path / "strict.h5"
    _assert_clean_error(run_cli("sweep", str(scene), "-o", str(strict), "--strict"),
                        "rk4.toml", "steps_per_period")
    assert not strict.exists()
    scene = tmp_path / "auto.toml"
    scene.write_text(STIFF_SCENE.format(c_c=1e4, method="auto"))  # stability bound in contact
    out = tmp_path / "auto.h5"
    proc = run_cli("sweep", str(scene), "-o", str(out))
    assert proc.returncode == 0 and "warning" not in proc.stderr, proc.stderr
    with xr.open_dataset(out) as ds:
        info = describe(ds)
    assert info["outcome"] == "converged" and info["integrator_resolved_method"] == "auto"
    steps = info["steps_by_method"]["classify"]
    assert steps["explicit"] > 0 and steps["stiff"] > 0 and steps["method_switches"] >= 2


HUNT_CROSSLEY_BASINS = """
[system]
model = "duffing"
[coupling]
d = 3.0
phi = "pi"
law = "hunt-crossley"
exponent = 1.5
[integrator]
max_periods = 400
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-8.0, 8.0], [-8.0, 8.0]]
resolution = [6, 6]
[catalogue]
grid = 4
random = 10
[output]
path = "{out}"
"""


def test_hunt_crossley_basins_and_trajectory_end_to_end(tmp_path):
    """law = "hunt-crossley" through sweep, info and plot: a basins plane and a trajectory
    that touches the stop."""
    out = tmp_path / "hc.h5"
    scene = tmp_path / "hc.toml"
    scene.write_text(HUNT_CROSSLEY_BASINS.format(out=out))
    proc = run_cli("sweep", str(scene))
    assert proc.returncode == 0, proc.stderr
    with xr.open_dataset(out) as ds:
        assert "law=hunt-crossley" in ds.attrs["parameters"]
        assert "exponent=1.5" in ds.attrs["parameters"]
        assert ds["label"].size == 36 and int((ds["status"] == 0).sum()) >= 30
    info = run_cli("info", str(out))
    assert info.returncode == 0 and "exponent=1.5" in info.stdout, info.stderr
    proc = run_cli("plot", "basins", str(out), "-o", str(tmp_path / "hc.png"))
    assert proc.returncode == 0, proc.stderr
    traj = tmp_path / "traj.toml"
    traj.write_text(SCENE.format(out=tmp_path / "traj.h5").replace(
        'phi = "pi"', 'phi = "pi"\nlaw = "hunt-crossley"\nexponent = 2.0'))
    proc = run_cli("sweep", str(traj))
    assert proc.returncode == 0, proc.stderr
    with xr.open_dataset(tmp_path / "traj.h5") as ds:
        assert ds.attrs["outcome"] == "converged"
        assert ds["section_contacts"].sum() > 0
        assert "exponent=2.0" in ds.attrs["parameters"]


def test_only_the_command_collects_garbage_less_often():
    # the `softimpact` script raises the collector's threshold from its first import on; a
    # program importing the package (a notebook, a test) keeps its own
    import subprocess
    import sys

    def threshold(argv0: str, load: bool) -> str:
        code = (f"import sys; sys.argv[0] = {argv0!r}; import gc; "
                + ("import softimpact_cli; " if load else "") + "print(*gc.get_threshold())")
        return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              check=True).stdout.strip()

    assert threshold("/x/.venv/bin/softimpact", True) == "50000 20 20"
    assert threshold("notebook", True) == threshold("notebook", False)
