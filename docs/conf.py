"""Sphinx configuration of gyroshell's documentation site.

Build it with ``python -m sphinx -W -b html docs docs/_build/html`` (warnings are errors).
The gallery's example scripts in ``docs/examples`` run while the site is built; their
figures and printed output appear in the pages (sphinx-gallery).
"""

import os
import sys

sys.path.insert(0, os.path.abspath(".."))

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
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinxarg.ext",
    "sphinx_gallery.gen_gallery",
]

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
autodoc_default_options = {"members": True, "inherited-members": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

# The gallery: every docs/examples/plot_*.py runs when the site is built.
sphinx_gallery_conf = {
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
