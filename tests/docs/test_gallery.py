"""The gallery's example scripts (docs/examples/<group>/plot_*.py, one folder per kind of
physics) are well-formed sphinx-gallery files, and each runs as a user would run it: in a
fresh process, the Agg back-end, an empty working folder, and draws its figures."""

from __future__ import annotations

import ast
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"
#: Every example, in the order of its number (the folders group them by physics).
SCRIPTS = sorted(EXAMPLES.glob("*/plot_*.py"), key=lambda path: path.name)
#: How each script says where its full-size case is: a sentence starting "Full-size:".
FULL_SIZE = re.compile(r"^#\s*Full-size:", re.MULTILINE)
#: Seconds one quick example may take in a subprocess before it counts as hung (they take
#: seconds; this is only a guard against a hang on a loaded machine).
TIMEOUT = 600

#: Runs a script as ``__main__`` (as sphinx-gallery does), then writes each open figure to
#: the working folder and prints, as JSON, how many data artists (lines, collections,
#: images, patches) each figure's Axes hold; an empty Axes holds none.
DRIVER = """
import json, runpy, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
runpy.run_path(sys.argv[1], run_name="__main__")
drawn = []
for number in plt.get_fignums():
    fig = plt.figure(number)
    fig.savefig(f"figure_{number}.png", dpi=40)
    drawn.append([len(ax.lines) + len(ax.collections) + len(ax.images) + len(ax.patches)
                  for ax in fig.axes])
print("FIGURES " + json.dumps(drawn))
"""


def _ids(path: Path) -> str:
    return path.stem


def test_the_gallery_has_its_examples_in_order():
    numbers = [re.match(r"plot_(\d+)_", path.name) for path in SCRIPTS]
    assert SCRIPTS and all(numbers), "examples are named plot_<NN>_<topic>.py"
    assert len({m.group(1) for m in numbers}) == len(SCRIPTS), "each number once"
    assert (EXAMPLES / "README.txt").is_file(), "sphinx-gallery needs the gallery header"
    assert not list(EXAMPLES.glob("plot_*.py")), "each example sits in its physics' folder"
    for group in {path.parent for path in SCRIPTS}:
        assert (group / "README.txt").is_file(), f"{group.name}/ needs its section header"


@pytest.mark.parametrize("script", SCRIPTS, ids=_ids)
def test_example_has_a_title_prose_cells_and_its_full_size_case(script):
    source = script.read_text(encoding="utf-8")
    tree = ast.parse(source, filename=str(script))  # a syntax error fails here, quickly
    doc = ast.get_docstring(tree, clean=False) or ""
    lines = doc.strip("\n").splitlines()
    assert len(lines) >= 3, f"{script.name}: a docstring with a title and text"
    title, underline = lines[0], lines[1]
    assert title.strip() and set(underline) == {"="} and len(underline) >= len(title), \
        f"{script.name}: the docstring opens with a title underlined by '='"
    assert " ".join(lines[2:]).strip(), f"{script.name}: text under the title"
    assert source.count("\n# %%") >= 2, f"{script.name}: '# %%' cells with prose"
    assert FULL_SIZE.search(source), f"{script.name}: a '# Full-size: ...' sentence"
    assert "\nplt.show()" in source, f"{script.name}: plt.show(), so a script shows its figures"
    assert "import gyroshell" in source or "from gyroshell" in source


@pytest.mark.slow
@pytest.mark.parametrize("script", SCRIPTS, ids=_ids)
def test_example_runs_and_draws_its_figures(script, tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT),
                                                       os.environ.get("PYTHONPATH")]))}
    proc = subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", DRIVER,
                           str(script)], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=TIMEOUT)
    assert proc.returncode == 0, f"{script.name} failed:\n{proc.stderr[-3000:]}"
    assert proc.stderr == "", f"{script.name} wrote to stderr:\n{proc.stderr[-3000:]}"
    report = [line for line in proc.stdout.splitlines() if line.startswith("FIGURES ")]
    figures = json.loads(report[-1].removeprefix("FIGURES "))
    printed = proc.stdout[:proc.stdout.rindex("FIGURES ")]
    assert printed.strip(), f"{script.name} prints some numbers"
    assert figures, f"{script.name} made no figure"
    for k, axes in enumerate(figures):
        assert axes and max(axes) > 0, f"{script.name}: figure {k + 1} has nothing drawn"
    pngs = sorted(tmp_path.glob("figure_*.png"))
    assert len(pngs) == len(figures) and all(p.stat().st_size > 0 for p in pngs)
    assert {p.name for p in tmp_path.iterdir()} == {p.name for p in pngs}, \
        f"{script.name} left files in its working folder"
