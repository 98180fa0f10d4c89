"""Every result kind's small examples: the EXAMPLES of the ``examples_*.py`` modules here."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

HERE = Path(__file__).parent


def every_example() -> dict:
    """{kind: callable returning a small instance} over every ``examples_*.py`` module;
    a kind given twice is an error."""
    found: dict = {}
    sys.path.insert(0, str(HERE))
    try:
        for path in sorted(HERE.glob("examples_*.py")):
            module = importlib.import_module(path.stem)
            overlap = set(found) & set(module.EXAMPLES)
            assert not overlap, f"{path.name} repeats examples of {sorted(overlap)}"
            found.update(module.EXAMPLES)
    finally:
        sys.path.remove(str(HERE))
    return found
