"""The README's commands work as written: subcommands, options, scene files and make
targets exist; the cheap commands run (in a scratch copy of configs/). QUICK=1 shrinks
every figure scene, as the README says."""

import re
import shlex
import shutil
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.kinds.scene import load_scene, quick

ROOT = Path(__file__).parents[1]
README = (ROOT / "README.md").read_text()
MAKEFILE = (ROOT / "Makefile").read_text()
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_]*(\.h5|\.png|\.toml)?$")


def shell_lines(text: str) -> list[str]:
    """The lines of the README's code blocks that are not TOML or Python."""
    lines, block = [], None
    for line in text.splitlines():
        if line.startswith("```"):
            block = None if block is not None else (line[3:].strip() or "sh")
            continue
        if block is not None and block not in ("toml", "python"):
            lines.append(line.strip())
    return lines


def softimpact_commands() -> list[list[str]]:
    """Each `softimpact ...` / `.venv/bin/softimpact ...` line, split as the shell would
    (comments dropped), without the program name."""
    commands = []
    for line in shell_lines(README):
        words = shlex.split(line, comments=True)
        if words and words[0] in ("softimpact", ".venv/bin/softimpact"):
            commands.append(words[1:])
    return commands


COMMANDS = softimpact_commands()


def without_optional(words: list[str]) -> list[str]:
    """The command without its [bracketed] optional parts and any redirection."""
    kept, depth = [], 0
    for w in words:
        if w == ">":
            break
        opened = w.startswith("[")
        depth += w.count("[") - w.count("]")
        if not opened and depth == 0 and not w.endswith("]"):
            kept.append(w)
    return kept


def resolve(words: list[str]) -> tuple[click.Command, list[str]]:
    """The click command a README line calls, and the words after it."""
    command, rest = main, list(words)
    while isinstance(command, click.Group) and rest and not rest[0].startswith("-"):
        name = rest.pop(0)
        sub = command.get_command(click.Context(command), name)  # `plot` asks the registry
        if sub is None:
            pytest.fail(f"README: `softimpact {' '.join(words)}`: no subcommand {name!r}")
        command = sub
    return command, rest


def test_the_readme_shows_softimpact_commands():
    """The README's walk-through (the rest is on the documentation site, whose commands
    tests/docs/test_docs_code.py checks the same way)."""
    subcommands = {c[0] for c in COMMANDS if c}
    assert {"sweep", "info", "plot", "example"} <= subcommands
    assert len(COMMANDS) >= 5


def test_the_readme_is_short_and_its_links_resolve():
    """At most 300 lines (the rest is on the site, docs/); every relative link names a
    file."""
    assert len(README.splitlines()) <= 300
    for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", README):
        assert (ROOT / target).exists(), f"README links to {target}, which does not exist"


@pytest.mark.parametrize("words", COMMANDS, ids=[" ".join(c)[:60] for c in COMMANDS])
def test_readme_command_names_existing_subcommand_options_and_files(words):
    command, rest = resolve(words)
    options = {o for p in command.params for o in (*p.opts, *p.secondary_opts)}
    options |= {"-h", "--help"}
    for w in rest:
        w = w.strip("[]")
        if w.startswith("-") and w not in ("-",):
            assert w in options, f"README: `softimpact {' '.join(words)}`: no option {w}"
        if w.startswith("configs/"):
            assert (ROOT / w).is_file(), f"README: `softimpact {' '.join(words)}`: no {w}"


def _cheap(words: list[str], scratch: Path, written: set[str]) -> bool:
    """Whether a README command is cheap enough to run here (help, example, cache, the
    tiny trajectory scene and what it produced, scenes the README's `example` lines wrote,
    dry runs)."""
    if any("$" in w or PLACEHOLDER.match(w) for w in words):
        return False
    if "--help" in words or "-h" in words or words[0] in ("example", "cache") \
            or "--dry-run" in words:
        return True
    if words[0] == "sweep":
        return words[1] in ("configs/trajectory_duffing.toml", *written)
    if words[0] in ("info", "plot"):
        result = words[1] if words[0] == "info" else words[2]
        return (scratch / result).is_file()
    return False


