"""Figs. 3–4: 3-D wire-frame time histories of the whole tape, L_x/L_y = 4.

Snapshots of w(x, y, t) after the step load at a series of times (β = 1/4, γ = 1/2), plus the
t = ∞ panel from the static solver, which the paper obtained with the damped β = 1, γ = 3/2
run. The tape moves from x = 0 to x = L_x.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.newmark import march
from ..engines.static import solve_static
from ..plot import wireframe
from ..tape.model import TapeModel
from ._common import PAPER_DT, Settings, pyplot, save_csv, save_figure

#: Snapshot times, s (the paper notes the first free-edge reflection near 28 µs).
TIMES = tuple(t * 1e-6 for t in (6, 12, 20, 28, 40, 60, 100, 200))


def compute(settings: Settings, velocity: float) -> pd.DataFrame:
    """Long table t (s; inf for the static panel), x, y (m), w (m)."""
    model = TapeModel(settings.params(length_ratio=4))
    g = model.grid
    steps = int(round(TIMES[-1] / PAPER_DT))
    res = march(model, velocity, dt=PAPER_DT, steps=steps, snapshot_times=TIMES,
                progress=settings.progress)
    snaps = res.snapshots
    fields = list(snaps.fields) + [solve_static(model, velocity).field]
    times = list(snaps.times) + [np.inf]
    X, Y = np.asarray(g.X), np.asarray(g.Y)
    return pd.concat([pd.DataFrame({"t": t, "x": X.ravel(), "y": Y.ravel(), "w": f.ravel()})
                      for t, f in zip(times, fields, strict=False)], ignore_index=True)


def plot(table: pd.DataFrame, velocity: float, title: str, path: Path) -> Path:
    plt = pyplot()
    times = list(dict.fromkeys(table["t"]))
    x, y = snapshot_axes(table)
    zmax = table["w"].abs().max()
    fig = plt.figure(figsize=(12, 8.5))
    for k, t in enumerate(times):
        W = table[table["t"] == t]["w"].to_numpy().reshape(len(x), len(y))
        label = "t = ∞ (static)" if np.isinf(t) else f"t = {t * 1e6:.0f} µs"
        wireframe(x, y, W, ax=fig.add_subplot(3, 3, k + 1, projection="3d"), title=label,
                  zmax=zmax)
    motion = " (tape moves toward +x)" if velocity > 0 else ""
    fig.suptitle(f"{title}: wave propagation after a step load, V = {velocity:g} m/s, "
                 f"L_x/L_y = 4{motion}", fontsize=12)
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.02, top=0.93, wspace=0.0, hspace=0.05)
    return save_figure(fig, path)


def snapshot_axes(table: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    """Node coordinates x, y (m) of a long snapshot table (t, x, y, w; x-major order)."""
    first = table[table["t"] == table["t"].iloc[0]]
    ny1 = first["y"].nunique()
    return first["x"].to_numpy()[::ny1], first["y"].to_numpy()[:ny1]


def run_figure(out: Path, settings: Settings, name: str, velocity: float) -> list[Path]:
    table = compute(settings, velocity)
    return [save_csv(table, out / f"{name}_snapshots.csv"),
            plot(table, velocity, name.replace("fig", "Fig. "), out / f"{name}_wireframes.png")]
