"""`softimpact design`: end to end on a tiny scene (in process, so the kernels compile
once), `info --json` and `plot design` on its result, and one clean line with exit
status 2 and no file for every bad target or bad design key."""

import json
import subprocess
import sys

import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.cli import main
from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import parse_scene

SCENE = """
[system]
model = "duffing"
[analysis]
kind = "design"
target = "L1^2 R1-0^2"
bounds = {{d = [3.0, 10.0], phi = ["pi/2", "3*pi/2"], k_c = [4.0, 12.0]}}
candidates = 4
screen_n = 12
refine = 2
robust_n = 12
phi_points = 24
reference = {{d = 5.0, phi = "pi"}}
[initial_conditions]
kind = "random"
box = {{x1 = [-12, 12], v1 = [-12, 12], x2 = [-12, 12], v2 = [-12, 12]}}
n = 24
seed = 15
[catalogue]
grid = 6
random = 20
[output]
path = "{out}"
"""


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def design_result(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("design")
    scene = tmp / "design.toml"
    out = tmp / "design.h5"
    scene.write_text(SCENE.format(out=out))
    # the scene's target (large orbits) is never alone: --target replaces it
    result = run("design", scene, "--target", "L1^1 R1-0^1", "--workers", 2, "-q")
    assert result.exit_code == 0, result.output
    return scene, out, result.stdout


def test_design_prints_table_and_writes_result(design_result):
    _, out, stdout = design_result
    assert out.is_file()
    assert "design for L1^1 R1-0^1" in stdout and "reference" in stdout
    assert "robustness" in stdout


def test_info_json_gives_the_pick(design_result):
    _, out, _ = design_result
    result = run("info", out, "--json")
    assert result.exit_code == 0, result.output
    info = json.loads(result.stdout)
    assert info["target"] == "L1^1 R1-0^1" and info["analysis"] == "design"
    best = info["best"]
    assert {"d", "phi", "k_c", "c_c", "share", "ci95", "impacting_share", "margin"} <= set(best)
    assert 0 <= best["ci95"][0] <= best["share"] <= best["ci95"][1] <= 1
    assert best["c_c"] == 10.0  # not in bounds: fixed at the [coupling] default
    assert len(info["runners_up"]) == 1
    ref = info["reference"]
    assert (ref["d"], ref["k_c"], ref["c_c"]) == (5.0, 8.0, 10.0)  # defaults filled in
    assert "--target 'L1^1 R1-0^1'" in info["scene"]  # the override is recorded
    assert f"d={best['d']}" in info["parameters"]  # the parameters are the pick's


def test_info_text_and_plot(design_result, tmp_path):
    _, out, _ = design_result
    result = run("info", out)
    assert result.exit_code == 0 and "design for L1^1 R1-0^1" in result.stdout
    fig = tmp_path / "design.png"
    result = run("plot", "design", out, "-o", fig)
    assert result.exit_code == 0, result.output
    assert fig.stat().st_size > 20_000


def test_existing_result_needs_overwrite(design_result):
    scene, out, _ = design_result
    before = out.stat().st_mtime_ns
    result = run("sweep", scene, "-q")  # sweep runs a design scene the same way
    assert result.exit_code == 2 and "--overwrite" in result.stderr
    result = run("sweep", scene, "--resume")
    assert result.exit_code == 2 and "a design reruns whole" in result.stderr
    assert out.stat().st_mtime_ns == before


def one_clean_line(result):
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("softimpact: error:"), result.stderr
    return lines[0]


@pytest.mark.parametrize("target, says", [
    ("impacting P1", "is an impacting solution"),
    ("unresolved", "is an unresolved outcome"),
    ("L1^1", "one body's attractor"),
    ("L1^1 R1-5^1", "shift must be < gcd"),
    ("nonsense", "cannot read label"),
])
def test_bad_target_on_the_command_line(tmp_path, target, says):
    scene = tmp_path / "s.toml"
    out = tmp_path / "r.h5"
    scene.write_text(SCENE.format(out=out))
    line = one_clean_line(run("design", scene, "--target", target))
    assert "--target" in line and says in line
    assert not out.exists()


def test_target_not_in_catalogue(tmp_path, design_result):
    scene = tmp_path / "s.toml"
    out = tmp_path / "r.h5"
    scene.write_text(SCENE.format(out=out))
    line = one_clean_line(run("design", scene, "--target", "L1^3 R1-0^1", "-q"))
    assert "[analysis] target" in line and "not in the catalogue" in line
    assert "L1^1 R1-0^1" in line  # names what there is
    assert not out.exists()


def test_target_never_alone(tmp_path, design_result):
    scene = tmp_path / "s.toml"
    out = tmp_path / "r.h5"
    scene.write_text(SCENE.format(out=out))
    line = one_clean_line(run("design", scene, "-q"))  # the scene's own L1^2 R1-0^2
    assert "never the only non-impacting combination" in line
    assert not out.exists()


def test_bad_target_as_a_subprocess(tmp_path):
    """The installed entry point too: one line on stderr, status 2, no file."""
    scene = tmp_path / "s.toml"
    out = tmp_path / "r.h5"
    scene.write_text(SCENE.format(out=out).replace('"L1^2 R1-0^2"', '"impacting P2"'))
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene)],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.strip().count("\n") == 0 and "[analysis] target" in proc.stderr
    assert not out.exists()


@pytest.mark.parametrize("change, key", [
    (("candidates = 4", "candidate = 4"), "[analysis] candidate: unknown key"),
    (("bounds = {{d = [3.0, 10.0], ", "bounds = {{"), "[analysis] bounds"),
    (("k_c = [4.0, 12.0]}}", "k_c = [12.0, 4.0]}}"), "[analysis] bounds.k_c"),
    (("k_c = [4.0, 12.0]}}", "k_c = [4.0, 12.0], kc = [1, 2]}}"), "bounds.kc: unknown axis"),
    (('reference = {{d = 5.0, phi = "pi"}}', 'reference = {{d = "x"}}'), "reference.d"),
    (("kind = \"random\"", "kind = \"plane\"\nranges = [[0, 1], [0, 1]]"),
     "[initial_conditions] kind"),
    (("[catalogue]", "[grid]\nd = 3.0\n[catalogue]"), "[grid]"),
    (("screen_n = 12", "screen_n = 0"), "[analysis] screen_n"),
])
def test_bad_design_keys(change, key):
    old, new = change
    text = SCENE.replace(old, new).format(out="r.h5")
    assert text != SCENE.format(out="r.h5")
    with pytest.raises(ConfigError) as err:
        parse_scene(text, "s.toml")
    assert key in str(err.value) and "\n" not in str(err.value)


def test_design_reports_the_targets_minimal_fatal_shock(design_result):
    """At the pick only the target survives, so no shock up to half the sampled box's
    diagonal reaches another attractor; the reference is measured the same way."""
    _, out, printed = design_result
    ds = si.open_result(out)
    assert ds.attrs["fatal_shock_settings"] == ("4 phases x 16 directions, 16 magnitudes up "
                                                "to 24, bisection to 0.01")
    assert ds.attrs["fatal_shock_best"] == float("inf")
    assert "fatal_shock_reference" in ds.attrs
    info = run("info", out, "--json")
    shocks = json.loads(info.output)["fatal_shock"]
    assert set(shocks) == {"best", "reference"}
    assert "minimal fatal shock of the target (an upper bound; 4 phases x 16" in printed
    assert "  pick: none up to the largest shock scanned" in printed
