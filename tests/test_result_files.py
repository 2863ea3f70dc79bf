"""Files that carry softimpact's attributes but are not its results (issue 31, item 9):
every command that reads a result says in one line, exit status 2, which file it is and
what is wrong, never a traceback (on eab4deb: KeyError tracebacks from info, plot,
compare and measure, `info` exit 0 on analysis = "nonsense", and click's usage error for
`compare DIRECTORY`)."""

import string

import pytest
import xarray as xr
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from softimpact_cli.cli import main
from softimpact_cli.kinds import KINDS


def hand_made(path, attrs: dict, variables=()) -> str:
    ds = xr.Dataset({name: ("x", [1.0, 2.0]) for name in variables}, attrs=attrs)
    ds.to_netcdf(path, engine="h5netcdf")
    return str(path)


def commands(path: str, kind: str, tmp_path) -> dict[str, list[str]]:
    """Every command that reads a result file, on ``path``."""
    out = {"info": ["info", path], "info --json": ["info", path, "--json"],
           "compare": ["compare", path, path],
           "measure": ["measure", path, "-o", str(tmp_path / "m.h5"), "--overwrite"]}
    if kind in KINDS and KINDS[kind].plot is not None:
        out["plot"] = ["plot", kind, path, "-o", str(tmp_path / "f.png")]
    return out


def one_line_error(result, path: str) -> str:
    assert result.exit_code == 2, (result.exit_code, result.output, result.exception)
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"softimpact: error: {path}: "), \
        result.output
    return lines[0]


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_result_without_variables(kind, tmp_path):
    path = hand_made(tmp_path / "r.h5", {"analysis": kind, "scene_text": "", "complete": 1})
    for name, args in commands(path, kind, tmp_path).items():
        line = one_line_error(CliRunner().invoke(main, args), path)
        assert f"a {kind} result without its variable" in line, (name, line)
        assert ", ".join(KINDS[kind].variables) in line, (name, line)


def test_an_unknown_analysis(tmp_path):
    path = hand_made(tmp_path / "r.h5", {"analysis": "nonsense", "scene_text": ""})
    for args in commands(path, "nonsense", tmp_path).values():
        line = one_line_error(CliRunner().invoke(main, args), path)
        assert "its 'analysis' attribute is 'nonsense', not one of the kinds trajectory, " \
               "catalogue, basins" in line


def test_compare_a_directory(tmp_path):
    result = CliRunner().invoke(main, ["compare", str(tmp_path), str(tmp_path)])
    assert one_line_error(result, str(tmp_path)).endswith("is a directory, not a result file")


TEXT = st.text(string.ascii_letters + string.digits + "_ -", max_size=12)
COMPLETE = st.one_of(st.none(), st.sampled_from([0, 1]), st.integers(-3, 5), TEXT,
                     st.floats(allow_nan=True))


@settings(max_examples=40, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(analysis=st.one_of(st.sampled_from(list(KINDS)), TEXT), complete=COMPLETE,
       scene=st.one_of(st.none(), TEXT), data=st.data())
def test_malformed_attribute_sets(tmp_path, analysis, complete, scene, data):
    declared = KINDS[analysis].variables if analysis in KINDS else ()
    variables = data.draw(st.lists(st.sampled_from(declared), unique=True,
                                   max_size=max(0, len(declared) - 1))) if declared else []
    attrs = {"analysis": analysis}
    if scene is not None:
        attrs["scene_text"] = scene
    if complete is not None:
        attrs["complete"] = complete
    path = hand_made(tmp_path / "r.h5", attrs, variables)
    header = (analysis in KINDS and KINDS[analysis].sweep and complete == 0
              and not isinstance(complete, bool | str) and scene is not None)
    for name, args in commands(path, analysis, tmp_path).items():
        result = CliRunner().invoke(main, args)
        if header and name.startswith("info"):  # an interrupted sweep's header: its plan
            assert result.exit_code == 0, result.output
            continue
        one_line_error(result, path)


def test_a_sweep_without_the_axis_of_a_swept_parameter(tmp_path):
    path = hand_made(tmp_path / "r.h5", {"analysis": "basins", "scene_text": "",
                                         "complete": 1, "grid_parameters": "w"},
                     KINDS["basins"].variables)
    line = one_line_error(CliRunner().invoke(main, ["info", path]), path)
    assert line.endswith(": a basins result without its variable w (damaged, or not "
                         "written by softimpact)"), line


@pytest.mark.parametrize("kind", [k for k in KINDS if KINDS[k].sweep])
def test_an_unfinished_sweep_header_shows_its_plan(kind, tmp_path):
    """An interrupted sweep's file holds its header only: ``info`` shows the plan and
    exits 0, never a kind's own lines, which read variables not written yet (CI found
    KeyError 'tip_from' from the tipping kind's)."""
    path = hand_made(tmp_path / "r.h5", {"analysis": kind, "scene_text": "", "complete": 0})
    for args in (["info", path], ["info", path, "--json"]):
        result = CliRunner().invoke(main, args)
        assert result.exit_code == 0, (kind, result.output, result.exception)
        if "--json" not in args:
            assert result.output.startswith(f"{kind}: incomplete, 0 of 0 chunks done"), \
                result.output
