"""Every jitted function stays small: the kernels are built from helpers, not copied loops.

Scans the package's sources: a function decorated with numba's ``njit`` takes at most
MAX_ARGS arguments (long lists go in bundles: surfaces, state, samples, known orbits,
cells), spans at most MAX_LINES lines (docstring included) and returns at most
MAX_RETURNED plain values (more go in a named tuple).
"""

from __future__ import annotations

import ast
from pathlib import Path

import softimpact_cli

PACKAGE = Path(softimpact_cli.__file__).parent
MAX_ARGS = 10
MAX_LINES = 64
MAX_RETURNED = 4


def jitted_functions():
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef) and any(
                    "jit" in ast.unparse(d) for d in node.decorator_list):
                yield f"{path.relative_to(PACKAGE)}:{node.lineno} {node.name}", node


def test_the_scan_finds_the_kernels():
    names = {name.split()[-1] for name, _ in jitted_functions()}
    assert {"advance", "redo", "classify_near", "rodas_step", "pair_rhs"} <= names


def test_no_jitted_function_takes_a_long_argument_list():
    long = [(name, len(f.args.args)) for name, f in jitted_functions()
            if len(f.args.args) > MAX_ARGS]
    assert not long, long


def test_no_jitted_function_is_long():
    long = [(name, f.end_lineno - f.lineno + 1) for name, f in jitted_functions()
            if f.end_lineno - f.lineno + 1 > MAX_LINES]
    assert not long, long


def test_no_jitted_function_returns_a_long_tuple():
    wide = [(name, len(r.value.elts)) for name, f in jitted_functions() for r in ast.walk(f)
            if isinstance(r, ast.Return) and isinstance(r.value, ast.Tuple)
            and len(r.value.elts) > MAX_RETURNED]
    assert not wide, wide
