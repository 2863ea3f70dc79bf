"""A chain's rigid stop in a scene: read, and its bad input refused in one line, exit 2."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from softimpact_cli.config import ConfigError
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.report.info import describe

HEAD = """\
[system]
model = "chain"
bodies = 1
c = 0.1
k1 = 1.0
F = 1.0
phi = "pi/2"
w = 0.8
"""

TAIL = """
[analysis]
kind = "trajectory"
state = [0.0, 0.0]
periods = 4
"""

RIGID = """
[[stop]]
body = 1
wall = 1.2
side = "right"
law = "rigid"
r = 0.8
"""


def test_a_rigid_stop_is_read_with_its_restitution_and_no_stiffness():
    scene = parse_scene(HEAD + RIGID + TAIL)
    v = scene.values
    assert v["stop.1.r"] == 0.8 and "stop.1.k_c" not in v and "stop.1.c_c" not in v
    assert scene.system.extra["rigid"] and not scene.system.piecewise_linear


@pytest.mark.parametrize("change, message", [
    (("r = 0.8", "r = 1.5"), "[stop 1] r: must be in [0, 1]"),
    (("r = 0.8", "r = -0.1"), "[stop 1] r: must be in [0, 1]"),
    (("r = 0.8", "r = 0.8\nk_c = 100.0"), "[stop 1] k_c: not a key of law 'rigid'"),
    (("r = 0.8", "r = 0.8\nc_c = 1.0"), "[stop 1] c_c: not a key of law 'rigid'"),
    (('law = "rigid"', 'law = "paper"'), "[stop 1] r: not a key of law 'paper'"),
    (('law = "rigid"', 'law = "hunt-crossley"'), "[stop 1] r: not a key of law"),
])
def test_bad_rigid_keys_are_one_line(change, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(HEAD + RIGID.replace(*change) + TAIL, "s.toml")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_preset_coupling_takes_no_rigid_law():
    text = ('[system]\nmodel = "duffing"\n[coupling]\nlaw = "rigid"\n'
            '[analysis]\nkind = "trajectory"\nstate = [1.0, 0.0, 0.0, 0.0]\nperiods = 2\n')
    with pytest.raises(ConfigError) as err:
        parse_scene(text, "s.toml")
    assert "law" in str(err.value) and "\n" not in str(err.value)


def test_rigid_needs_located_switches_and_the_lyapunov_saltation():
    with pytest.raises(ConfigError, match="locate_switches"):
        parse_scene(HEAD + RIGID + TAIL + '[integrator]\nmethod = "rk4"\n'
                    'locate_switches = false\n', "s.toml")
    lyapunov = '\n[analysis]\nkind = "lyapunov"\nstart = "state"\nstate = [0.0, 0.0]\n'
    parse_scene(HEAD + RIGID + lyapunov, "s.toml")  # runs: the impacts' saltation is applied
    with pytest.raises(ConfigError, match="saltation: false is not offered with a rigid stop"):
        parse_scene(HEAD + RIGID + lyapunov + "saltation = false\n", "s.toml")


def test_cli_refuses_restitution_out_of_range_before_anything_runs(tmp_path):
    scene = tmp_path / "s.toml"
    out = tmp_path / "out.h5"
    scene.write_text(HEAD + RIGID.replace("r = 0.8", "r = 2.0") + TAIL
                     + f'[output]\npath = "{out}"\n')
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene)],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and not out.exists()
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "r: must be in [0, 1]" in lines[0]


def test_a_rigid_trajectory_scene_counts_its_impacts(tmp_path):
    scene = parse_scene(HEAD + RIGID + TAIL + f'[output]\npath = "{tmp_path / "t.h5"}"\n')
    ds = run_scene(scene)
    assert ds.attrs["rigid_impacts"] >= 1 and ds.attrs["rigid_chatter_sequences"] >= 0
    assert ds.attrs["rigid_impacts"] == int(ds["section_contacts"].sum())
    assert np.isfinite(ds.attrs["rigid_sticking_time"])
    assert float(ds["state"].sel(variable="x1").max()) <= 1.2 + 1e-12  # never past it
    summary = describe(ds)  # what info shows
    assert summary["rigid_impacts"] == ds.attrs["rigid_impacts"]
    assert {"rigid_chatter_sequences", "rigid_sticking_phases",
            "rigid_sticking_time"} <= set(summary)