def test_cheap_readme_commands_run(tmp_path, monkeypatch):
    shutil.copytree(ROOT / "configs", tmp_path / "configs")
    monkeypatch.chdir(tmp_path)
    runner, written, ran = CliRunner(), set(), []
    for line in COMMANDS:
        words = without_optional(line)
        if not words or not _cheap(words, tmp_path, written):
            continue
        resolve(words)  # fails on a subcommand the CLI lacks
        result = runner.invoke(main, words)
        assert result.exit_code == 0, f"`softimpact {' '.join(words)}`: {result.output}"
        if ">" in line:  # `softimpact example KIND > FILE`
            target = line[line.index(">") + 1]
            (tmp_path / target).write_text(result.output)
            written.add(target)
        ran.append(words[0])
    # the walk-through works: help, an example written and run, a result shown and drawn
    assert {"example", "sweep", "info", "plot"} <= set(ran)


def make_targets() -> set[str]:
    targets = set()
    for line in MAKEFILE.splitlines():
        m = re.match(r"^([A-Za-z0-9_.%/ -]+):(?!=)", line)
        if m:
            targets.update(m.group(1).split())
    return targets


def readme_make_targets() -> list[str]:
    """Targets of every `make ...` the README shows, in code blocks and inline code."""
    snippets = [line for line in shell_lines(README) if line.startswith("make ")]
    snippets += re.findall(r"`(make [^`]+)`", README)
    targets = []
    for snippet in snippets:
        for w in shlex.split(snippet, comments=True)[1:]:
            if "=" in w or w.startswith("-"):
                continue
            if not re.fullmatch(r"[a-z0-9-]+", w):
                break  # prose after the command
            targets.append(w)
    return sorted(set(targets))


def test_every_make_target_the_readme_shows_exists():
    shown = readme_make_targets()
    assert {"demo", "test"} <= set(shown)
    missing = [t for t in shown if t not in make_targets()]
    assert not missing, f"README shows make targets the Makefile lacks: {missing}"


def test_no_reference_outside_the_repository():
    for path in [ROOT / "README.md", ROOT / "Makefile", *(ROOT / "configs").rglob("*.toml")]:
        text = path.read_text()
        assert "../shared" not in text and "SPEC.md" not in text, path


FIGURE_SCENES = sorted((ROOT / "configs" / "figures").glob("*.toml")) + sorted(
    (ROOT / "configs").glob("*.toml"))


@pytest.mark.parametrize("path", FIGURE_SCENES, ids=[p.name for p in FIGURE_SCENES])
def test_quick_shrinks_every_scene(path):
    scene = load_scene(path)
    small = quick(scene)
    ic = small.initial_conditions
    if ic is not None and ic.kind == "plane":
        assert max(ic.resolution) <= 24
    if ic is not None and ic.kind == "random":
        assert ic.count <= 100
    if small.grid is not None and not small.grid.panels and scene.analysis.kind != "dcrit":
        for axis in small.grid.swept:
            values = small.grid.axes[axis]
            assert len(values) <= 6
            assert values[0] == scene.grid.axes[axis][0]  # endpoints kept
            assert values[-1] == scene.grid.axes[axis][-1]
    if scene.analysis.kind == "dcrit":
        assert len(small.analysis.phis) <= 64
        assert small.analysis.phis[0] == scene.analysis.phis[0]
    if scene.analysis.kind == "bifurcation":
        a = small.analysis
        assert abs(a.stop - a.start) / a.step <= 50
        assert (a.start, a.stop) == (scene.analysis.start, scene.analysis.stop)
    if scene.analysis.kind == "design":  # every stage still runs, on fewer points
        a = small.analysis
        assert a.candidates <= 6 and 1 <= a.refine <= 2 and a.shock_directions <= 4
        assert a.screen_n <= 50 and (a.robust_n or 0) <= 50
        assert (a.bounds, a.phi_points, a.target) == (scene.analysis.bounds,
                                                      scene.analysis.phi_points,
                                                      scene.analysis.target)
    if scene.analysis.kind == "fatal_shock":
        a = small.analysis
        assert a.phases <= 4 and a.directions <= 16
        assert (a.scan, a.tol, a.max_shock) == (scene.analysis.scan, scene.analysis.tol,
                                                scene.analysis.max_shock)
    if small is not scene:
        assert "--quick" in small.text and small.sha256 != scene.sha256


