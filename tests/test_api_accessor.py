"""ds.si (softimpact_cli/accessor.py): label names and basin shares with their 95%
intervals as a table, on results from si.run, si.open_result and xarray.open_dataset;
si.kinds(), the kinds registry with its help lines."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import softimpact_cli as si
from softimpact_cli.analysis.stability import wilson_interval

ROOT = Path(__file__).parents[1]
PLANES = {"system": {"model": "duffing"},  # figure 6(d)'s plane at d = 6 and d = 10
          "coupling": {"d": 6.0, "phi": 0.0, "k_c": 8.0, "c_c": 10.0},
          "analysis": {"kind": "basins"},
          "initial_conditions": {"kind": "plane", "axes": ["x1", "x2"],
                                 "ranges": [[-12.0, 12.0], [-12.0, 12.0]],
                                 "resolution": [10, 8]},
          "catalogue": {"grid": 4, "random": 20},
          "grid": {"d": [6.0, 10.0]}}


@pytest.fixture(scope="module")
def planes(tmp_path_factory):
    out = tmp_path_factory.mktemp("planes") / "planes.h5"
    return si.sweep(PLANES, out, workers=1), out


def counted(ds) -> dict[tuple[float, str], int]:
    """{(d, label name): starts} counted from the labels themselves."""
    names = dict(zip(ds["label_code"].values.tolist(), ds["label_name"].values.tolist(),
                     strict=True))
    out = {}
    for d in ds["d"].values:
        codes, counts = np.unique(ds["label"].sel(d=d).values, return_counts=True)
        out.update({(float(d), names[int(c)]): int(n) for c, n in zip(codes, counts,
                                                                        strict=True)})
    return out


def test_shares_are_the_label_counts_with_wilson_intervals(planes):
    ds, _ = planes
    table = ds.si.shares()
    assert list(table.columns) == ["d", "label", "count", "share", "ci_low", "ci_high"]
    assert len(table) == 2 * ds.sizes["label_index"]  # every label at every d
    n = ds.sizes["x1"] * ds.sizes["x2"]
    expected = counted(ds)
    for row in table.itertuples():
        count = expected.get((row.d, row.label), 0)
        assert row.count == count and row.share == count / n
        lo, hi = wilson_interval(count, n)
        assert (row.ci_low, row.ci_high) == (float(lo), float(hi))
        assert row.ci_low <= row.share <= row.ci_high
    for d in (6.0, 10.0):
        assert table[table.d == d]["share"].sum() == pytest.approx(1.0)
    assert len(set(table[table["count"] > 0]["label"])) >= 2


def test_shares_of_one_point_and_the_sums(planes):
    ds, _ = planes
    one = ds.sel(d=6.0).si.shares(groups=True)
    assert list(one.columns) == ["label", "count", "share", "ci_low", "ci_high"]
    rows = dict(zip(one["label"], one["count"], strict=True))
    assert rows["impacting (all)"] + rows["non-impacting (sum)"] + rows.get(
        "unresolved", 0) + rows.get("diverged", 0) == ds.sizes["x1"] * ds.sizes["x2"]


def test_shares_without_pandas_are_a_list_of_dicts(planes, monkeypatch):
    ds, _ = planes
    import builtins

    frame = ds.si.shares()
    real = builtins.__import__

    def without_pandas(name, globals=None, *args, **kwargs):  # for the accessor only:
        if name == "pandas" and (globals or {}).get("__name__") == "softimpact_cli.accessor":
            raise ImportError("No module named 'pandas'")  # xarray itself needs pandas
        return real(name, globals, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", without_pandas)
    rows = ds.si.shares()
    assert isinstance(rows, list) and rows == frame.to_dict("records")


def test_names_and_the_files_xarray_opens(planes):
    import xarray as xr

    ds, out = planes
    names = ds.si.names()
    assert names == dict(zip(ds["label_code"].values.tolist(),
                             ds["label_name"].values.tolist(), strict=True))
    assert all(isinstance(k, int) and isinstance(v, str) for k, v in names.items())
    with xr.open_dataset(out, engine="h5netcdf") as raw:
        assert raw.si.names() == names
        assert raw.si.shares().equals(ds.si.shares())
    assert si.open_result(out).si.shares().equals(ds.si.shares())
    pair = {k: PLANES[k] for k in ("system", "coupling")}
    trajectory = si.System(pair).trajectory([8.0, 0.0, -4.0, 0.0], periods=3)
    with pytest.raises(ValueError, match="'trajectory' result has no label table"):
        trajectory.si.names()


def test_kinds_lists_the_registry_with_one_line_each():
    from softimpact_cli.kinds import ANALYSIS_KINDS, KINDS

    listed = si.kinds()
    assert tuple(listed) == ANALYSIS_KINDS and len(listed) >= 13
    assert listed == {name: kind.description for name, kind in KINDS.items()}
    assert all(text and "\n" not in text for text in listed.values())
    # si.kinds is the function, the package stays importable, whatever is imported later
    code = ("import softimpact_cli as si; import softimpact_cli.kinds.trajectory; "
            "from softimpact_cli.kinds import KINDS; "
            "assert callable(si.kinds) and list(si.kinds()) == list(KINDS)")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


def test_the_accessor_is_there_for_datasets_xarray_opens_itself():
    """Importing softimpact_cli after xarray registers ds.si; before, the package still
    imports no xarray (it registers ds.si on the first dataset it returns)."""
    code = ("import xarray as xr, numpy as np; import softimpact_cli; "
            "ds = xr.Dataset({'label_code': ('label_index', np.array([0, -2])), "
            "'label_name': ('label_index', np.array(['L1^1', 'unresolved']))}); "
            "assert ds.si.names() == {0: 'L1^1', -2: 'unresolved'}")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)
    code = "import sys, softimpact_cli; assert 'xarray' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)
