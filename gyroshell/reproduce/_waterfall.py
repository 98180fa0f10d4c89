"""Figs. 5–6: wave action on the centre line y = L_y/2 of the long tape, L_x/L_y = 19.

The centre-line displacement after the step load, at a series of times, stacked as a
waterfall (each curve offset by its time). The tape moves from left to right.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ..plot import waterfall
from ._common import PAPER_DT, Settings, pyplot, save_csv, save_figure
from ._marches import step_response

#: Centre-line times, s: every 32 µs up to 800 µs (the paper labels a panel 736 µs).
TIMES = tuple(k * 32e-6 for k in range(26))


def compute(settings: Settings, velocity: float) -> pd.DataFrame:
    """Long table t (s), x (m), w (m) of the centre line."""
    steps = int(round(TIMES[-1] / PAPER_DT))
    s = step_response(settings, velocity, PAPER_DT, steps, centerline_times=TIMES,
                      progress=settings.progress)
    return pd.concat([pd.DataFrame({"t": t, "x": s.x, "w": line})
                      for t, line in zip(s.centerline_times, s.centerlines, strict=False)],
                     ignore_index=True)


def plot(table: pd.DataFrame, velocity: float, title: str, path: Path,
         x0: float | None = None) -> Path:
    plt = pyplot()
    times = np.array(sorted(table["t"].unique()))
    x = table[table["t"] == times[0]]["x"].to_numpy()
    lines = np.array([table[table["t"] == t]["w"].to_numpy() for t in times])
    fig, ax = plt.subplots(figsize=(9, 10))
    waterfall(times, x, lines, ax=ax, load_point=x0,
              title=f"{title}: centre-line (y = L_y/2) wave action, V = {velocity:g} m/s, "
                    "L_x/L_y = 19")
    fig.tight_layout()
    return save_figure(fig, path)


def run_figure(out: Path, settings: Settings, name: str, velocity: float) -> list[Path]:
    table = compute(settings, velocity)
    x0 = settings.params(length_ratio=19).load_centroid[0]
    return [save_csv(table, out / f"{name}_centerline.csv"),
            plot(table, velocity, name.replace("fig", "Fig. "), out / f"{name}_waterfall.png",
                 x0=x0)]
