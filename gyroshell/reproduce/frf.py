"""Frequency response at V = 0, 50 and 90 m/s: the resonances move down with speed.

Bode plot (amplitude and phase at the load point, L_x/L_y = 4, Table 1, light viscous
damping) of the steady response to the Gaussian load P₀ e^{iωt} of Eq. 17, computed by the
reduced (rational Krylov) model with direct solves wherever its estimated error is above
the tolerance. The eigen-solver's lowest frequencies at each speed are drawn as ticks: the
peaks sit on them and move down as V grows (the effective tension T − ρV² falls).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.eigen import modes
from ..engines.frequency_response import frequency_response
from ..plot import bode
from ..tape.model import TapeModel
from ._common import Settings, pyplot, save_csv, save_figure
from ._runner import run_parts

VELOCITIES = (0.0, 50.0, 90.0)
#: Viscous (air) damping, N·s/m³ (damping ratio c / (2ρω) ≈ 0.9 % near √(k/ρ)).
DAMPING = 30.0
#: Angular frequency range, rad/s: from statics to above the lowest cluster of resonances.
OMEGA_MAX = 1.6e5
#: Eigen-solver frequencies marked per speed.
MODE_COUNT = 8


def parts(settings: Settings) -> tuple[float, ...]:
    """The independent parts: one per speed V, m/s."""
    return VELOCITIES


def compute_part(settings: Settings, velocity: float) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The FRF rows and the eigen-solver's frequencies at one speed."""
    model = TapeModel(settings.params(length_ratio=4))
    omega = np.linspace(0.0, OMEGA_MAX, settings.pick(1000, 300))
    v = velocity
    res = frequency_response(model, v, omega, damping=DAMPING, progress=settings.progress)
    frame = res.to_frame()
    frame.insert(0, "velocity", v)
    frame["factorizations"] = res.info["factorizations"]
    m = modes(model, v, MODE_COUNT)
    return frame, pd.DataFrame({"velocity": v, "rank": np.arange(1, m.count + 1),
                                "omega": m.omega})


def compute(settings: Settings) -> tuple[pd.DataFrame, pd.DataFrame]:
    """FRF rows (velocity, omega, amplitude, phase, method, error_estimate) and modes."""
    return combine([compute_part(settings, v) for v in parts(settings)])


def combine(results: list) -> tuple[pd.DataFrame, pd.DataFrame]:
    return (pd.concat([f for f, _ in results], ignore_index=True),
            pd.concat([m for _, m in results], ignore_index=True))


def plot(table: pd.DataFrame, found: pd.DataFrame, path: Path) -> Path:
    plt = pyplot()
    fig, ax = plt.subplots(2, 1, sharex=True, figsize=(9, 7))
    for i, v in enumerate(VELOCITIES):
        rows = table[table["velocity"] == v]
        bode(rows["omega"], rows["amplitude"], rows["phase"], axes=ax, color=f"C{i}",
             label=f"V = {v:g} m/s", mode_omegas=found[found["velocity"] == v]["omega"])
    ax[0].legend(title="dotted: eigen-solver ω_j", fontsize=9)
    worst = table["error_estimate"].max()
    ax[0].set_title(f"Frequency response at the load point, L_x/L_y = 4, c = {DAMPING:g} N·s/m³"
                    f" (reduced model, estimated error ≤ {worst:.0e})", fontsize=10)
    fig.tight_layout()
    return save_figure(fig, path)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    table, found = combine(results)
    return [save_csv(table, out / "frf.csv"), save_csv(found, out / "frf_modes.csv"),
            plot(table, found, out / "frf_bode.png")]


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