def test_quick_keeps_explicit_panels_and_resolution_flag_keeps_grids():
    scene = load_scene(ROOT / "configs" / "figures" / "fig06_duffing_basins.toml")
    assert quick(scene).grid == scene.grid  # explicit panels are the figure itself
    map_scene = load_scene(ROOT / "configs" / "figures" / "map_duffing_d_phi.toml")
    assert quick(map_scene, axis=None).grid == map_scene.grid  # --resolution N


def test_every_figure_target_passes_quick():
    """`make figures QUICK=1` must shrink every scene: each sweep or design line of the
    Makefile that runs a figure or design scene passes $(QUICKFLAG)."""
    joined = MAKEFILE.replace("\\\n", " ")
    runs = [line for line in joined.splitlines()
            if re.search(r"\$\(SI\) (sweep|design) ", line)
            and "trajectory" not in line and "demo" not in line]
    assert len(runs) >= 8
    assert all("$(QUICKFLAG)" in line for line in runs), [
        line for line in runs if "$(QUICKFLAG)" not in line]


def test_the_python_api_page_runs_as_written(tmp_path):
    """The worked example of the site's Python API page (docs/howto/python-api.md) runs
    top to bottom (in a scratch folder with configs/), writes what it says and prints
    True for the stored labels."""
    import os
    import subprocess
    import sys

    page = (ROOT / "docs" / "howto" / "python-api.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", page, flags=re.S)
    assert len(blocks) == 1 and "import softimpact_cli as si" in blocks[0]
    shutil.copytree(ROOT / "configs", tmp_path / "configs")
    script = tmp_path / "readme_api.py"
    script.write_text(blocks[0])
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600, env={**os.environ, "MPLBACKEND": "Agg"})
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "basins.png").stat().st_size > 0
    assert (tmp_path / "results" / "basins.h5").is_file()
    lines = run.stdout.strip().splitlines()
    assert lines[-1] == "True" and "(1, 1, 1, 1, 1, 16, 16)" in lines[0]


def test_the_readme_lists_every_kind_of_the_registry():
    from softimpact_cli.kinds import KINDS, REGISTRY

    listed = re.findall(r"^  - `(\w+)`: (.*)$", README, re.M)
    assert [name for name, _ in listed] == list(REGISTRY)
    assert all(line == KINDS[name].description for name, line in listed)


def test_make_stiff_limit_runs_its_recipe_and_draws_the_rate(tmp_path, capsys):
    """The README's `make stiff-limit`: its recipe's script (``make -n``), run here with
    the figure written to a scratch path, finds the soft wall's distance to the rigid
    orbit falling as k_c^(-1/2) (slope within 0.05 over k_c >= 1e3) and draws it."""
    import importlib
    import subprocess
    import sys

    assert "make stiff-limit" in README
    recipe = subprocess.run(["make", "-n", "stiff-limit"], cwd=ROOT, capture_output=True,
                            text=True, check=True).stdout
    assert "benchmarks/stiff_limit.py --out results/stiff_limit.png" in recipe
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        stiff_limit = importlib.import_module("stiff_limit")
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    out = tmp_path / "stiff_limit.png"
    assert stiff_limit.main(["--out", str(out)]) == 0
    assert out.stat().st_size > 10_000
    printed = capsys.readouterr().out
    distance = [float(d) for d in re.findall(r"distance (\S+)", printed)]
    assert len(distance) == 9 and all(a > b for a, b in zip(distance, distance[1:],
                                                              strict=False))
    slope = float(re.search(r"fitted slope (\S+) for k_c >= 1000", printed).group(1))
    assert abs(slope + 0.5) < 0.05
