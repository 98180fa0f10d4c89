"""Sphinx configuration of gyroshell's documentation site.

Build it with ``python -m sphinx -W -b html docs docs/_build/html`` (warnings are errors).
The gallery's example scripts in ``docs/examples`` run while the site is built; their
figures and printed output appear in the pages (sphinx-gallery).
"""

import os
import re
import sys

sys.path.insert(0, os.path.abspath(".."))
# cli_reference: the CLI parser with its help texts escaped for reStructuredText, and the
# table of each sub-command's options (cli.rst).
sys.path.insert(0, os.path.abspath("_ext"))

from sphinx_gallery.sorting import ExplicitOrder  # noqa: E402

import gyroshell  # noqa: E402

project = "gyroshell"
author = "the gyroshell developers"
copyright = "2026, the gyroshell developers"
release = gyroshell.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_parser",
    "sphinxarg.ext",
    "cli_reference",  # the gyroshell-options directive: each sub-command's options (cli.rst)
    "sphinx_gallery.gen_gallery",
    "sphinx-mathjax-offline",  # MathJax served from _static: the maths renders offline (CI)
]

# Quotes and ellipses, but "--option" stays two hyphens (no en dash) in text and titles.
smartquotes_action = "qe"

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "examples/README.txt", "**/GALLERY_HEADER.rst"]
templates_path = ["_templates"]
html_static_path = ["_static"]

# MyST: $...$ and $$...$$ maths, heading anchors for [text](page.md#anchor) links.
myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3

# The API reference: one page per public name, generated from the numpydoc docstrings.
autosummary_generate = True
# Names that differ from another only in case get their own file names, so that the pages
# also work on case-insensitive file systems (macOS, Windows).
autosummary_filename_map = {
    "gyroshell.divergence": "gyroshell.divergence-function",
    "gyroshell.modes": "gyroshell.modes-function",
    "gyroshell.linalg.qep.problem.max_count": "gyroshell.linalg.qep.problem.max_count-function",
}
# A class page documents its members, with those it inherits from gyroshell's classes (a
# result kind shows the protocol's save, to_xarray, summary, plot), not from builtins'.
autodoc_default_options = {"members": True,
                           "inherited-members": "object,BaseException,tuple,dict,Protocol"}
autodoc_member_order = "bysource"
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

# The gallery: every docs/examples/<group>/plot_*.py runs when the site is built; the groups
# (one folder per kind of physics, each with its README.txt) from the tape to the heads.
sphinx_gallery_conf = {
    "subsection_order": ExplicitOrder(["examples/eigen_stability", "examples/transients",
                                       "examples/bearing_heads"]),
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "pydata_sphinx_theme"
html_title = f"gyroshell {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
}
# Without a default mode the theme's first visit (empty localStorage) logs a console error.
html_context = {"default_mode": "auto"}


# A "|" in gyroshell's docstrings is an absolute value or a norm (|λ|, |V|, |W|), never a
# reStructuredText substitution reference: it is shown as written. Inline literals, roles
# (``a|b``, :math:`|x|`), literal blocks and doctests are left as they are.
_LITERAL = re.compile(r"(``.+?``|:\w+:`[^`]*`)")


def _escape_bars(text: str) -> str:
    parts = _LITERAL.split(text)
    parts[::2] = [re.sub(r"(?<!\\)\|", r"\\|", part) for part in parts[::2]]
    return "".join(parts)


def _absolute_values(app, what, name, obj, options, lines):
    literal_indent = None  # the indent of the paragraph that opened a literal block
    for i, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        if literal_indent is not None:
            if not line.strip() or indent > literal_indent:
                continue
            literal_indent = None
        if line.lstrip().startswith(">>>") or line.lstrip().startswith("..."):
            continue
        lines[i] = _escape_bars(line)
        if line.rstrip().endswith("::"):
            literal_indent = indent


def _skip_file_layouts(app, what, name, obj, skip, options):
    """Document ``file_layout`` on the protocol (``Result``, where it is None), not each
    kind's long value (its variables are in the kind's docstring)."""
    if name == "file_layout" and obj is not None:
        return True
    return None


def _commands_by_name(app, env):
    """Each command of the CLI reference under its name in the search index.

    sphinx-argparse records a command's description as its display name; the search index
    HTML-escapes that name and the search page escapes it again, so a result read
    ``Benson&#x27;s 111 m/s`` (with the reStructuredText escapes of :mod:`cli_reference`
    too). The name (``gyroshell critical``) is what a reader looks for.
    """
    domain = env.get_domain("commands")
    domain.data["commands"] = [(name, name, *rest)
                               for name, _description, *rest in domain.data["commands"]]
    for group, entries in domain.data["commands-by-group"].items():
        domain.data["commands-by-group"][group] = [(name, name, *rest)
                                                   for name, _description, *rest in entries]


def setup(app):
    app.connect("env-updated", _commands_by_name)
    # before numpydoc (priority 500) turns the sections into reStructuredText
    app.connect("autodoc-process-docstring", _absolute_values, priority=400)
    app.connect("autodoc-skip-member", _skip_file_layouts)
