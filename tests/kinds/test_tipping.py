"""The tipping kind: the study's control scenario (d 22 -> 6 at phi = 0) from the command
line, its matrix against the two panels' own labels, the solutions' destinations against
a direct labelling, and the refusal of a grid that is not two points."""

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact_cli as si
from softimpact_cli.analysis.tipping import tipping_probabilities
from softimpact_cli.cli import main
from softimpact_cli.kinds.scene import parse_scene

SCENE = "configs/tipping_duffing_d22_to_6.toml"


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    out = tmp_path_factory.mktemp("tipping") / "tip.h5"
    run = CliRunner().invoke(main, ["sweep", SCENE, "--resolution", "12", "-o", str(out),
                                    "--workers", "1", "-q"])
    assert run.exit_code == 0, run.output
    return out


def test_the_matrix_is_the_overlap_of_the_two_panels(result):
    ds = si.open_result(result)
    label = ds["label"].transpose("panel", "x1", "x2").values.reshape(2, -1)
    table = dict(zip(ds["label_code"].values.tolist(),
                     [str(n) for n in ds["label_name"].values], strict=True))
    again = tipping_probabilities(label[0], label[1], table)
    np.testing.assert_array_equal(ds["tip_count"].values, again["tip_count"].values)
    assert ds.attrs["tip_before"] == "d = 22, phi = 0"
    assert ds.attrs["tip_after"] == "d = 6, phi = 0"
    # at d = 22 the four combinations coexist; the study's figure 6(d) keeps two at d = 6
    assert set(ds["tip_from"].values) == {"L1^1 R1-0^1", "L1^1 R1-0^2", "L1^2 R1-0^1",
                                          "L1^2 R1-0^2"}
    assert set(ds["tip_to"].values) <= {"L1^1 R1-0^1", "L1^2 R1-0^2"}


def test_destinations_are_the_orbits_labelled_at_the_second_point(result):
    ds = si.open_result(result)
    dest = {str(s): [str(v) for v in row if v] for s, row in
            zip(ds["tip_solution"].values, ds["tip_destination"].values, strict=True)}
    assert set(dest) == set(ds["tip_from"].values)
    # independently: each combination's section points as a list scene at d = 6
    orbits = {str(n): ds["combination_orbit"].values[i] for i, n
              in enumerate(ds["combination_name"].values)}
    states = [p.tolist() for name in dest for p in orbits[name] if np.all(np.isfinite(p))]
    text = (open(SCENE).read().replace('kind = "tipping"', 'kind = "basins"')
            .replace("panels = [{ d = 22.0 }, { d = 6.0 }]", "d = 6.0")
            .split("[initial_conditions]")[0]
            + f'[initial_conditions]\nkind = "list"\nstates = {states}\n')
    direct = si.run(parse_scene(text, "<direct>"), workers=1, verify=False)
    names = dict(zip(direct["label_code"].values.tolist(),
                     [str(n) for n in direct["label_name"].values], strict=True))
    got = [names[int(c)] for c in direct["label"].values.ravel()]
    assert got == [v for name in dest for v in dest[name]]
    assert dest["L1^1 R1-0^1"] == ["L1^1 R1-0^1"]  # the survivor stays


def test_info_and_plot(result, tmp_path):
    runner = CliRunner()
    info = runner.invoke(main, ["info", str(result)])
    assert info.exit_code == 0, info.output
    assert "tipping from (d = 22, phi = 0) to (d = 6, phi = 0)" in info.output
    assert "  basin L1^1 R1-0^1 (" in info.output
    assert "solutions before, their section points (t = 0 mod T) labelled after:" in \
        info.output
    as_json = runner.invoke(main, ["info", str(result), "--json"])
    assert '"destinations"' in as_json.output
    for extra, panels in (([], 3), (["--no-basins"], 1)):
        png = tmp_path / f"t{panels}.png"
        run = runner.invoke(main, ["plot", "tipping", str(result), "-o", str(png), *extra])
        assert run.exit_code == 0, run.output
        assert png.stat().st_size > 10_000
    fig = si.plot.tipping(si.open_result(result))
    assert len([a for a in fig.axes if a.get_visible()]) >= 3


def test_a_grid_of_other_than_two_points_is_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(open(SCENE).read().replace("panels = [{ d = 22.0 }, { d = 6.0 }]",
                                              "panels = [{ d = 22.0 }, { d = 6.0 }, "
                                              "{ d = 2.0 }]"))
    run = CliRunner().invoke(main, ["sweep", str(bad), "-o", str(tmp_path / "x.h5")])
    assert run.exit_code == 2
    assert run.output.strip().splitlines() == [
        f"softimpact: error: {bad}: [grid]: kind 'tipping' needs exactly 2 grid points "
        "(before and after, e.g. panels = [{d = 22.0}, {d = 6.0}]), got 3"]
    assert not (tmp_path / "x.h5").exists()
