"""The scene form of a chain (config/chain_scene.py): read, and refused in one line."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from softimpact_cli.config import ConfigError
from softimpact_cli.config.examples import CHAIN_EXAMPLE
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene

HEAD = """\
[system]
model = "chain"
bodies = 3
c = 0.05
k2 = 0.01
F = [1.0, 0.5, 0.0]
phi = [0.0, "5*pi/8", "5*pi/4"]
w = 1.3
"""

TAIL = """
[analysis]
kind = "trajectory"
state = [1.5, 0.0, -0.5, 1.0, -2.0, 0.0]
periods = 3
"""

STOPS = """
[[stop]]
between = [1, 2]
d = 2.0

[[stop]]
body = 3
wall = 2.5
side = "left"
law = "hunt-crossley"
exponent = 1.5
"""


def test_a_chain_scene_is_read_into_named_values():
    scene = parse_scene(HEAD + STOPS + TAIL)
    assert scene.system.model == "chain" and scene.system.bodies == 3
    assert scene.system.state_names == ("x1", "v1", "x2", "v2", "x3", "v3")
    v = scene.values
    assert (v["F.1"], v["F.2"], v["F.3"]) == (1.0, 0.5, 0.0)
    assert v["phi.2"] == 5 * math.pi / 8 and v["c.3"] == 0.05 and v["m.2"] == 1.0
    assert v["stop.1.d"] == 2.0 and v["stop.2.wall"] == 2.5 and v["stop.2.k_c"] == 8.0
    surfaces = scene.system.surfaces(scene.system.pack(v))
    assert surfaces.names == ("stop 1", "stop 2") and surfaces.contacts == 0b11
    # the left wall: contact while x3 <= 2.5, g = 2.5 - x3
    assert np.array_equal(surfaces.A[1], [0, 0, 0, 0, -1, 0]) and surfaces.b[1] == 2.5


def test_the_printed_example_is_a_valid_scene():
    scene = parse_scene(CHAIN_EXAMPLE)
    assert scene.system.bodies == 3 and len(scene.system.extra["chain"].stops) == 3


@pytest.mark.parametrize("change, message", [
    ("bodies = 0", "[system] bodies: must be a whole number in 1..8, got 0"),
    ("bodies = 1000", "[system] bodies: must be a whole number in 1..8, got 1000"),
    ("m = -1.0", "[system] m: must be > 0, got -1.0"),
    ("m = [1.0, 2.0]", "[system] m: has 2 values for 3 bodies; give one number or a list of 3"),
    ("phi = [0.0, 1.0]", "[system] phi: has 2 values for 3 bodies"),
    ("k_x3 = 0.1", "[system] k_x3: unknown key"),
])
def test_bad_system_keys_are_one_line(change, message):
    key = change.split(" = ")[0]
    head = "\n".join(line for line in HEAD.splitlines() if not line.startswith(key + " "))
    with pytest.raises(ConfigError) as err:
        parse_scene(head + "\n" + change + "\n" + STOPS + TAIL, "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("stops, message", [
    ("[[stop]]\nbetween = [1, 4]\nd = 1.0\n",
     "s.toml: [stop 1] between: body 4 does not exist; bodies 1..3"),
    ("[[stop]]\nbody = 5\nwall = 1.0\nside = \"left\"\n",
     "s.toml: [stop 1] body: body 5 does not exist; bodies 1..3"),
    ("[[stop]]\nbody = 1\nwall = 1.0\n",
     "s.toml: [stop 1] side: is required: \"left\" or \"right\""),
    ("[[stop]]\nbody = 1\nwall = 1.0\nd = 2.0\nside = \"left\"\n",
     "s.toml: [stop 1] d: a wall stop has no gap"),
    ("[[stop]]\nd = 2.0\n", "s.toml: [stop 1]: needs between = [i, j]"),
    ("[[stop]]\nbetween = [1, 2]\n", "s.toml: [stop 1] d: is required"),
    ("[[kink]]\nbody = 1\nside = \"left\"\nx = -1.0\nk = 2.0\n"
     "[[kink]]\nbody = 1\nside = \"left\"\nx = -1.0\nk = 3.0\n",
     "s.toml: [[kink]]: kinks 1 and 2 overlap: body 1, side 'left', position -1"),
    ("[[kink]]\nbody = 1\nside = \"up\"\nx = -1.0\nk = 2.0\n",
     "s.toml: [kink 1] side: must be one of 'right', 'left', got 'up'"),
])
def test_bad_stops_and_kinks_are_one_line(stops, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(HEAD + stops + TAIL, "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_chain_tables_only_with_a_chain_and_coupling_only_without():
    with pytest.raises(ConfigError, match=r"\[\[stop\]\]: only for model = 'chain'"):
        parse_scene('[system]\nmodel = "duffing"\n' + STOPS + TAIL)
    with pytest.raises(ConfigError, match=r"\[coupling\]: not for model = 'chain'"):
        parse_scene(HEAD + "[coupling]\nd = 1.0\n" + TAIL)


def test_cli_refuses_a_missing_body_before_anything_runs(tmp_path):
    scene = tmp_path / "bad.toml"
    out = tmp_path / "out.h5"
    scene.write_text(HEAD + "[[stop]]\nbetween = [2, 7]\nd = 1.0\n" + TAIL
                     + f'\n[output]\npath = "{out}"\n')
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene)],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == [
        f"softimpact: error: {scene}: [stop 1] between: body 7 does not exist; bodies 1..3"]
    assert not out.exists()


def test_example_chain_prints_the_commented_scene():
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "example", "chain"],
                          capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout == CHAIN_EXAMPLE


@pytest.mark.parametrize("kind, extra, message", [
    ("atlas", "", "[analysis] kind = 'atlas': not yet for model = \"chain\" (it seeds its "
                  "bifurcation curves from a pair's combinations and continues them in two of "
                  "the pair's parameters; on a chain, kind \"continuation\" finds the folds, "
                  "period doublings and Neimark-Sacker points of its orbits along any one "
                  "parameter by name, kind \"dcrit\" where a stop starts to touch each "
                  "non-impacting product (its grazing) against any parameter, kind "
                  "\"design\" where only one product survives, and kind \"map\" which "
                  "attractors coexist over two parameters); a chain runs kind 'trajectory'"),
])
def test_kinds_a_chain_cannot_run_yet_are_refused_in_one_line(kind, extra, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(HEAD + STOPS + f'[analysis]\nkind = "{kind}"\n' + extra, "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_the_readme_chain_runs_as_written(tmp_path):
    """The README's three-body chain (its toml block under "A chain of your own"), run."""
    readme = (Path(__file__).parents[2] / "README.md").read_text()
    section = readme[readme.index("### A chain of your own"):]
    block = section[section.index("```toml\n") + 8:]
    block = block[: block.index("```")]
    scene = parse_scene(block + f'\n[output]\npath = "{tmp_path / "chain.h5"}"\n', "README")
    assert scene.system.model == "chain" and scene.system.bodies == 3
    result = run_scene(scene)
    assert result["section_contacts"].sum() > 0  # the stops engage
    assert result.sizes["section"] == 101 and result.sizes["variable"] == 6


