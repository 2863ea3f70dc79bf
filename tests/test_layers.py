"""The layering of the package (ARCHITECTURE.md): imports go one way, bottom to top.

The graph is built from every import statement of ``softimpact_cli`` (at module level and
inside functions, read with ``ast``) and from the ``"softimpact_cli.module:function"``
strings a registry uses to name a function it imports when called: a package may name
only packages of its own layer's rank or below, so there is no cycle between packages.
Imports inside functions hide the order they break; at most ``MAX_LOCAL_IMPORTS``
remain, each beside a comment saying why (an optional or heavy dependency imported only
when used, never a cycle).
"""

from __future__ import annotations

import ast
import re
from collections import defaultdict
from pathlib import Path

import softimpact_cli

ROOT = Path(softimpact_cli.__file__).parent

# bottom to top; a package imports only packages of a lower rank (or its own package).
# "(root)" is the modules at the top of the package: api.py, cli.py, __init__.py (the
# command line runs the reproduction, hence reproduce below it)
LAYERS = (
    ("kernels",),
    ("systems",),
    ("config",),
    ("analysis",),
    ("store",),
    ("sweep",),
    ("report",),
    ("plot",),
    ("kinds",),
    ("reproduce",),
    ("(root)",),
)
RANK = {package: rank for rank, layer in enumerate(LAYERS) for package in layer}
MAX_LOCAL_IMPORTS = 30
HOOK = re.compile(r"^softimpact_cli\.([A-Za-z_]\w*)(?:\.[\w.]+)?:\w+$")


def _package(parts: tuple[str, ...]) -> str:
    return parts[0] if len(parts) > 1 else "(root)"


def _targets(node: ast.AST, parts: tuple[str, ...]) -> list[str]:
    """The top-level packages of softimpact_cli an import statement names."""
    if isinstance(node, ast.ImportFrom):
        if node.level:
            base = list(parts[:-1])[: len(parts) - node.level]
            module = base + (node.module.split(".") if node.module else [])
            if module:
                return [module[0]]
            return [alias.name for alias in node.names]  # from . import x (at the top)
        if node.module and node.module.split(".")[0] == "softimpact_cli":
            rest = node.module.split(".")[1:]
            return [rest[0]] if rest else [alias.name for alias in node.names]
        return []
    if isinstance(node, ast.Import):
        return [alias.name.split(".")[1] for alias in node.names
                if alias.name.startswith("softimpact_cli.")]
    return []


def import_graph(root: Path = ROOT):
    """(edges {(from, to): [where]}, local imports [where]) of the package at ``root``."""
    packages = {p.name for p in root.iterdir() if (p / "__init__.py").is_file()}
    edges: dict[tuple[str, str], list[str]] = defaultdict(list)
    local: list[str] = []
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).parts
        source = _package(parts)
        tree = ast.parse(path.read_text())
        in_function = {id(node) for fn in ast.walk(tree)
                       if isinstance(fn, ast.FunctionDef | ast.AsyncFunctionDef)
                       for node in ast.walk(fn)}
        for node in ast.walk(tree):
            where = f"{'/'.join(parts)}:{getattr(node, 'lineno', 0)}"
            if isinstance(node, ast.Import | ast.ImportFrom):
                targets = [t for t in _targets(node, parts) if t in packages]
                if (targets or _internal(node)) and id(node) in in_function:
                    local.append(where)
            elif isinstance(node, ast.Constant) and isinstance(node.value, str):
                hook = HOOK.match(node.value)
                targets = [hook.group(1)] if hook and hook.group(1) in packages else []
            else:
                continue
            for target in targets:
                if target != source:
                    edges[(source, target)].append(where)
    return edges, local


def _internal(node) -> bool:
    return isinstance(node, ast.ImportFrom) and (node.level > 0 or (node.module or "")
                                                 .startswith("softimpact_cli"))


def cycles(edges) -> list[list[str]]:
    """The strongly connected groups of more than one package (Tarjan)."""
    graph = defaultdict(set)
    for a, b in edges:
        graph[a].add(b)
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                found.append(sorted(group))

    for v in list(graph):
        if v not in index:
            visit(v)
    return found


def test_every_package_has_a_layer():
    packages = {p.name for p in ROOT.iterdir() if (p / "__init__.py").is_file()}
    assert packages | {"(root)"} == set(RANK)


def test_no_cycle_between_packages():
    edges, _ = import_graph()
    assert cycles(edges) == []


def test_imports_go_down_the_layers_only():
    edges, _ = import_graph()
    upward = {f"{a} -> {b}": where[:3] for (a, b), where in edges.items()
              if RANK[b] >= RANK[a] and (RANK[b] > RANK[a] or a != b)}
    assert upward == {}, "imports against ARCHITECTURE.md's order"


def test_few_imports_inside_functions_each_with_its_reason():
    _, local = import_graph()
    assert len(local) <= MAX_LOCAL_IMPORTS, "\n".join(local)
    unexplained = []
    for where in local:
        path, line = where.rsplit(":", 1)
        lines = (ROOT / path).read_text().splitlines()
        before = lines[max(0, int(line) - 4):int(line)]
        if not any("#" in text for text in before):
            unexplained.append(where)
    assert unexplained == [], "a deferred import needs a comment saying why"


def test_the_check_finds_a_cycle_and_an_upward_import(tmp_path):
    """The graph is read from the files: a lower layer naming a higher one fails."""
    package = tmp_path / "softimpact_cli"
    for name in ("config", "kinds"):
        (package / name).mkdir(parents=True)
        (package / name / "__init__.py").write_text("")
    (package / "config" / "scene.py").write_text(
        "def read():\n    from ..kinds import KINDS  # the registry\n    return KINDS\n")
    (package / "kinds" / "base.py").write_text("from ..config.scene import read\n"
                                               "DRAW = 'softimpact_cli.config.scene:read'\n")
    edges, local = import_graph(package)
    assert set(edges) == {("config", "kinds"), ("kinds", "config")}
    assert cycles(edges) == [["config", "kinds"]]
    assert local == ["config/scene.py:2"]
