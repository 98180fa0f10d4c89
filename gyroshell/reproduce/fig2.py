"""Fig. 2: transient load-point displacement for V = 0, 50, 90, 100 m/s, L_x/L_y = 19.

A step load (Eq. 17) is applied at t = 0 to the tape at rest in its wrapped equilibrium.
Displacements are shown nondimensionally as w k / P_0: the deflection as a fraction of the
Winkler value P_0 / k of a uniformly loaded foundation (9.10e-7 m for Table 1). The dots are
the steady states from the static solver, cross-checked by a strongly damped Newmark run
(β = 1, γ = 3/2, large Δt), as the paper did.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.newmark import march
from ..engines.static import solve_static
from ..plot import load_point_history
from ..tape.model import TapeModel
from ._common import PAPER_DT, Settings, pyplot, save_csv, save_figure
from ._marches import step_response
from ._runner import run_parts

VELOCITIES = (0.0, 50.0, 90.0, 100.0)
#: Damped run to the steady state: Δt (s) and steps.
DAMPED_DT, DAMPED_STEPS = 1.0e-2, 100


def parts(settings: Settings) -> tuple[float, ...]:
    """The independent parts: one per speed V, m/s."""
    return VELOCITIES


def compute_part(settings: Settings, velocity: float) -> tuple[pd.DataFrame, dict]:
    """The load-point history (long format) and the steady states at one speed."""
    model = TapeModel(settings.params(length_ratio=19))
    scale = model.params.k / model.params.load_pressure
    steps = settings.pick(1000, 200)
    v = velocity
    res = step_response(settings, v, PAPER_DT, steps, progress=settings.progress)
    history = pd.DataFrame({"velocity": v, "t": res.times, "w": res.load_point,
                            "w_nondim": res.load_point * scale})
    w_static = solve_static(model, v).load_point_deflection
    damped = march(model, v, dt=DAMPED_DT, steps=DAMPED_STEPS, beta=1.0, gamma=1.5,
                   progress=False)
    steady = dict(velocity=v, w_static=w_static, w_damped=damped.load_point[-1],
                  rel_difference=abs(damped.load_point[-1] / w_static - 1),
                  w_static_nondim=w_static * scale,
                  w_mean_transient=float(np.mean(res.load_point)))
    return history, steady


def compute(settings: Settings) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Load-point histories (long format) and steady states for each speed."""
    return combine([compute_part(settings, v) for v in parts(settings)])


def combine(results: list) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The parts' results as the two tables."""
    return (pd.concat([h for h, _ in results], ignore_index=True),
            pd.DataFrame([s for _, s in results]))


def plot(history: pd.DataFrame, steady: pd.DataFrame, path: Path) -> Path:
    plt = pyplot()
    speeds = list(steady["velocity"])
    fig, axes = plt.subplots(len(speeds), 1, figsize=(8, 8.5), sharex=True)
    for ax, v in zip(axes, speeds, strict=False):
        h = history[history["velocity"] == v]
        s = steady[steady["velocity"] == v].iloc[0]
        load_point_history(h["t"], h["w_nondim"], steady=s["w_static_nondim"], ylabel="w k / P₀",
                           velocity=v, ax=ax)
    for ax in axes[:-1]:
        ax.set_xlabel("")
    axes[0].legend(loc="lower right", fontsize=8)
    fig.suptitle("Fig. 2: load-point displacement after a step load, L_x/L_y = 19", y=0.995)
    fig.tight_layout()
    return save_figure(fig, path)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    history, steady = combine(results)
    return [save_csv(history, out / "fig2_load_point.csv"),
            save_csv(steady, out / "fig2_steady_state.csv"),
            plot(history, steady, out / "fig2_load_point.png")]


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
