import math
import textwrap
from pathlib import Path

import pytest

from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.scene import load_scene, parse_scene
from softimpact_cli.systems import stops

GOOD = """
[system]
model = "bilinear"
F = 0.603
w = 0.928
[coupling]
d = 2.0
phi = "pi/2"
law = "no-tension"
[integrator]
method = "rk4"
steps_per_period = 720
[analysis]
kind = "trajectory"
state = [1.0, 0.0, -1.0, 0.0]
periods = 10
t0 = "T/4"
"""


def test_good_scene_fills_defaults():
    scene = parse_scene(GOOD, "good.toml")
    v = scene.values
    assert scene.system.model == "bilinear" and scene.system.bodies == 2
    assert v["F"] == 0.603 and v["w"] == 0.928
    assert v["k2"] == 29.0 and v["d1"] == 1.26 and v["c"] == 0.02  # SPEC defaults
    assert v["phi"] == pytest.approx(math.pi / 2)
    assert v["k_c"] == 8.0 and v["c_c"] == 10.0 and v["law"] == "no-tension"
    assert scene.integrator.method == "rk4" and scene.integrator.steps_per_period == 720
    assert scene.analysis.t0 == pytest.approx(0.25 * 2 * math.pi / 0.928)
    assert str(scene.output) == "results/good.h5"


def test_hunt_crossley_scene_reads_its_exponent():
    text = ("[system]\nmodel='duffing'\n[coupling]\nlaw='hunt-crossley'\n{}"
            "[analysis]\nstate=[1.0, 0.0, 0.0, 0.0]\n")
    assert parse_scene(text.format("")).values["exponent"] == 1.5  # the default, n = 3/2
    scene = parse_scene(text.format("exponent = 1\n"))
    assert scene.values["law"] == "hunt-crossley" and scene.values["exponent"] == 1.0
    # reaches the kernels' parameters (the coupling block ends the pair's)
    assert scene.system.pack(scene.values)[stops.EXPONENT - stops.COUPLING_SIZE] == 1.0
    assert "exponent" not in parse_scene(GOOD).values  # other laws do not carry it


def test_one_body_scene_has_no_coupling():
    scene = parse_scene('[system]\nmodel="duffing"\nbodies=1\n[analysis]\nstate=[1.0, 0.0]\n')
    assert scene.system.dim == 2 and "d" not in scene.values


def test_scene_is_frozen():
    scene = parse_scene(GOOD)
    with pytest.raises(AttributeError):
        scene.integrator.rtol = 1.0


