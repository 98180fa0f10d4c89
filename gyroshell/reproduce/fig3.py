"""Fig. 3: 3-D wire frames of the tape after a step load, V = 0 m/s, L_x/L_y = 4."""

from __future__ import annotations

from pathlib import Path

from ._common import Settings
from ._wireframes import run_figure

VELOCITY = 0.0


def run(out: Path, settings: Settings) -> list[Path]:
    return run_figure(out, settings, "fig3", VELOCITY)
