"""The CLI reference lists, for each sub-command, exactly the options of its own parser.

``docs/cli.rst`` is built alone (a small Sphinx project in a temporary folder, with the
site's ``cli_reference`` extension and sphinx-argparse, warnings as errors: a few seconds),
and the rendered page is read back: each sub-command's section (sphinx-argparse, one
``<kbd>`` per option) and its row of the page's option table must name exactly the option
strings of ``gyroshell COMMAND``'s parser (``-h``/``--help`` aside), and the page's prose
must not say that every command takes an option some do not.
"""

from __future__ import annotations

import html
import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from gyroshell.cli import build_parser

DOCS = Path(__file__).resolve().parents[2] / "docs"

CONF = """
import sys
sys.path.insert(0, {ext!r})
extensions = ["sphinxarg.ext", "cli_reference"]
smartquotes_action = "qe"
root_doc = "index"
"""


def _reference_module():
    spec = importlib.util.spec_from_file_location("cli_reference",
                                                  DOCS / "_ext" / "cli_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _parser_options() -> dict[str, set[str]]:
    reference = _reference_module()
    return {name: set(reference.option_strings(sub))
            for name, sub in reference.subcommands(build_parser()).items()}


def _text(fragment: str) -> str:
    return html.unescape(re.sub(r"<[^>]+>", "", fragment)).strip()


@pytest.fixture(scope="module")
def cli_page(tmp_path_factory) -> str:
    """The HTML of ``docs/cli.rst`` built alone with ``-W``."""
    for module in ("sphinx", "sphinxarg"):
        if importlib.util.find_spec(module) is None:
            pytest.skip(f"{module} is not installed (pip install -e \".[docs]\")")
    src = tmp_path_factory.mktemp("cli_src")
    out = tmp_path_factory.mktemp("cli_html")
    shutil.copy(DOCS / "cli.rst", src / "index.rst")
    (src / "conf.py").write_text(CONF.format(ext=str(DOCS / "_ext")), encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "-q", "-b", "html",
                           str(src), str(out)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, f"cli.rst alone did not build:\n{proc.stderr[-3000:]}"
    return (out / "index.html").read_text(encoding="utf-8")


def test_each_section_lists_exactly_its_parsers_options(cli_page):
    expected = _parser_options()
    sections = {}
    for chunk in re.split(r"<h2>", cli_page)[1:]:
        title = _text(chunk[:chunk.index("</h2>")])
        match = re.match(r"gyroshell (\w+):", title)
        if match:
            shown = set()
            for kbd in re.findall(r"<kbd>(.*?)</kbd>", chunk):
                shown |= {s for s in _text(kbd).split(", ") if s.startswith("-")}
            sections[match.group(1)] = shown
    assert sections.keys() == expected.keys()
    wrong = {name: {"listed, not taken": sorted(sections[name] - options),
                    "taken, not listed": sorted(options - sections[name])}
             for name, options in expected.items() if sections[name] != options}
    assert not wrong, wrong


def test_the_option_table_lists_exactly_each_parsers_options(cli_page):
    expected = _parser_options()
    table = cli_page[cli_page.index("<table"):cli_page.index("</table>")]
    rows = {}
    for row in re.findall(r"<tr[^>]*>(.*?)</tr>", table, re.DOTALL)[1:]:
        name_cell, options_cell = re.findall(r"<td[^>]*>(.*?)</td>", row, re.DOTALL)
        rows[_text(name_cell)] = {_text(code) for code in
                                  re.findall(r"<code[^>]*>(.*?)</code>", options_cell)}
    assert rows == expected


def test_no_prose_claims_every_command_takes_an_option():
    text = (DOCS / "cli.rst").read_text(encoding="utf-8")
    options = _parser_options()
    for sentence in re.split(r"(?<=[.:])\s", text):
        if re.search(r"\b(every|each|all) (sub-)?commands?\b", sentence, re.IGNORECASE):
            claimed = set(re.findall(r"``(--[\w-]+)", sentence))
            lacking = {name: sorted(claimed - taken) for name, taken in options.items()
                       if claimed - taken}
            assert not lacking, f"{sentence!r}: not taken by {lacking}"