BAD = {
    "unknown key": ("[system]\nmodel='duffing'\ncc=1\n", "[system] cc", "unknown key"),
    "misspelt section": ("[system]\nmodel='duffing'\n[integrater]\nrtol=1e-6\n",
                         "[integrater]", "did you mean 'integrator'"),
    "negative damping": ("[system]\nmodel='duffing'\nc=-0.1\n", "[system] c", ">= 0"),
    "NaN": ("[system]\nmodel='duffing'\nF=nan\n", "[system] F", "finite"),
    "bad phi": ("[system]\nmodel='duffing'\n[coupling]\nphi='5*pie/8'\n", "[coupling] phi",
                "'a*pi/b'"),
    "w zero": ("[system]\nmodel='duffing'\nw=0\n", "[system] w", "> 0"),
    "negative d1": ("[system]\nmodel='bilinear'\nd1=-1\n", "[system] d1", ">= 0"),
    "negative k_c": ("[system]\nmodel='duffing'\n[coupling]\nk_c=-8\n", "[coupling] k_c", ">= 0"),
    "unknown model": ("[system]\nmodel='van der pol'\n", "[system] model", "'duffing'"),
    "bad law": ("[system]\nmodel='duffing'\n[coupling]\nlaw='hertz'\n", "[coupling] law",
                "'no-tension'"),
    "exponent below 1": ("[system]\nmodel='duffing'\n[coupling]\nlaw='hunt-crossley'\n"
                         "exponent=0.5\n", "[coupling] exponent", "must be in [1, 10], got 0.5"),
    "exponent zero": ("[system]\nmodel='bilinear'\n[coupling]\nlaw='hunt-crossley'\n"
                      "exponent=0\n", "[coupling] exponent", "[1, 10]"),
    "exponent huge": ("[system]\nmodel='duffing'\n[coupling]\nlaw='hunt-crossley'\n"
                      "exponent=11\n", "[coupling] exponent", "[1, 10]"),
    "exponent string": ("[system]\nmodel='duffing'\n[coupling]\nlaw='hunt-crossley'\n"
                        "exponent='3/2'\n", "[coupling] exponent", "must be a number"),
    "exponent nan": ("[system]\nmodel='duffing'\n[coupling]\nlaw='hunt-crossley'\n"
                     "exponent=nan\n", "[coupling] exponent", "finite"),
    "exponent without its law": ("[system]\nmodel='duffing'\n[coupling]\nexponent=1.5\n",
                                 "[coupling] exponent",
                                 "only with law = 'hunt-crossley'; law is 'paper'"),
    "exponent with no-tension": ("[system]\nmodel='duffing'\n[coupling]\nlaw='no-tension'\n"
                                 "exponent=2\n", "[coupling] exponent", "law is 'no-tension'"),
    "bad method": ("[system]\nmodel='duffing'\n[integrator]\nmethod='euler'\n",
                   "[integrator] method", "'dopri5'"),
    "string number": ("[system]\nmodel='duffing'\nk1='1'\n", "[system] k1", "number"),
    "bool number": ("[system]\nmodel='duffing'\n[integrator]\nrtol=true\n", "[integrator] rtol",
                    "number"),
    "state length": ("[system]\nmodel='duffing'\n[analysis]\nstate=[1,2]\n", "[analysis] state",
                     "4 numbers"),
    "periods zero": ("[system]\nmodel='duffing'\n[analysis]\nstate=[1,0,0,0]\nperiods=0\n",
                     "[analysis] periods", "in 1.."),
    "coupling for one body": ("[system]\nmodel='duffing'\nbodies=1\n[coupling]\nd=1\n",
                              "[coupling]", "bodies = 1"),
    "bad toml": ("[system\nmodel='duffing'\n", "invalid TOML", ""),
    "no model": ("[system]\nbodies=2\n", "[system] model", "required"),
    "bad t0": ("[system]\nmodel='duffing'\n[analysis]\nstate=[1,0,0,0]\nt0='T/4pi'\n",
               "[analysis] t0", "'T'"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_scenes_name_file_and_key(name):
    text, where, what = BAD[name]
    with pytest.raises(ConfigError) as info:
        parse_scene(text + ("\n[analysis]\nstate=[1,0,0,0]\n" if "[analysis]" not in text
                            and "bodies=1" not in text and "[system\n" not in text else ""),
                    "scene.toml")
    msg = str(info.value)
    assert msg.startswith("scene.toml: "), msg
    assert where in msg and what in msg, msg
    assert "\n" not in msg


def test_missing_file(tmp_path):
    with pytest.raises(ConfigError, match="no such scene file"):
        load_scene(tmp_path / "nope.toml")


def test_example_scenes_are_valid():
    from pathlib import Path

    for path in sorted(Path(__file__).parents[2].joinpath("configs").glob("*.toml")):
        load_scene(path)


def test_indented_toml_is_read():
    # scenes written inline in tests and docs are indented
    parse_scene(textwrap.dedent("""
        [system]
        model = "duffing"
        [analysis]
        state = [0.0, 0.0, 0.0, 0.0]
    """))


# ---------------------------------------------------------------- sizes and bounds (issue 20)

SWEEP = """
[system]
model = "duffing"
{system}
[analysis]
kind = "basins"
[grid]
{grid}
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-1.0, 1.0], [-1.0, 1.0]]
resolution = {resolution}
{ic}
"""


def sweep_scene(system="", grid="", resolution="[4, 4]", ic=""):
    return SWEEP.format(system=system, grid=grid, resolution=resolution, ic=ic)


def trajectory_scene(analysis="", integrator="", system=""):
    return (f"[system]\nmodel = 'duffing'\n{system}\n[integrator]\n{integrator}\n"
            f"[analysis]\nstate = [1.0, 0.0, -1.0, 0.0]\n{analysis}\n")


SIZE_ERRORS = {
    # a grid axis of 1e9 values: refused before np.linspace builds it
    "num 1e9": (sweep_scene(grid="d = {start = 1.0, stop = 2.0, num = 1000000000}"),
                "[grid] d.num", "at most 1000000"),
    "num 2e6": (sweep_scene(grid="d = {start = 1.0, stop = 2.0, num = 2000000}"),
                "[grid] d.num", "at most 1000000"),
    # 65536^4 = 2^64 grid points: np.prod gave 0
    "65536^4 grid": (sweep_scene(grid="\n".join(f"{a} = {{start = 1.0, stop = 2.0, num = 65536}}"
                                                for a in ("d", "phi", "k_c", "c_c"))),
                     "[grid]", "at most 1000000"),
    "step overflow": (sweep_scene(grid="d = {start = 0.0, stop = 1e308, step = 1e-308}"),
                      "[grid] d", "at most 1000000"),
    "resolution 2^32": (sweep_scene(resolution="[4294967296, 4294967296]"),
                        "[initial_conditions] resolution", "at most 10000000"),
    "trajectories": (sweep_scene(grid="d = {start = 1.0, stop = 2.0, num = 1000}",
                                 resolution="[1000, 1000]"),
                     "[grid]/[initial_conditions]", "at most 10000000 trajectories per sweep"),
    "periods 1e7": (trajectory_scene("periods = 10000000"), "[analysis] periods",
                    "at most 10000000"),
    "t0 1e20": (trajectory_scene("t0 = 1e20"), "[analysis] t0", "at most 1000000 forcing"),
    "t0 1e308*T": (trajectory_scene("t0 = '1e308*T'"), "[analysis] t0", "not finite"),
    "steps_per_period 2^40": (trajectory_scene(integrator="steps_per_period = 1099511627776"),
                              "[integrator] steps_per_period", "in 4..1000000"),
    "w 1e300": (trajectory_scene(system="w = 1e300"), "[system] w", "[0.001, 1000]"),
    "d 1e300": (trajectory_scene() + "[coupling]\nd = 1e300\n", "[coupling] d", "+-1e+09"),
    "phi 1e300": (trajectory_scene() + "[coupling]\nphi = '1e300*pi'\n", "[coupling] phi",
                  "+-1e+09"),
    "huge integer": (trajectory_scene(system="F = 100000000000000000000000000"), "[system] F",
                     "64-bit"),
    "nested arrays": (trajectory_scene(system="F = " + "[" * 20 + "]" * 20), "[system] F",
                      "nested"),
    "nested deeper than tomllib": (trajectory_scene(system="F = " + "[" * 5000 + "]" * 5000),
                                   "nested too deeply", ""),
    "seed 2^63": (sweep_scene().replace('kind = "plane"', 'kind = "random"\nseed = '
                                        '9223372036854775807\nn = 4\nbox = {x1 = [0, 1], '
                                        'v1 = [0, 1], x2 = [0, 1], v2 = [0, 1]}')
                  .replace("axes = [\"x1\", \"x2\"]\nranges = [[-1.0, 1.0], [-1.0, 1.0]]\n"
                           "resolution = [4, 4]\n", ""), None, None),
    "NUL in path": (trajectory_scene() + "[output]\npath = \"a\\u0000b.h5\"\n",
                    "[output] path", "NUL"),
}


@pytest.mark.parametrize("name", sorted(SIZE_ERRORS))
def test_sizes_are_bounded_before_allocating(name):
    text, where, what = SIZE_ERRORS[name]
    if where is None:  # accepted: the largest seed TOML can hold
        assert parse_scene(text, "s.toml").initial_conditions.seed == 2**63 - 1
        return
    with pytest.raises(ConfigError) as info:
        parse_scene(text, "s.toml")
    msg = str(info.value)
    assert msg.startswith("s.toml: ") and "\n" not in msg, msg
    assert where in msg and what in msg, msg


def test_design_sample_count_is_bounded():
    text = (Path(__file__).parents[2] / "configs" / "design_duffing.toml").read_text()
    with pytest.raises(ConfigError, match=r"\[initial_conditions\] n: must be in 1..10000000"):
        parse_scene(text.replace("n = 1000\n", "n = 1000000000\n"), "d.toml")
    with pytest.raises(ConfigError, match="at most 10000000"):  # 100000 x 10**6 screened
        parse_scene(text.replace("n = 1000\n", "n = 1000000\n").replace(
            "candidates = 48", "candidates = 100000").replace("screen_n = 100", "screen_n "
                                                                "= 1000000"), "d.toml")


def test_grid_size_is_a_python_integer():
    scene = parse_scene(sweep_scene(grid="d = [1.0, 2.0, 3.0]\nphi = [0.0, 1.0]"), "s.toml")
    assert scene.grid.size == 6 and isinstance(scene.grid.size, int)
    assert scene.initial_conditions.count == 16


def test_output_path_with_trailing_slash_is_a_directory():
    scene = parse_scene(trajectory_scene() + "[output]\npath = \"newdir/\"\n", "runs/s.toml")
    assert scene.output == Path("newdir/s.h5")


def test_every_shipped_scene_parses():
    root = Path(__file__).parents[2] / "configs"
    scenes = sorted(root.glob("*.toml")) + sorted(root.glob("figures/*.toml"))
    assert len(scenes) >= 20
    for path in scenes:
        load_scene(path)


@pytest.mark.parametrize("text, expected", [
    ("[system]\nmodel = 'duffing'\n",
     "<string>: [analysis]: missing; a scene without it is one trajectory (kind = "
     "\"trajectory\"), which needs [analysis] state = [x1, v1, x2, v2] (the initial state); "
     "or set [analysis] kind"),
    ("[system]\nmodel = 'duffing'\n[initial_conditions]\nkind = 'plane'\n",
     "<string>: [analysis]: missing; a scene without it is one trajectory (kind = "
     "\"trajectory\"), which needs [analysis] state = [x1, v1, x2, v2] (the initial state); "
     "for a sweep over [initial_conditions] set [analysis] kind = \"basins\", \"stability\" "
     "or \"map\""),
    ("[system]\nmodel = 'duffing'\n[analysis]\nperiods = 10\n",
     "<string>: [analysis] state: is required: the initial x1, v1, x2, v2 (no kind is set: "
     "the scene is one trajectory, the default kind)"),
], ids=["no analysis", "no analysis, a plane", "no kind"])
def test_a_scene_without_analysis_names_the_missing_section(text, expected):
    # issue 31, item 11: the message was "[analysis] state: is required" alone
    with pytest.raises(ConfigError) as caught:
        parse_scene(text)
    assert str(caught.value).startswith(expected), str(caught.value)
