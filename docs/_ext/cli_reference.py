"""The ``gyroshell`` parser for sphinx-argparse, its texts made safe for reStructuredText.

sphinx-argparse parses every help text, description and epilog as reStructuredText, where
plain-text characters such as ``|V|`` (a substitution), ``*`` (emphasis) or a trailing ``_``
(a link) mean markup. :func:`build_parser` returns ``gyroshell.cli.build_parser()`` with those
characters escaped, so the page shows exactly the words ``gyroshell --help`` prints, and the
help strings stay plain text for the terminal.
"""

from __future__ import annotations

import argparse
import re

from gyroshell.cli import build_parser as _gyroshell_parser

#: Inline markup characters, each shown literally once preceded by a backslash.
_INLINE = re.compile(r"([\\`*_|\[\]<>])")
#: A paragraph that would open a list, a comment or a literal block in reStructuredText.
_BLOCK_START = re.compile(r"^(?=[-+*#] |\d+[.)] |\.\. |>>>)", re.MULTILINE)


def escape(text: str | None) -> str | None:
    """``text`` as reStructuredText that renders to the same characters."""
    if not text:
        return text
    text = _INLINE.sub(r"\\\1", text)
    text = _BLOCK_START.sub("\\\\", text)
    return text.replace("::", r"\:\:")


def _escape_parser(parser: argparse.ArgumentParser, done: set[int]) -> None:
    """Escape the texts of ``parser`` and its sub-parsers, each object once (the shared tape
    options are the same action objects in every sub-command: ``done`` holds their ids)."""
    for item in (parser, *parser._actions):
        if id(item) in done:
            continue
        done.add(id(item))
        if item is parser:
            parser.description = escape(parser.description)
            parser.epilog = escape(parser.epilog)
        elif item.help not in (None, argparse.SUPPRESS):
            item.help = escape(item.help)
        if isinstance(item, argparse._SubParsersAction):
            for choice in item._choices_actions:
                choice.help = escape(choice.help)
            for sub in dict.fromkeys(item.choices.values()):
                _escape_parser(sub, done)


def build_parser() -> argparse.ArgumentParser:
    """``gyroshell.cli.build_parser()`` with every text escaped for reStructuredText."""
    parser = _gyroshell_parser()
    _escape_parser(parser, set())
    return parser


def subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """``{name: parser}`` of the command's sub-commands, in ``--help``'s order."""
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(action.choices)


def option_strings(parser: argparse.ArgumentParser) -> list[str]:
    """Every option string of ``parser`` (``--help`` and ``-h`` left out), in its order."""
    return [option for action in parser._actions
            if not isinstance(action, argparse._HelpAction)
            for option in action.option_strings]


def option_table() -> str:
    """A reStructuredText list-table: each sub-command and exactly its own options."""
    rows = [".. list-table::", "   :header-rows: 1", "   :widths: 15 85", "",
            "   * - sub-command", "     - its options (each explained in its section below)"]
    for name, sub in subcommands(_gyroshell_parser()).items():
        options = ", ".join(f"``{option}``" for option in option_strings(sub))
        rows += [f"   * - ``{name}``", f"     - {options or '(none)'}"]
    return "\n".join(rows) + "\n"


def setup(app):
    """The ``gyroshell-options`` directive: :func:`option_table`, from the parser itself."""
    from docutils import nodes
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective

    class OptionTable(SphinxDirective):
        has_content = False

        def run(self):
            container = nodes.container()
            self.state.nested_parse(StringList(option_table().splitlines(), "cli_reference"),
                                    self.content_offset, container)
            return container.children

    app.add_directive("gyroshell-options", OptionTable)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
