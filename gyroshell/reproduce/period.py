"""Dominant period of the load-point displacement against tape speed, L_x/L_y = 19.

Two independent routes (the study that explains why the period grows with V):

* ``period_transient``: the tallest peak of a Hann-windowed, zero-padded FFT of the
  load-point history after a step load (Newmark, β = 1/4, γ = 1/2);
  ``period_transient_edge``: the lowest spectral peak reaching 25 % of the tallest;
* ``period_eigen``: 2π/ω₁, the lowest frequency of the gyroscopic eigenproblem.

The load-point spectrum is empty below ω₁ and starts there with a sharp peak (the band
edge, ``period_transient_edge`` = ``period_eigen``); above it the finite tape's standing
waves give further peaks, and between 50 and 95 m/s one of them, 5–30 % higher in frequency,
is the tallest. Both measures grow with V as the paper observed.

A long tape's lowest frequency is the minimum over wavenumbers of the moving-frame dispersion
ω(α) = |Vα − √((Dα⁴ + Tα² + k)/ρ)|: a wave with zero group velocity, which stays at the load
point and dominates its history. It falls from √(k/ρ) at V = 0 to zero at the critical
speed, so the period grows without bound as V approaches it.

Record length: at least 2 ms and 60 eigen-periods. Below ω₁ the spectrum is empty and
above it is dense (a band edge), so a short record's windowed peak sits above ω₁: with 10
periods the FFT period came out 6–26 % short at 75–95 m/s, with 60 it is within a few per
cent. The time step is the paper's 2 µs, or a fortieth of the eigen-period when that is
longer (near the critical speed), which resolves the dominant period (phase error
~ (2π/40)²/12 = 0.2 %) while the unresolved fast content stays far above it.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.eigen import modes
from ..plot import period_vs_velocity
from ..plot import spectra as plot_spectra
from ..studies.signal import amplitude_spectrum, dominant_period
from ..tape.model import TapeModel
from ._common import PAPER_DT, Settings, pyplot, save_csv, save_figure
from ._marches import step_response
from ._runner import run_parts

VELOCITIES = (0.0, 25.0, 50.0, 75.0, 90.0, 95.0, 100.0)
MIN_RECORD = 2.0e-3
PERIODS_PER_RECORD = 60
STEPS_PER_PERIOD = 40
EDGE_FRACTION = 0.25


def parts(settings: Settings) -> tuple[float, ...]:
    """The independent parts: one per speed V, m/s."""
    return VELOCITIES


def compute_part(settings: Settings, velocity: float) -> tuple[dict, pd.DataFrame]:
    """The periods at one speed (a table row) and its load-point spectrum (ω in rad/s)."""
    model = TapeModel(settings.params(length_ratio=19))
    v = velocity
    eig = modes(model, v, count=1)
    p_eig = float(eig.period[0])
    dt = max(PAPER_DT, p_eig / STEPS_PER_PERIOD)
    steps = math.ceil(max(MIN_RECORD, PERIODS_PER_RECORD * p_eig) / dt)
    steps = settings.pick(steps, min(steps, 400))
    res = step_response(settings, v, dt, steps, progress=settings.progress)
    p_tr = dominant_period(res.times, res.load_point)
    p_edge = dominant_period(res.times, res.load_point, lowest_fraction=EDGE_FRACTION)
    freqs, amp = amplitude_spectrum(res.load_point, dt)
    keep = freqs * 2 * np.pi <= 4 * eig.omega[0]
    spectrum = pd.DataFrame({"velocity": v, "omega": 2 * np.pi * freqs[keep],
                             "amplitude": amp[keep] / amp[keep].max()})
    row = dict(velocity=v, period_transient=p_tr, period_transient_edge=p_edge,
               period_eigen=p_eig,
               omega_eigen=float(eig.omega[0]), dt=dt, steps=steps,
               record=steps * dt, edge_vs_eigen=abs(p_edge / p_eig - 1),
               dominant_vs_eigen=abs(p_tr / p_eig - 1))
    return row, spectrum


def compute(settings: Settings) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Periods against speed, and the load-point amplitude spectra (ω in rad/s)."""
    return combine([compute_part(settings, v) for v in parts(settings)])


def combine(results: list) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The parts' results as the two tables."""
    return (pd.DataFrame([row for row, _ in results]),
            pd.concat([sp for _, sp in results], ignore_index=True))


def plot(table: pd.DataFrame, spectra: pd.DataFrame, path: Path,
         v_crit: float | None = None) -> Path:
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5), gridspec_kw={"width_ratios": [1, 1]})
    period_vs_velocity(table["velocity"], table["period_eigen"],
                       transient_edge=table["period_transient_edge"],
                       transient=table["period_transient"], critical_speed=v_crit, ax=ax,
                       title="Dominant period against tape speed, L_x/L_y = 19")
    groups = list(spectra.groupby("velocity"))
    omega_1 = [table.loc[table["velocity"] == v, "omega_eigen"].iloc[0] for v, _ in groups]
    plot_spectra([v for v, _ in groups], [sp["omega"] for _, sp in groups],
                 [sp["amplitude"] for _, sp in groups], omega_ref=omega_1, ax=bx, xmax=3.0,
                 title="Spectra start at ω₁: nothing below the lowest eigenfrequency")
    bx.set_ylabel("load-point amplitude spectrum (normalized, offset by speed)")
    fig.tight_layout()
    return save_figure(fig, path)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    from ..engines.divergence import divergence_speed

    table, spectra = combine(results)
    v_c = divergence_speed(TapeModel(settings.params(length_ratio=19)))
    return [save_csv(table, out / "period_vs_velocity.csv"),
            save_csv(spectra, out / "period_spectra.csv"),
            plot(table, spectra, out / "period_vs_velocity.png", v_c)]


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
