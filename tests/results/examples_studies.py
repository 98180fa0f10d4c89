"""Small instances of the result kinds of gyroshell.studies, for the round-trip tests.

``EXAMPLES`` maps each kind to a function building one in well under a second (a tiny
grid); the registry test saves and loads each through NetCDF and compares every field.
"""

from __future__ import annotations

from collections.abc import Callable

from gyroshell import TapeModel, TapeParameters
from gyroshell.results.base import Result
from gyroshell.studies.campbell import campbell
from gyroshell.studies.parameter_study import run_study
from gyroshell.studies.sweep import sweep

#: A tape of 16 x 8 intervals: every solve takes milliseconds.
TINY = TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)
#: A critical speed (m/s) to mark, so that the diagram stores a number there.
MARKED_SPEED = 93.5


def sweep_example() -> Result:
    """Three speeds, one above critical (divergence), two modes each."""
    return sweep(TapeModel(TINY), [0.0, 60.0, 110.0], 2)


def campbell_example() -> Result:
    """Four speeds, three branches, a given critical speed."""
    return campbell(TapeModel(TINY), [0.0, 2.0, 4.0, 6.0], 3,
                    critical_speed=MARKED_SPEED)


def study_example() -> Result:
    """Two speeds; the static deflection fails above critical, reported in its row."""
    return run_study(TINY, vary={"velocity": [0.0, 110.0]}, compute=["modes", "static"],
                     count=2, workers=1)


EXAMPLES: dict[str, Callable[[], Result]] = {
    "sweep": sweep_example, "campbell": campbell_example, "study": study_example}
