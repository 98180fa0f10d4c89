"""Critical-speed table: this model (free and simply supported edges, L_x/L_y = 4 and 19)
beside the string value, the infinite-strip value and the values the paper quotes.

For the models computed here, ``critical_speed`` is where the lowest gyroscopic frequency
crosses zero (eigen-solver + root-finding) and ``divergence_speed`` is √((T + μ_min)/ρ)
from one symmetric eigen-solve; the two must agree.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pandas as pd

from ..engines.critical import PAPER_SPEED, SUNDARAM_BENSON_SPEED, critical_speeds
from ..tape.model import TapeModel
from ._common import Settings, save_csv, save_markdown
from ._runner import run_parts

CASES = (("free", 4.0), ("free", 19.0), ("simply-supported", 4.0), ("simply-supported", 19.0))


def parts(settings: Settings) -> tuple[tuple[str, float], ...]:
    """The independent parts: one per computed model (edges, L_x/L_y)."""
    return CASES


def compute_part(settings: Settings, case: tuple[str, float]) -> dict:
    """The table row of one model: its critical and divergence speeds, m/s."""
    edges, ratio = case
    params = settings.params(length_ratio=ratio, edges=edges)
    c = critical_speeds(TapeModel(params))
    return dict(model=f"this model, {edges} edges, L_x/L_y = {ratio:g}",
                critical_speed=c.critical_speed, divergence_speed=c.divergence_speed,
                source="gyroscopic eigenvalue crosses zero; divergence eigsh")


def compute(settings: Settings) -> pd.DataFrame:
    return combine(settings, [compute_part(settings, case) for case in parts(settings)])


def combine(settings: Settings, rows: list[dict]) -> pd.DataFrame:
    """The computed rows, then the closed forms and the quoted values."""
    p = settings.params()
    nan = math.nan
    rows = list(rows) + [
        dict(model="moving string/beam, sqrt(T/rho) (Wickert & Mote 1990)",
             critical_speed=p.string_speed, divergence_speed=nan, source="closed form"),
        dict(model="infinite strip on foundation, sqrt((T + 2 sqrt(D k))/rho)",
             critical_speed=p.strip_critical_speed, divergence_speed=nan,
             source="closed form"),
        dict(model="Sundaram & Benson (1989), all sides simply supported, quoted",
             critical_speed=SUNDARAM_BENSON_SPEED, divergence_speed=nan,
             source="quoted by the paper"),
        dict(model="Mueftue & Benson (the paper), 'just above 100 m/s'",
             critical_speed=PAPER_SPEED, divergence_speed=nan, source="the paper's Fig. 2"),
    ]
    return pd.DataFrame(rows)


def write(out: Path, settings: Settings, results: list[dict]) -> list[Path]:
    table = combine(settings, results)
    return [save_csv(table, out / "critical_speeds.csv"),
            save_markdown(table, out / "critical_speeds.md",
                          "# Critical tape speeds (m/s), Table 1 parameters")]


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
