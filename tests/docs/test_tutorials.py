"""Each tutorial of the site (``docs/tutorials/*.md``) runs from top to bottom, as a reader
would run it, in a fresh process and an empty folder.

The page's code blocks run in their order: a ``toml`` block with a ``:caption:`` is written
to the file the caption names, a ``bash`` block runs in ``bash -e`` (its ``gyroshell`` is
this interpreter's), and the ``python`` blocks run one after another in one namespace, as
in one notebook. Other blocks (``text``) are not run. Every command must succeed, print
something, and leave no traceback; the files the tutorial says it writes must exist.
"""

from __future__ import annotations

import json
import os
import re
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TUTORIALS = ROOT / "docs" / "tutorials"

#: A fenced block, plain (```python) or a MyST directive (```{code-block} toml) with options.
BLOCK = re.compile(r"^```(?:\{code-block\}\s*)?(\w+)[^\n]*\n((?::\w+:[^\n]*\n)*)\n?(.*?)^```\s*$",
                   re.MULTILINE | re.DOTALL)
RUN = {"bash", "python", "toml"}

#: Runs the blocks given as JSON on stdin, in order; prints a marker before each.
DRIVER = r"""
import json, subprocess, sys
blocks = json.load(sys.stdin)
namespace = {"__name__": "__main__"}
for k, (language, caption, code) in enumerate(blocks):
    print(f"=== block {k + 1}: {language}", flush=True)
    if language == "toml":
        open(caption, "w", encoding="utf-8").write(code)
    elif language == "bash":
        subprocess.run(["bash", "-e", "-o", "pipefail", "-c", code], check=True)
    else:
        exec(compile(code, f"<python block {k + 1}>", "exec"), namespace)
    sys.stdout.flush()
"""

#: Seconds a tutorial may take here before the test counts it as hung (each takes about a
#: minute or less; see each page's "Time:").
TIMEOUT = 600
#: Every tutorial runs with the slow tests (CI runs them on every push): reproducing the
#: paper runs three full-size studies (50-70 s on 2 shared cores), your own tape and the
#: flat head 7-30 s each, which would otherwise be a third of the README's test command.
SLOW = {"reproducing_the_paper", "your_own_tape", "flat_head"}
#: The files each tutorial's commands must have written.
WRITES = {
    "your_own_tape": ["mytape.toml", "campbell.csv", "campbell.png", "campbell_python.png"],
    "reproducing_the_paper": ["preview/fig2_load_point.png", "preview/fig3_wireframes.png",
                              "preview/fig4_wireframes.png", "preview/fig5_waterfall.png",
                              "preview/fig6_waterfall.png", "paper/critical_speeds.md",
                              "paper/observations.csv", "paper/period_vs_velocity.csv"],
    "flat_head": ["head.toml", "head_sketch.png", "single/summary.json", "single.png",
                  "wrap_speed.csv", "wrap_speed.png", "wrap_speed_python.png"],
}


def blocks(page: Path) -> list[tuple[str, str, str]]:
    """(language, caption, code) of the blocks of ``page`` that run, in the page's order."""
    found = []
    for language, options, code in BLOCK.findall(page.read_text(encoding="utf-8")):
        if language not in RUN:
            continue
        caption = re.search(r"^:caption:\s*(\S+)", options, re.MULTILINE)
        assert language != "toml" or caption, f"{page.name}: a toml block without :caption:"
        found.append((language, caption.group(1) if caption else "", code))
    return found


PAGES = sorted(p for p in TUTORIALS.glob("*.md") if p.stem != "index")


def test_every_tutorial_is_in_the_index_and_runs_something():
    index = (TUTORIALS / "index.md").read_text(encoding="utf-8")
    assert PAGES, "no tutorial"
    for page in PAGES:
        assert re.search(rf"^{page.stem}$", index, re.MULTILINE), f"{page.stem} not in index"
        kinds = {language for language, _, _ in blocks(page)}
        assert {"bash", "python"} <= kinds, f"{page.name}: both the shell and Python"
        assert page.stem in WRITES, f"{page.name}: say which files it writes (WRITES)"


def _run(page: Path, tmp_path: Path) -> tuple[subprocess.CompletedProcess, float]:
    bin_dir = tmp_path / ".bin"
    bin_dir.mkdir()
    shim = bin_dir / "gyroshell"  # the tutorial's `gyroshell` is this interpreter's
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m gyroshell "$@"\n')
    shim.chmod(shim.stat().st_mode | stat.S_IXUSR)
    work = tmp_path / "work"
    work.mkdir()
    env = {**os.environ, "MPLBACKEND": "Agg",
           "PATH": os.pathsep.join([str(bin_dir), os.environ.get("PATH", "")]),
           "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT),
                                                       os.environ.get("PYTHONPATH")]))}
    started = time.perf_counter()
    proc = subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", DRIVER],
                          input=json.dumps(blocks(page)), cwd=work, env=env,
                          capture_output=True, text=True, timeout=TIMEOUT)
    return proc, time.perf_counter() - started


@pytest.mark.parametrize("page", [pytest.param(p, id=p.stem, marks=[pytest.mark.slow]
                                               if p.stem in SLOW else [])
                                  for p in PAGES])
def test_the_tutorial_runs_end_to_end_in_a_fresh_process(page, tmp_path):
    proc, seconds = _run(page, tmp_path)
    last = proc.stdout.rsplit("=== block", 1)[-1][:3000]
    assert proc.returncode == 0, (f"{page.name} failed after {seconds:.0f} s in block"
                                  f"{last}\n--- stderr ---\n{proc.stderr[-3000:]}")
    assert "Traceback" not in proc.stderr, proc.stderr[-3000:]
    for k, chunk in enumerate(proc.stdout.split("=== block ")[1:]):
        assert chunk.split("\n", 1)[-1].strip() or chunk.startswith(f"{k + 1}: toml"), \
            f"{page.name}: block {k + 1} printed nothing"
    missing = [name for name in WRITES[page.stem] if not (tmp_path / "work" / name).is_file()]
    assert not missing, f"{page.name} did not write {missing}"
