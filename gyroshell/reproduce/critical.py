"""Critical-speed table: this model (free and simply supported edges, L_x/L_y = 4 and 19)
beside the string value, the infinite-strip value and the values the paper quotes.

For the models computed here, ``critical_speed`` is where the lowest gyroscopic frequency
crosses zero (eigen-solver + root-finding) and ``divergence_speed`` is √((T + μ_min)/ρ)
from one symmetric eigen-solve; the two must agree.
"""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from ..engines.critical import PAPER_SPEED, SUNDARAM_BENSON_SPEED, critical_speeds
from ..tape.model import TapeModel
from ._common import Settings, save_csv, save_markdown

CASES = (("free", 4.0), ("free", 19.0), ("simply-supported", 4.0), ("simply-supported", 19.0))


def compute(settings: Settings) -> pd.DataFrame:
    rows = []
    for edges, ratio in CASES:
        params = settings.params(length_ratio=ratio, edges=edges)
        c = critical_speeds(TapeModel(params))
        rows.append(dict(model=f"this model, {edges} edges, L_x/L_y = {ratio:g}",
                         critical_speed=c.critical_speed, divergence_speed=c.divergence_speed,
                         source="gyroscopic eigenvalue crosses zero; divergence eigsh"))
    p = settings.params()
    nan = math.nan
    rows += [
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


def run(out: Path, settings: Settings) -> list[Path]:
    table = compute(settings)
    return [save_csv(table, out / "critical_speeds.csv"),
            save_markdown(table, out / "critical_speeds.md",
                          "# Critical tape speeds (m/s), Table 1 parameters")]
