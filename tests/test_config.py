import math
import textwrap

import pytest

from softimpact_cli.config import ConfigError, load_scene, parse_scene

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

    for path in sorted(Path(__file__).parents[1].joinpath("configs").glob("*.toml")):
        load_scene(path)


def test_indented_toml_is_read():
    # scenes written inline in tests and docs are indented
    parse_scene(textwrap.dedent("""
        [system]
        model = "duffing"
        [analysis]
        state = [0.0, 0.0, 0.0, 0.0]
    """))
