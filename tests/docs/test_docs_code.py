"""Every command and code block of the documentation site works as written, as
tests/test_readme.py checks the README's: each `softimpact` line names an existing
subcommand, options and scene files, and the cheap ones run (in a scratch folder holding
a copy of configs/, as from the repository root); each `make` target exists; every
```python block runs (in a new interpreter) and every ```toml block is a scene the reader
accepts or a part of one whose sections and keys the reader knows."""

import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.kinds.key_reference import read_schema
from softimpact_cli.kinds.scene import parse_scene
from tests.test_readme import (
    PLACEHOLDER,
    _cheap,
    make_targets,
    resolve,
    shell_lines,
    without_optional,
)

ROOT = Path(__file__).parents[2]
DOCS = ROOT / "docs"
PAGES = sorted(p for p in DOCS.rglob("*.md"))


def tutorial_markdown(path: Path) -> str:
    """The markdown cells of a percent-format tutorial (its code cells run in the build)."""
    from docs.hooks import percent_cells

    return "\n\n".join(src for kind, src in percent_cells(path.read_text()) if kind == "markdown")


def page_text(path: Path) -> str:
    return tutorial_markdown(path) if path.suffix == ".py" else path.read_text()


SOURCES = PAGES + sorted((DOCS / "tutorials").glob("*.py"))
IDS = [p.relative_to(DOCS).as_posix() for p in SOURCES]


def commands(text: str) -> list[tuple[list[str], str]]:
    """(words after the program name, the line) of each softimpact command line."""
    out = []
    for line in shell_lines(text):
        words = shlex.split(line, comments=True)
        if words and words[0] in ("softimpact", ".venv/bin/softimpact"):
            out.append((words[1:], line))
    return out


def blocks(text: str, language: str) -> list[str]:
    return re.findall(rf"^```{language}\n(.*?)^```", text, flags=re.S | re.M)


def test_the_site_shows_commands_in_a_new_shell():
    """Every command block calls `.venv/bin/softimpact`, except after the page says to
    activate the environment."""
    bare = []
    for path in SOURCES:
        text = page_text(path)
        activated = "source .venv/bin/activate" in text
        for line in shell_lines(text):
            if re.match(r"softimpact\b", line) and not activated:
                bare.append(f"{path.relative_to(DOCS)}: {line}")
    assert not bare, bare


@pytest.mark.parametrize("path", SOURCES, ids=IDS)
def test_page_commands_name_existing_subcommands_options_and_files(path):
    for words, line in commands(page_text(path)):
        command, rest = resolve(words)
        options = {o for p in command.params for o in (*p.opts, *p.secondary_opts)}
        options |= {"-h", "--help"}
        for w in rest:
            w = w.strip("[]")
            if w.startswith("-") and w != "-":
                assert w in options, f"{path.name}: `{line}`: no option {w}"
            if w.startswith("configs/"):
                assert (ROOT / w).is_file(), f"{path.name}: `{line}`: no {w}"


@pytest.mark.parametrize("path", SOURCES, ids=IDS)
def test_cheap_page_commands_run(path, tmp_path, monkeypatch):
    shutil.copytree(ROOT / "configs", tmp_path / "configs")
    monkeypatch.chdir(tmp_path)
    runner, written = CliRunner(), set()
    for line_words, line in commands(page_text(path)):
        words = without_optional(line_words)
        if not words or not _cheap(words, tmp_path, written):
            continue
        result = runner.invoke(main, words)
        assert result.exit_code == 0, f"{path.name}: `{line}`: {result.output}"
        if ">" in line_words:
            target = line_words[line_words.index(">") + 1]
            (tmp_path / target).write_text(result.output)
            written.add(target)


def test_every_make_target_the_site_shows_exists():
    shown = set()
    for path in SOURCES:
        text = page_text(path)
        snippets = [line for line in shell_lines(text) if line.startswith("make ")]
        snippets += re.findall(r"`(make [^`]+)`", text)
        for snippet in snippets:
            for w in shlex.split(snippet, comments=True)[1:]:
                if "=" in w or w.startswith("-"):
                    continue
                if not re.fullmatch(r"[a-z0-9-]+", w):
                    break
                shown.add(w)
    assert {"demo", "test", "docs", "figures"} <= shown
    assert not shown - make_targets(), sorted(shown - make_targets())


# python blocks that cannot run here, and why (each still must compile)
NOT_RUN = {"howto/sweeps.md": "needs dask-jobqueue and a Slurm cluster",
           "howto/python-api.md": "run, with its outputs checked, by "
                                  "tests/test_readme.py::test_the_python_api_page_runs_as_written"}


@pytest.mark.parametrize("path", [p for p in PAGES if blocks(p.read_text(), "python")],
                         ids=lambda p: p.relative_to(DOCS).as_posix())