def test_lyapunov_of_a_chain_sums_to_its_damping():
    """kind = "lyapunov" on a two-body chain with unequal masses whose stop never engages:
    the exponents sum to the trace of the Jacobian, -(c1/m1 + c2/m2) (Liouville)."""
    text = """
[system]
model = "chain"
bodies = 2
m = [1.0, 2.0]
c = [0.05, 0.1]
k2 = 0.01
phi = [0.0, 1.0]

[[stop]]
between = [1, 2]
d = 50.0

[analysis]
kind = "lyapunov"
state = [1.0, 0.0, -1.0, 0.0]
periods = 100
transient = 10
"""
    ds = run_scene(parse_scene(text))
    assert int(ds["status"][0]) == 0 and ds.sizes["order"] == 4
    total = float(ds["exponent"][0].sum())
    assert abs(total - (-(0.05 / 1.0 + 0.1 / 2.0))) < 1e-6


def test_the_python_system_of_a_chain_runs_trajectories_and_refuses_names():
    import softimpact_cli as si

    system = si.System(HEAD + STOPS + TAIL)
    assert system.state_names == ("x1", "v1", "x2", "v2", "x3", "v3")
    ds = system.trajectory([1.5, 0.0, -0.5, 1.0, -2.0, 0.0], periods=3)
    assert ds.sizes["variable"] == 6
    for call in (system.catalogue, lambda: system.classify([0.0] * 6),
                 lambda: system.with_(w=1.2)):
        with pytest.raises(ConfigError, match='not yet for model = "chain"') as err:
            call()
        assert "\n" not in str(err.value)
