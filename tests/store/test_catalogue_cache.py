"""The catalogue cache: a repeated search is read back bit for bit, any change of what it
depends on is a miss, a damaged or tampered entry is recomputed, writes are atomic, and
SOFTIMPACT_NO_CACHE / --no-cache turn it off."""

import json
import os

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact_cli.analysis.catalogue import (
    body_problem,
    sample_states,
    search_arrays,
    search_from_arrays,
    search_key_material,
)
from softimpact_cli.cli import main
from softimpact_cli.config import IntegratorSettings
from softimpact_cli.kinds.scene import parse_scene
from softimpact_cli.store import catalogue_cache, catalogues
from softimpact_cli.store.catalogues import cached_body_search
from softimpact_cli.sweep import run_sweep
from softimpact_cli.systems import get_system

from ..sweep.test_sweep import equal_results, scene_text

PAIR = get_system("duffing", 2)
VALUES = PAIR.defaults()
STATES = sample_states({"x": (-12.0, 12.0), "v": (-12.0, 12.0)}, 2, 4, 1)  # 8 states
DEFAULT = IntegratorSettings()


@pytest.fixture(autouse=True)
def own_cache(tmp_path, monkeypatch):
    """A fresh cache folder per test, on."""
    monkeypatch.setenv("SOFTIMPACT_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("SOFTIMPACT_NO_CACHE", raising=False)
    return tmp_path / "cache" / "catalogues"


@pytest.fixture
def searches(monkeypatch):
    """Counts the one-body searches actually run."""
    calls = []
    real = catalogues.body_catalogue

    def counted(*args, **kwargs):
        calls.append(args)
        return real(*args, **kwargs)

    monkeypatch.setattr(catalogues, "body_catalogue", counted)
    return calls


def search(values=VALUES, integrator=DEFAULT, states=STATES, match_tol=1e-3):
    return cached_body_search(body_problem(PAIR, values, integrator), states, 0.0, match_tol)


def same_search(a, b) -> bool:
    """Equal to the bit, multipliers' dtype included."""
    return (search_key_bytes(a) == search_key_bytes(b) and a.counts == b.counts
            and a.n_states == b.n_states)


def search_key_bytes(s) -> bytes:
    return b"".join(v.dtype.str.encode() + v.tobytes() for _, v in
                    sorted(search_arrays(s).items()))


def test_second_search_is_read_from_the_cache_bit_for_bit(searches, own_cache):
    first = search()
    again = search()
    assert len(searches) == 1
    assert first.source == "computed" and again.source.startswith("cache ")
    assert again.source[6:] == catalogue_cache.entry_key(
        search_key_material(body_problem(PAIR, VALUES, IntegratorSettings()), STATES, 0.0,
                            1e-3))[:catalogue_cache.KEY_SHOWN]
    assert first.attractors and same_search(first, again)
    for a, b in zip(first.attractors, again.attractors, strict=True):
        assert a.points.tobytes() == b.points.tobytes()
        assert a.multipliers.dtype == b.multipliers.dtype
        assert (a.amplitude, a.share, a.residual) == (b.amplitude, b.share, b.residual)
    assert len(list(own_cache.glob("*.npz"))) == 1


def test_arrays_round_trip_keeps_real_multipliers_real():
    s = search()
    real = s._replace(attractors=[a.__class__(a.number, a.period, a.points, a.amplitude,
                                              np.array([0.5, -0.25]), a.share, a.residual)
                                  for a in s.attractors])
    back = search_from_arrays(search_arrays(real), "x")
    assert all(b.multipliers.dtype == np.float64 for b in back.attractors)
    assert same_search(real, back)


@pytest.mark.parametrize("change", ["body parameter", "catalogue states", "match_tol",
                                    "integrator", "sources"])
def test_a_changed_ingredient_is_a_miss(searches, monkeypatch, change):
    search()
    kwargs = {}
    if change == "body parameter":
        kwargs["values"] = {**VALUES, "F": VALUES["F"] * (1 + 1e-15)}
    elif change == "catalogue states":
        kwargs["states"] = sample_states({"x": (-12.0, 12.0), "v": (-12.0, 12.0)}, 2, 4, 2)
    elif change == "match_tol":
        kwargs["match_tol"] = 2e-3
    elif change == "integrator":
        kwargs["integrator"] = IntegratorSettings(rtol=1e-9)
    else:
        from softimpact_cli.kernels import numba_cache

        monkeypatch.setattr(numba_cache, "source_hash", lambda **_: "edited sources")
    assert search(**kwargs).source == "computed"
    assert len(searches) == 2


def test_coupling_parameters_are_not_part_of_the_key(searches):
    search()
    other = {**VALUES, "d": 3.0, "phi": 1.0, "k_c": 2.0, "c_c": 7.0}
    assert search(values=other).source.startswith("cache ")
    assert len(searches) == 1


def entry(own_cache):
    (path,) = own_cache.glob("*.npz")
    return path


def test_damaged_entry_is_recomputed_and_replaced(searches, own_cache):
    first = search()
    path = entry(own_cache)
    path.write_bytes(path.read_bytes()[:100])  # truncated
    again = search()
    assert again.source == "computed" and same_search(first, again) and len(searches) == 2
    assert search().source.startswith("cache ")


def test_tampered_or_foreign_entry_is_recomputed(searches, own_cache):
    search()
    path = entry(own_cache)
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    arrays["amplitude"] = arrays["amplitude"] + 1.0  # checksum no longer matches
    with open(path, "wb") as fh:
        np.savez(fh, **arrays)
    assert search().source == "computed"
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    meta = json.loads(arrays["meta"].tobytes())
    meta["material"]["match_tol"] = 0.5  # another search's key material under this key
    arrays["meta"] = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    with open(path, "wb") as fh:
        np.savez(fh, **arrays)
    assert search().source == "computed"
    assert len(searches) == 3


def test_no_cache_variable_is_honoured(searches, own_cache, monkeypatch):
    monkeypatch.setenv("SOFTIMPACT_NO_CACHE", "1")
    assert search().source == search().source == "computed (cache off)"
    assert len(searches) == 2 and not own_cache.exists()


def test_a_failed_write_leaves_no_entry_and_no_temporary_file(own_cache, monkeypatch):
    def killed(fh, **arrays):
        fh.write(b"PK\x03\x04 half an entry")
        raise OSError("killed")

    monkeypatch.setattr(catalogue_cache.np, "savez", killed)
    assert search().source == "computed"
    assert list(own_cache.iterdir()) == []


def test_an_entry_appears_whole_under_its_name(own_cache, monkeypatch):
    seen = []
    replace = os.replace

    def watching(src, dst):
        seen.append((os.path.basename(src).startswith("."), os.path.exists(dst),
                     np.load(src)["meta"].size > 0))
        replace(src, dst)

    monkeypatch.setattr(catalogue_cache.os, "replace", watching)
    search()
    assert seen == [(True, False, True)]  # written as a hidden temporary, complete, renamed


def test_unwritable_folder_is_not_an_error(monkeypatch, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setenv("SOFTIMPACT_CACHE_DIR", str(blocker))  # catalogues/ cannot be made
    assert search().source == search().source == "computed"


def test_info_and_clear(own_cache):
    assert catalogue_cache.info().entries == 0
    search()
    state = catalogue_cache.info()
    assert (state.location, state.entries, state.enabled) == (own_cache, 1, True)
    assert state.size == entry(own_cache).stat().st_size
    assert catalogue_cache.clear() == 1 and catalogue_cache.info().entries == 0


def test_cache_commands(own_cache):
    search()
    runner = CliRunner()
    shown = runner.invoke(main, ["cache", "info", "--json"])
    assert shown.exit_code == 0 and json.loads(shown.output)["entries"] == 1
    assert str(own_cache) in runner.invoke(main, ["cache", "info"]).output
    cleared = runner.invoke(main, ["cache", "clear"])
    assert cleared.exit_code == 0 and "removed 1 catalogue cache entry" in cleared.output
    assert catalogue_cache.info().entries == 0


def test_switched_off_restores_the_variable(monkeypatch):
    with catalogue_cache.switched_off():
        assert not catalogue_cache.enabled()
    assert catalogue_cache.enabled() and "SOFTIMPACT_NO_CACHE" not in os.environ
    monkeypatch.setenv("SOFTIMPACT_NO_CACHE", "0")
    with catalogue_cache.switched_off():
        assert not catalogue_cache.enabled()
    assert os.environ["SOFTIMPACT_NO_CACHE"] == "0"


# ------------------------------------------------------------------ a whole sweep


def sweep(tmp_path, name: str):
    out = tmp_path / f"{name}.h5"
    return run_sweep(parse_scene(scene_text(out, 4), f"{name}.toml"), out, workers=1)


def test_sweep_with_cached_catalogue_equals_one_without(tmp_path, monkeypatch, searches):
    cold = sweep(tmp_path, "cold")
    warm = sweep(tmp_path, "warm")
    monkeypatch.setenv("SOFTIMPACT_NO_CACHE", "1")
    off = sweep(tmp_path, "off")
    assert len(searches) == 2  # cold and off
    assert cold.attrs["catalogue_source"] == "computed"
    assert warm.attrs["catalogue_source"].startswith("cache ")
    assert off.attrs["catalogue_source"] == "computed (cache off)"
    for other in (warm, off):
        equal_results(cold, other)
        for v in ("attractor_amplitude", "multiplier_re", "multiplier_im", "combination_orbit"):
            assert cold[v].values.tobytes() == other[v].values.tobytes(), v


def test_sweep_no_cache_flag(tmp_path, searches):
    scene = tmp_path / "s.toml"
    out = tmp_path / "s.h5"
    scene.write_text(scene_text(out, 2))
    runner = CliRunner()
    for flags in ((), ("--no-cache",)):  # --no-verify: the verification's own catalogue
        result = runner.invoke(main, ["sweep", str(scene), "--workers", "1", "--overwrite",
                                      "--no-verify", *flags])  # would search once more
        assert result.exit_code == 0, result.output
    assert "catalogue search: computed (cache off)" in result.output
    assert len(searches) == 2 and "SOFTIMPACT_NO_CACHE" not in os.environ
    shown = runner.invoke(main, ["info", str(out)])
    assert "catalogue_source" in shown.output and "cache off" in shown.output
