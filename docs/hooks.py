"""MkDocs hooks: the pages generated at build time, so that none of them can drift.

- ``reference/scene-keys.md``: the scene-key reference, from the scene reader's own schema
  (``softimpact_cli.kinds.key_reference``).
- ``reference/commands.md``: every command's ``--help``, from the click commands.
- ``howto/reproduce-table.md``: the committed reproduction table (results/reproduce.md).
- ``tutorials/<name>.md``: each tutorial, a jupytext percent-format script
  (``docs/tutorials/<name>.py``), executed cell by cell in a scratch folder holding a copy
  of configs/ (so paths work as from the repository root and nothing is written into the
  checkout); its printed output and figures are shown under each cell. A cell that raises
  fails the build. ``SOFTIMPACT_DOCS_EXECUTE=0`` renders the code without running it
  (for editing prose only; the tests never set it).
"""

from __future__ import annotations

import ast
import contextlib
import io
import os
import shutil
import tempfile
import time
from pathlib import Path

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parents[1]
TUTORIALS = ROOT / "docs" / "tutorials"


# ---------------------------------------------------------------- tutorials


def percent_cells(text: str) -> list[tuple[str, str]]:
    """The cells of a jupytext percent-format script: ("markdown" | "code", source)."""
    cells: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        if line.startswith("# %%"):
            cells.append(("markdown" if "[markdown]" in line else "code", []))
        elif cells:
            cells[-1][1].append(line)
    out = []
    for kind, lines in cells:
        if kind == "markdown":
            lines = [ln[2:] if ln.startswith("# ") else ln.lstrip("#") for ln in lines]
        source = "\n".join(lines).strip("\n")
        if source:
            out.append((kind, source))
    return out


def _run_cell(source: str, namespace: dict, name: str) -> tuple[str, list]:
    """Execute one code cell; return what it printed (and its last expression's repr, as
    a notebook shows it) and the figures it made: pyplot's and the matplotlib Figures
    bound to names (softimpact's figure functions return Figures pyplot does not know)."""
    from matplotlib.figure import Figure

    before = {id(v) for v in namespace.values() if isinstance(v, Figure)}
    tree = ast.parse(source, filename=name)
    last = None
    if tree.body and isinstance(tree.body[-1], ast.Expr):
        last = ast.Expression(tree.body.pop().value)
    buffer = io.StringIO()
    value = None
    with contextlib.redirect_stdout(buffer):
        exec(compile(tree, name, "exec"), namespace)
        if last is not None:
            value = eval(compile(last, name, "eval"), namespace)
            if value is not None and not isinstance(value, Figure):
                print(repr(value))
    figures = [v for v in namespace.values() if isinstance(v, Figure) and id(v) not in before]
    if isinstance(value, Figure) and value not in figures:
        figures.append(value)
    return buffer.getvalue(), figures


def render_tutorial(path: Path, config, files, execute: bool) -> str:
    """The tutorial's page: its markdown cells, its code, and (executed) each cell's
    output and figures (added to ``files`` as tutorials/<stem>-<n>.png)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    parts = [f"<!-- generated from docs/tutorials/{path.name} by docs/hooks.py -->\n"]
    namespace = {"__name__": "__main__"}
    cwd = os.getcwd()
    scratch = Path(tempfile.mkdtemp(prefix=f"softimpact-tutorial-{path.stem}-"))
    shutil.copytree(ROOT / "configs", scratch / "configs")
    started = time.perf_counter()
    figure = 0
    try:
        os.chdir(scratch)
        for index, (kind, source) in enumerate(percent_cells(path.read_text())):
            if kind == "markdown":
                parts.append(source + "\n")
                continue
            parts.append(f"```python\n{source}\n```\n")
            if not execute:
                continue
            try:
                printed, figures = _run_cell(source, namespace, f"{path.name} cell {index}")
            except Exception as exc:  # the build fails, naming the cell
                raise PluginError(f"docs/tutorials/{path.name}, cell {index}: "
                                  f"{type(exc).__name__}: {exc}") from exc
            if printed.strip():
                parts.append(f"```text\n{printed.rstrip()}\n```\n")
            figures += [plt.figure(n) for n in plt.get_fignums() if plt.figure(n) not in figures]
            for shown in figures:
                figure += 1
                png = io.BytesIO()
                shown.savefig(png, format="png", dpi=80, bbox_inches="tight")
                name = f"tutorials/{path.stem}-{figure}.png"
                files.append(File.generated(config, name, content=png.getvalue()))
                parts.append(f"![figure {figure} of this tutorial]({path.stem}-{figure}.png)\n")
            plt.close("all")
    finally:
        os.chdir(cwd)
        shutil.rmtree(scratch, ignore_errors=True)
    if execute:
        parts.append(f"<small>Executed when the site was built "
                     f"({time.perf_counter() - started:.1f} s).</small>\n")
    return "\n".join(parts)


# ---------------------------------------------------------------- commands


def commands_page() -> str:
    """Every command's ``--help`` text, from the click commands themselves."""
    import click

    from softimpact_cli.cli import main

    lines = ["# Commands", "",
             "Every `softimpact` command's `--help`, generated from the commands when the "
             "site is built. Call it as `.venv/bin/softimpact` (or activate the "
             "environment once: `source .venv/bin/activate`).", ""]

    def walk(command: click.Command, path: list[str]) -> None:
        ctx = click.Context(command, info_name=" ".join(path))
        lines.extend([f"## {' '.join(path)}", "", "```text", command.get_help(ctx), "```", ""])
        if isinstance(command, click.Group):
            for name in command.list_commands(ctx):
                walk(command.get_command(ctx, name), [*path, name])

    walk(main, ["softimpact"])
    return "\n".join(lines)


# ---------------------------------------------------------------- the hook


def on_files(files, config):
    from softimpact_cli.kinds.key_reference import scene_key_reference

    execute = os.environ.get("SOFTIMPACT_DOCS_EXECUTE", "1") != "0"
    generated = {
        "reference/scene-keys.md": scene_key_reference(),
        "reference/commands.md": commands_page(),
        "howto/reproduce-table.md": (ROOT / "results" / "reproduce.md").read_text(),
    }
    for path in sorted(TUTORIALS.glob("*.py")):
        generated[f"tutorials/{path.stem}.md"] = render_tutorial(path, config, files, execute)
    for uri, content in generated.items():
        files.append(File.generated(config, uri, content=content))
    return files
