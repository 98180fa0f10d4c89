"""The API and CLI references cover the code, so that they cannot drift from it.

The API reference (``docs/api/*.rst``) lists its entries in ``autosummary`` blocks under a
``currentmodule``; from those sources alone (no Sphinx) every entry must name a real object,
and every public name must have an entry: each name of ``gyroshell.__all__`` as
``gyroshell.NAME``, each name of every other ``__all__`` of the package and each entry point
of the modules that declare none (:data:`WITHOUT_ALL`) as the same object under the same
name. The CLI reference (``docs/cli.rst``) must have one section per sub-command, and the
texts it renders must read exactly as ``--help`` prints them.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import inspect
import io
import pkgutil
import re
from pathlib import Path

import pytest

import gyroshell
from gyroshell.cli import build_parser

DOCS = Path(__file__).resolve().parents[2] / "docs"

#: The public names of modules that declare no ``__all__``: the entry points a user meets
#: (the errors, the unit table, saving and loading, the linear solvers, tape files, the
#: branch tracker and the signal analysis of the studies).
WITHOUT_ALL: dict[str, tuple[str, ...]] = {
    "gyroshell.core.errors": ("InputFileError", "MissingFileError", "SingularError"),
    "gyroshell.core.units": ("SI_UNITS", "ACCEPTED", "unit_of", "axis_label"),
    "gyroshell.kinds": ("load", "save", "load_table", "import_kinds", "KIND_MODULES"),
    "gyroshell.results.base": ("Result", "kinds", "read", "from_dataset"),
    "gyroshell.results.tables": ("Table",),
    "gyroshell.tape.config": ("TapeConfig", "load_config", "write_config", "config_text"),
    "gyroshell.linalg.factorization": ("Factorization", "splu", "use_factorization",
                                       "factorize", "available_backends", "ORDERING"),
    "gyroshell.linalg.cholesky": ("available", "cholesky", "ldl", "negative_count",
                                  "CholeskyFactor", "LDLFactor"),
    "gyroshell.engines.newmark": ("sharing_factorizations",),
    "gyroshell.studies.branches": ("BranchTracker", "Match", "track"),
    "gyroshell.studies.signal": ("amplitude_spectrum", "dominant_period",
                                 "dominant_wavelength", "front_position", "first_departure"),
}
#: Packages whose ``__all__`` are not the Python API: the CLI's interface is the command,
#: documented by ``docs/cli.rst``.
NOT_API = ("gyroshell.cli",)


def resolve(name: str):
    """The object a dotted name stands for: the longest importable module, then attributes."""
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            value = importlib.import_module(".".join(parts[:cut]))
        except ModuleNotFoundError:
            continue
        for attr in parts[cut:]:
            value = getattr(value, attr)
        return value
    raise ModuleNotFoundError(name)


def reference_entries() -> list[tuple[str, str]]:
    """(source file, full name) of every autosummary entry of the API reference's sources."""
    entries = []
    for path in sorted((DOCS / "api").glob("*.rst")):
        module, in_block = None, False
        for line in path.read_text(encoding="utf-8").splitlines():
            current = re.match(r"\.\. currentmodule:: (\S+)", line)
            if current:
                module, in_block = current.group(1), False
            elif line.startswith(".. autosummary::"):
                in_block = True
            elif in_block and line.strip() and not line.startswith(" "):
                in_block = False
            elif in_block and line.strip() and not line.strip().startswith(":"):
                entry = line.strip().lstrip("~")
                entries.append((path.name, entry if module is None else f"{module}.{entry}"))
    return entries


ENTRIES = reference_entries()


def documented() -> set[tuple[str, int]]:
    """(name, object id) of every entry: an object counts as documented under its name."""
    return {(full.rsplit(".", 1)[-1], id(resolve(full))) for _, full in ENTRIES}


def public_names() -> dict[str, tuple[str, ...]]:
    """Module -> its public names: its ``__all__``, or its entries of :data:`WITHOUT_ALL`."""
    public = {"gyroshell": tuple(gyroshell.__all__)}
    for info in pkgutil.walk_packages(gyroshell.__path__, "gyroshell."):
        name = info.name
        if name.endswith("__main__") or name.startswith(NOT_API):
            continue
        module = importlib.import_module(name)
        if hasattr(module, "__all__"):
            assert name not in WITHOUT_ALL, f"{name} has an __all__ now: drop it from WITHOUT_ALL"
            public[name] = tuple(module.__all__)
    return public | WITHOUT_ALL


