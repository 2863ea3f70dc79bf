"""What a result records (issue 20, item 3 and "results other tools read well"): the start
time actually used, and the label as CF categorical data."""

import numpy as np
import pytest

from softimpact_cli.kinds.results import describe
from softimpact_cli.kinds.run import run_scene
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store import open_result
from softimpact_cli.sweep import run_sweep
from softimpact_cli.sweep.result import categorical_attrs, cf_word

BASINS = """
[system]
model = "duffing"
[coupling]
d = 6.0
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [3, 2]
{t0}
[catalogue]
grid = 6
random = 30
seed = 2
"""
T = 2 * np.pi / 1.3  # the duffing default w = 1.3


@pytest.fixture(scope="module")
def at_0_and_half_T(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("t0")
    out = {}
    for name, line in (("zero", ""), ("half", 't0 = "T/2"')):
        path = tmp / f"{name}.h5"
        run_sweep(parse_scene(BASINS.format(t0=line), f"{name}.toml"), path, workers=1)
        out[name] = open_result(path)
    return out


def test_a_fixed_t0_is_recorded_in_attrs_and_coordinate(at_0_and_half_T):
    zero, half = at_0_and_half_T["zero"], at_0_and_half_T["half"]
    assert half["t0"].values.tolist() == pytest.approx([T / 2])
    assert zero["t0"].values.tolist() == [0.0]
    assert half.attrs["t0"] == pytest.approx(T / 2) and half.attrs["t0_over_T"] == 0.5
    assert zero.attrs["t0"] == 0.0 and zero.attrs["t0_over_T"] == 0.0
    assert half.attrs["t0_mode"] == zero.attrs["t0_mode"] == "fixed"
    assert describe(half)["t0"] == pytest.approx(T / 2)  # `info` shows it


def test_the_label_is_cf_categorical_data(at_0_and_half_T):
    ds = at_0_and_half_T["zero"]
    attrs = ds["label"].attrs
    assert attrs["flag_values"].dtype == ds["label"].dtype
    assert list(attrs["flag_values"]) == list(ds["label_code"].values)
    words = attrs["flag_meanings"].split(" ")
    names = attrs["flag_names"].split("; ")
    assert names == list(ds["label_name"].values) and len(words) == len(names)
    assert words[0] == "L1_1_R1-0_1" and names[0] == "L1^1 R1-0^1"
    assert ds.attrs["Conventions"] == "CF-1.10"
    assert len(ds.attrs["history"].splitlines()) == 1  # one run, one line: time + command
    assert ds.attrs["history"][:4].isdigit()


def test_cf_words_are_safe_and_unique():
    assert cf_word("L1^2 R1-0^1") == "L1_2_R1-0_1"
    assert cf_word("unresolved") == "unresolved"
    attrs = categorical_attrs([0, 1, -1], ["a b", "a^b", "x"], np.int32)
    assert attrs["flag_meanings"] == "a_b a_b_ x"
    assert attrs["flag_values"].dtype == np.int32


@pytest.mark.parametrize("kind", ["trajectory", "catalogue"])
def test_analysis_t0_is_recorded(kind):
    section = ("kind = 'trajectory'\nstate = [8.0, 0.0, -4.0, 0.0]\nperiods = 3\n"
               if kind == "trajectory" else "kind = 'catalogue'\ngrid = 2\nrandom = 2\n")
    scene = parse_scene(f"[system]\nmodel = 'duffing'\n[coupling]\nd = 6.0\n[analysis]\n"
                        f"{section}t0 = \"T/4\"\n", f"{kind}.toml")
    ds = run_scene(scene)
    assert ds.attrs["t0"] == pytest.approx(T / 4)
    assert ds.attrs["t0_over_T"] == pytest.approx(0.25) and ds.attrs["t0_mode"] == "fixed"
