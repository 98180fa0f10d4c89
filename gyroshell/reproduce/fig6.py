"""Fig. 6: centre-line wave action after a step load, V = 100 m/s, L_x/L_y = 19."""

from __future__ import annotations

from pathlib import Path

from ._common import Settings
from ._waterfall import run_figure

VELOCITY = 100.0


def run(out: Path, settings: Settings) -> list[Path]:
    return run_figure(out, settings, "fig6", VELOCITY)