def test_the_reference_has_entries_in_every_page_of_its_index():
    pages = re.findall(r"^   (\w+)$", (DOCS / "api" / "index.rst").read_text(encoding="utf-8"),
                       re.MULTILINE)
    assert sorted(pages) == sorted(p.stem for p in (DOCS / "api").glob("*.rst")
                                   if p.stem != "index")
    assert {source for source, _ in ENTRIES} == {f"{page}.rst" for page in pages}


def test_every_entry_names_a_real_object_once():
    names = [full for _, full in ENTRIES]
    for full in names:
        resolve(full)  # raises for a name that is not (or no longer) in the code
    assert len(names) == len(set(names)), "an entry is listed twice"
    routines = [full for full in names if inspect.isclass(resolve(full))
                or inspect.isfunction(resolve(full))]
    objects = [id(resolve(full)) for full in routines]
    twice = sorted(full for full in routines if objects.count(id(resolve(full))) > 1)
    assert not twice, f"the same class or function documented under two names: {twice}"


def test_the_gyroshell_namespace_is_documented_as_gyroshell_names():
    names = {full for _, full in ENTRIES}
    missing = [name for name in gyroshell.__all__ if f"gyroshell.{name}" not in names]
    assert not missing, f"gyroshell.__all__ names without an entry: {missing}"


@pytest.mark.parametrize("module", sorted(public_names()))
def test_every_public_name_has_an_entry(module):
    have = documented()
    values = {name: getattr(importlib.import_module(module), name)
              for name in public_names()[module]}
    missing = [name for name, value in values.items() if (name, id(value)) not in have]
    assert not missing, f"{module}: public names without an entry in docs/api: {missing}"


def subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(action.choices)


def test_the_cli_reference_has_one_section_per_subcommand():
    text = (DOCS / "cli.rst").read_text(encoding="utf-8")
    paths = re.findall(r"^   :path: (\S+)$", text, re.MULTILINE)
    assert paths == list(subcommands(build_parser()))  # each once, in --help's order
    for name in paths:
        assert re.search(rf"^gyroshell {name}: .+\n-+\n", text, re.MULTILINE), name


def help_texts() -> list[str]:
    """Every description, epilog and help text of the command and its sub-commands."""
    top = build_parser()
    texts = []
    for parser in (top, *subcommands(top).values()):
        texts += [parser.description or "", parser.epilog or ""]
        texts += [a.help for a in parser._actions if a.help and a.help != argparse.SUPPRESS]
    return [t for t in dict.fromkeys(texts) if t]


def test_the_cli_page_renders_the_help_texts_as_written():
    core = pytest.importorskip("docutils.core")
    spec = importlib.util.spec_from_file_location("cli_reference",
                                                  DOCS / "_ext" / "cli_reference.py")
    cli_reference = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cli_reference)

    def rendered(text: str) -> tuple[str, list]:
        tree = core.publish_doctree(text, settings_overrides={
            "report_level": 2, "halt_level": 5, "warning_stream": io.StringIO()})
        problems = [*tree.parse_messages, *tree.transform_messages,
                    *(n for n in tree.findall() if n.tagname in ("system_message",
                                                                 "problematic"))]
        return tree.astext(), problems

    texts = help_texts()
    # plain text that reStructuredText reads as markup (an undefined substitution), which
    # the escaping shows as written (today's help texts need none of it, tomorrow's may)
    sample = "tape speed V, |V| below, *not emphasis*, not_a_link_"
    assert rendered(sample)[1]
    assert rendered(cli_reference.escape(sample)) == (sample, [])
    # one document, one paragraph per text (each its own block, as on the page)
    shown, problems = rendered("\n\n".join(cli_reference.escape(t) for t in texts))
    assert not problems, [p.astext() for p in problems]
    assert shown.split() == "\n\n".join(texts).split()
