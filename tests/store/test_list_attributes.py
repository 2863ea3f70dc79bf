"""List-valued attributes are lists in memory and arrays in the file, read back as lists;
the one-body search's shares are named for what they are (attractor_search_share); and
a result written the old way (joined texts, attractor_share) still opens, prints, plots
and gives its shares."""

import json

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.analysis.attributes import LIST_ATTRIBUTES, as_list, attribute_list
from softimpact_cli.analysis.catalogue import OLD_SEARCH_SHARE, SEARCH_SHARE, catalogue_from_dataset
from softimpact_cli.cli import main
from softimpact_cli.store import open_result
from tests.test_api import PLANE  # figure 6(d)'s plane, 10 x 8 starts


def written_the_old_way(ds: xr.Dataset, path) -> None:
    """``ds`` as softimpact wrote it before 2026-11-27: list attributes joined into one
    text ("x1 x2"; names with "; "), the search's shares named attractor_share."""
    old = ds.rename({SEARCH_SHARE: OLD_SEARCH_SHARE})
    for key in LIST_ATTRIBUTES:
        if key in old.attrs:
            joined = "; " if key == "catalogue_names" else " "
            old.attrs[key] = joined.join(str(v) for v in old.attrs[key])
    old.to_netcdf(path, engine="h5netcdf")


@pytest.fixture(scope="module")
def plane(tmp_path_factory):
    folder = tmp_path_factory.mktemp("plane")
    ds = si.sweep(PLANE, folder / "new.h5", workers=1)
    written_the_old_way(ds, folder / "old.h5")
    return ds, folder / "new.h5", folder / "old.h5"


def test_list_attributes_are_lists_and_arrays_in_the_file(plane):
    import h5py

    ds, new, _ = plane
    assert ds.attrs["ic_dims"] == ["x1", "x2"]
    assert ds.attrs["grid_swept"] == [] and ds.attrs["grid_dims"] == [
        "d", "phi", "k_c", "c_c", "t0"]
    assert ds.attrs["catalogue_names"] == ["L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1",
                                           "L1^2 R1-0^2"]
    with h5py.File(new, "r") as f:  # arrays in the file, not one joined text
        assert [v.decode() if isinstance(v, bytes) else v for v in f.attrs["ic_dims"]] == \
            ["x1", "x2"]
        assert len(f.attrs["catalogue_names"]) == 4
    for read in (open_result(new), si.open_result(new)):
        for key in ("ic_dims", "grid_swept", "grid_dims", "catalogue_names"):
            assert read.attrs[key] == ds.attrs[key], key
    with xr.open_dataset(new, engine="h5netcdf") as raw:  # a 1-element array: its element
        assert attribute_list(raw.attrs, "grid_dims") == ds.attrs["grid_dims"]


def test_each_stored_form_reads_as_the_list():
    assert as_list("ic_dims", "x1 x2") == ["x1", "x2"] == as_list("ic_dims", ["x1", "x2"])
    assert as_list("grid_swept", "d") == ["d"] == as_list("grid_swept", np.array(["d"]))
    assert as_list("grid_swept", "") == [] == as_list("grid_swept", np.array([]))
    assert as_list("catalogue_names", "L1^1 R1-0^1; L1^2 R1-0^2") == ["L1^1 R1-0^1",
                                                                      "L1^2 R1-0^2"]
    assert as_list("catalogue_names", "L1^1 R1-0^1") == ["L1^1 R1-0^1"]
    assert as_list("box_sizes", "2 5 10") == [2, 5, 10] == as_list("box_sizes",
                                                                  np.array([2, 5, 10]))
    assert as_list("cell_size", "0.5 0.25") == [0.5, 0.25]
    assert as_list("radii", np.int64(3)) == [3]
    assert as_list("ic_dims", json.dumps(["x1", "x2"])) == ["x1", "x2"]


def test_the_search_share_says_what_it_is(plane):
    """Issue 31.12: each attractor's share of the one-body search is not a basin share."""
    ds, _, _ = plane
    assert OLD_SEARCH_SHARE not in ds and SEARCH_SHARE in ds
    text = ds[SEARCH_SHARE].attrs["long_name"]
    assert "attractor search" in text and "not a basin share" in text
    basin = ds.si.shares().set_index("label")["share"]
    search = dict(zip(ds["attractor_name"].values, ds[SEARCH_SHARE].values, strict=True))
    assert set(search) == {"L1^1", "L1^2"} and sum(search.values()) == pytest.approx(1.0)
    assert basin["L1^1 R1-0^1"] != pytest.approx(search["L1^1"], abs=0.05)  # not the same


def test_a_result_written_the_old_way_still_opens(plane, tmp_path):
    ds, _, old = plane
    with xr.open_dataset(old, engine="h5netcdf") as raw:
        assert raw.attrs["ic_dims"] == "x1 x2" and OLD_SEARCH_SHARE in raw
    read = si.open_result(old)
    for key in ("ic_dims", "grid_swept", "grid_dims", "catalogue_names"):
        assert read.attrs[key] == ds.attrs[key], key
    assert read.si.shares().equals(ds.si.shares())
    si.plot.basins(read)
    cat = catalogue_from_dataset(read)
    assert [a.share for a in cat.attractors] == ds[SEARCH_SHARE].values.tolist()
    runner = CliRunner()
    info = runner.invoke(main, ["info", str(old)])
    assert info.exit_code == 0, info.output
    table = info.output.split("catalogue:\n")[1].splitlines()
    assert table[0].split()[-2:] == ["search", "residual"]
    assert f"{ds[SEARCH_SHARE].values[0]:7.3f}" in table[1]
    assert runner.invoke(main, ["plot", "basins", str(old), "-o",
                                str(tmp_path / "b.png")]).exit_code == 0