def test_python_blocks_run(path, tmp_path):
    """Each page's ```python blocks, in order, as one script in a new interpreter (from a
    scratch folder holding configs/)."""
    code = "\n".join(blocks(path.read_text(), "python"))
    compile(code, str(path), "exec")
    if path.relative_to(DOCS).as_posix() in NOT_RUN:
        return
    shutil.copytree(ROOT / "configs", tmp_path / "configs")
    script = tmp_path / "page.py"
    script.write_text(code)
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=900, env={**os.environ, "MPLBACKEND": "Agg"})
    assert run.returncode == 0, run.stderr[-3000:]


KNOWN = {(s, k) for (s, _, k) in read_schema()}


@pytest.mark.parametrize("path", [p for p in PAGES if blocks(p.read_text(), "toml")],
                         ids=lambda p: p.relative_to(DOCS).as_posix())
def test_toml_blocks_are_scenes_or_known_keys(path):
    for block in blocks(path.read_text(), "toml"):
        doc = tomllib.loads(block)
        if "system" in doc and "analysis" in doc:
            parse_scene(block, f"{path.name} block")
            continue
        for section, table in doc.items():
            for key in table:
                assert (section, key) in KNOWN, f"{path.name}: [{section}] {key} is no key"


# What the slow test below adds to a command so that it takes seconds: sweeps and designs
# at --quick size (replacing a result of the same path), reproduce with its run cache in
# the scratch folder instead of the repository's results/reproduce/.
SHRINK = {"sweep": ["--quick", "--overwrite"], "design": ["--quick", "--overwrite"],
          "reproduce": ["--cache", "reproduce-cache"]}


def shrunk(words: list[str]) -> list[str]:
    """The command as the slow test runs it: the page's words, plus SHRINK's."""
    extra = [w for w in SHRINK.get(words[0], []) if w not in words]
    if words[0] == "reproduce" and "--cached-only" in words:
        extra = []  # computes nothing, reads the repository's runs
    return [*words, *extra]


WITH_COMMANDS = [p for p in SOURCES if commands(page_text(p))]


def make_results() -> dict[str, list[str]]:
    """Result path -> the `softimpact sweep|design ...` words with which a make target
    writes it (`make -n QUICK=1` of the targets the pages name, expanded by make)."""
    run = subprocess.run(["make", "-n", "QUICK=1", "demo", "trajectory", "figures",
                          "continuation", "designs", "lyapunov", "chaos"], cwd=ROOT,
                         capture_output=True, text=True, check=True)
    made = {}
    for line in run.stdout.replace("\\\n", " ").splitlines():
        if not line.startswith(".venv/bin/softimpact "):
            continue
        words = shlex.split(line)
        if words[1] in ("sweep", "design") and "-o" in words:
            made[words[words.index("-o") + 1]] = words[1:]
    return made


@pytest.mark.slow
@pytest.mark.parametrize("path", WITH_COMMANDS,
                         ids=[p.relative_to(DOCS).as_posix() for p in WITH_COMMANDS])
def test_every_page_command_runs_at_quick_size(path, tmp_path, monkeypatch):
    """Each page's commands in order, the costly ones too (the test above runs only the
    cheap ones), in a scratch folder holding configs/, as SHRINK makes them small; each
    must exit 0, and info, plot and measure read what the page's commands wrote, or,
    for a result a make target writes (results/demo.h5 of `make demo`, results/fig04.h5
    of `make fig04`), what that target's own sweep writes at QUICK=1 size. Left out, and
    printed: lines with a placeholder (SCENE, RESULT.h5) or a shell variable, and lines
    reading a result nothing here writes."""
    shutil.copytree(ROOT / "configs", tmp_path / "configs")
    monkeypatch.chdir(tmp_path)
    runner, ran, left, by_make = CliRunner(), [], [], make_results()
    for line_words, line in commands(page_text(path)):
        words = without_optional(line_words)
        if not words or any("$" in w or PLACEHOLDER.match(w) for w in words):
            left.append(line)
            continue
        reads = {"info": 1, "plot": 2, "measure": 1}.get(words[0])
        if reads is not None and not (tmp_path / words[reads]).is_file():
            if words[reads] not in by_make:
                left.append(line)
                continue
            made = runner.invoke(main, shrunk(by_make[words[reads]]))
            assert made.exit_code == 0, f"{path.name}: making {words[reads]}: {made.output}"
        result = runner.invoke(main, shrunk(words))
        assert result.exit_code == 0, f"{path.name}: `{line}`: {result.output[-2000:]}"
        if ">" in line_words:
            (tmp_path / line_words[line_words.index(">") + 1]).write_text(result.output)
        ran.append(line)
    print(f"{path.name}: {len(ran)} run, {len(left)} left out: {left}")
    assert ran, f"{path.name}: none of its commands ran"
