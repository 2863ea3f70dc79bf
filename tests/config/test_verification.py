"""[verification]: the section's keys, its errors, and the sample-size rule."""

import subprocess
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softimpact_cli.config import ConfigError, VerificationSettings
from softimpact_cli.kinds.scene import parse_scene

BASINS = """
[system]
model = "duffing"
[analysis]
kind = "basins"
[initial_conditions]
kind = "plane"
axes = ["x1", "x2"]
ranges = [[-12.0, 12.0], [-12.0, 12.0]]
resolution = [10, 10]
"""


def test_defaults_without_the_section():
    v = parse_scene(BASINS, "b.toml").verification
    assert v == VerificationSettings()
    assert (v.share, v.min_sample, v.max_sample, v.threshold) == (0.01, 50, 2000, 0.005)
    assert v.tighten and v.enabled and v.seed == 0
    assert v.pilot and v.pilot_sample == 400


def test_every_key_is_read():
    text = BASINS + ("[verification]\nshare = 0.05\nmin_sample = 10\nmax_sample = 100\n"
                     "threshold = 0.02\ntighten = false\nseed = 7\nenabled = false\n"
                     "pilot = false\npilot_sample = 30\n")
    assert parse_scene(text, "b.toml").verification == VerificationSettings(
        share=0.05, min_sample=10, max_sample=100, threshold=0.02, tighten=False, seed=7,
        enabled=False, pilot=False, pilot_sample=30)


@pytest.mark.parametrize("body, message", [
    ("shares = 0.1", "[verification] shares: unknown key (did you mean 'share'?); allowed: "
                     "enabled, max_sample, min_sample, pilot, pilot_sample, seed, share, "
                     "threshold, tighten"),
    ("share = 0.0", "[verification] share: must be in (0, 1], got 0.0"),
    ("share = 1.5", "[verification] share: must be in (0, 1], got 1.5"),
    ("threshold = 1", "[verification] threshold: must be in (0, 1), got 1.0"),
    ("threshold = \"0.5%\"", "[verification] threshold: must be a number, got '0.5%'"),
    ("min_sample = 0", "[verification] min_sample: must be in 1..1000000, got 0"),
    ("min_sample = 500\nmax_sample = 100",
     "[verification] min_sample: must be <= max_sample (100), got 500"),
    ("tighten = 1", "[verification] tighten: must be true or false, got 1"),
    ("pilot = \"yes\"", "[verification] pilot: must be true or false, got 'yes'"),
    ("pilot_sample = 0", "[verification] pilot_sample: must be in 1..1000000, got 0"),
])
def test_bad_keys_name_the_key_and_what_is_allowed(body, message):
    with pytest.raises(ConfigError) as err:
        parse_scene(BASINS + "[verification]\n" + body + "\n", "b.toml")
    assert str(err.value) == f"b.toml: {message}"


def test_refused_where_there_is_nothing_to_verify():
    text = ('[system]\nmodel = "duffing"\n[analysis]\nkind = "trajectory"\n'
            "state = [1.0, 0.0, -1.0, 0.0]\n[verification]\nshare = 0.1\n")
    with pytest.raises(ConfigError, match=r"t.toml: \[verification\]: only for the "
                                          r"analyses basins, stability, map"):
        parse_scene(text, "t.toml")


def test_cli_bad_key_is_one_line_and_exit_2(tmp_path):
    scene = tmp_path / "b.toml"
    scene.write_text(BASINS + "[verification]\nthreshold = -1\n")
    proc = subprocess.run([sys.executable, "-m", "softimpact_cli", "sweep", str(scene),
                           "-o", str(tmp_path / "b.h5")], capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == [
        f"softimpact: error: {scene}: [verification] threshold: must be in (0, 1), got -1.0"]
    assert not (tmp_path / "b.h5").exists()


@given(share=st.floats(1e-6, 1.0), low=st.integers(1, 5000), span=st.integers(0, 5000),
       total=st.integers(1, 10**7))
def test_sample_size_rule(share, low, span, total):
    v = VerificationSettings(share=share, min_sample=low, max_sample=low + span)
    n = v.sample_size(total)
    assert 1 <= n <= total
    assert n == min(total, max(low, min(low + span, round(share * total))))
    assert min(low, total) <= n <= low + span
    assert v.sample_size(total + 1) >= n  # a larger sweep never reruns fewer


def test_sample_size_examples():
    v = VerificationSettings()
    assert v.sample_size(256) == 50 and v.sample_size(30) == 30
    assert v.sample_size(10_000) == 100 and v.sample_size(250_000) == 2000
