"""Fig. 4: 3-D wire frames of the tape after a step load, V = 50 m/s, L_x/L_y = 4."""

from __future__ import annotations

from pathlib import Path

from ._common import Settings
from ._wireframes import run_figure

VELOCITY = 50.0


def run(out: Path, settings: Settings) -> list[Path]:
    return run_figure(out, settings, "fig4", VELOCITY)
