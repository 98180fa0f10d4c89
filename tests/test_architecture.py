"""The form of the package: folders are layers, no import cycles, small functions, public
names only, no machine paths."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "gyroshell"
#: The longest a function may be, in lines (a screen).
MAX_FUNCTION_LINES = 60
#: Text that only an absolute path of some machine would contain.
MACHINE_PATH = re.compile(r"(?<![\w.])(/work/|/root/|/home/\w|/Users/\w|/tmp/\w|[A-Z]:\\\\)")


def _tracked(*patterns: str) -> list[Path]:
    out = subprocess.run(["git", "ls-files", *patterns], cwd=ROOT, capture_output=True,
                         text=True)
    if out.returncode != 0:
        pytest.skip("not a git checkout")
    return [ROOT / name for name in out.stdout.split()]


def test_every_layer_imports_only_from_the_layers_below():
    """The import-linter contract in pyproject.toml, checked on every run."""
    from importlinter.cli import lint_imports

    assert lint_imports(config_filename=str(ROOT / "pyproject.toml"), no_cache=True) == 0


def _import_graph() -> dict[str, set[str]]:
    import grimp

    graph = grimp.build_graph("gyroshell")
    return {m: set(graph.find_modules_directly_imported_by(m)) for m in graph.modules}


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10_000))
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_import_cycles():
    graph = _import_graph()
    # the package's __init__ exports names lazily from every layer: it is the root, not a layer
    graph = {m: {t for t in ts if t != "gyroshell"} for m, ts in graph.items()}
    assert _cycles(graph) == []


def _functions(tree: ast.AST):
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            yield node


def test_no_function_is_longer_than_a_screen():
    long = []
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in _functions(tree):
            lines = node.end_lineno - node.lineno + 1
            if lines > MAX_FUNCTION_LINES:
                long.append(f"{path.relative_to(ROOT)}:{node.lineno} {node.name} ({lines})")
    assert long == []


def test_no_absolute_machine_paths_in_the_project():
    hits = []
    for path in _tracked("*.py", "*.md", "*.toml", "*.cfg", "*.txt", ".ci/*"):
        if not path.is_file() or path == Path(__file__).resolve():
            continue
        for k, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if MACHINE_PATH.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{k}: {line.strip()[:80]}")
    assert hits == []


def test_dir_lists_the_public_names_only():
    import gyroshell

    names = dir(gyroshell)
    assert names == sorted(gyroshell.__all__)
    assert not {"sys", "importlib", "types", "annotations", "PackageNotFoundError"} & set(names)
    assert all(not n.startswith("_") for n in names)


def test_subpackages_load_on_first_attribute_access():
    # a user who wrote `import gyroshell` reaches gyroshell.plot and gyroshell.bearing
    # without importing them by name; a fresh interpreter, so no earlier import helps
    code = ("import sys, gyroshell; assert 'gyroshell.plot' not in sys.modules; "
            "f = gyroshell.plot.wireframe; b = gyroshell.bearing.BearingModel; "
            "assert 'gyroshell.plot' in sys.modules; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=False)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
