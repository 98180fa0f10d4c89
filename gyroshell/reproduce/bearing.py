"""Head–tape air bearing studies: spacing against speed beside the 2/3 law, spacing and
pressure maps of a 2-D tape, its cross-width spacing, and the transient after a tension
step. The paper's Table 1 tape over a head of its radius, 15° wrap, air at 20 °C.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from ..bearing import AirParameters, BearingModel
from ..bearing.model import BearingModelWarning, foil_length_scales
from ..bearing.steady import solve_steady
from ..bearing.transient import march, tension_step
from ..tape.parameters import TapeParameters
from ._common import Settings, pyplot, save_csv, save_figure
from ._runner import run_parts

WRAP = math.radians(15.0)
#: Blok & van Rossum's flexible-foil constant, h₀ = 0.643 R (6μV/T)^(2/3) (Eshel & Elrod
#: 1965); the tests derive it from the scaled foil equation, here it only labels a line.
FOIL_CONSTANT = 0.643
TENSION_STEP = (90.0, 120.0)


def sweep_speeds(settings: Settings) -> list[float]:
    """The tape speeds of the sweep, m/s."""
    return [float(v) for v in np.geomspace(0.5, 16.0, settings.pick(11, 4))]


def sweep_rows(settings: Settings, v: float) -> list[dict]:
    """The sweep's rows at one speed V (m/s): one per film model."""
    tape = TapeParameters()
    flexible = tape.replace(bending_rigidity=1e-12, foundation_stiffness=0.0)
    incompressible = AirParameters(compressible=False, mean_free_path=0.0)
    cases = {"compressible, slip": (tape, AirParameters()),
             "incompressible, no slip": (tape, incompressible),
             "flexible (D, k -> 0), incompressible": (flexible, incompressible)}
    rows = []
    for name, (params, air) in cases.items():
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", BearingModelWarning)
            model = BearingModel(params, air, velocity=v, wrap_angle=WRAP,
                                 infinitely_wide=True,
                                 nx=settings.pick(1600 if params is flexible else None, 400))
        sol = solve_steady(model)
        rows.append(dict(velocity=v, film=name, central_spacing=sol.central_spacing,
                         minimum_spacing=sol.minimum_spacing,
                         foil_law=FOIL_CONSTANT * foil_length_scales(tape, air, v)[0],
                         contact_force=sol.contact_force,
                         newton_iterations=sol.info.iterations,
                         # the wrap below the smallest the shell's spans allow at this V
                         # (BearingModel.smallest_valid_wrap): the spacing comes out low
                         below_valid_wrap=any(issubclass(w.category, BearingModelWarning)
                                              for w in caught)))
    return rows


def speed_sweep(settings: Settings) -> pd.DataFrame:
    return pd.DataFrame([row for v in sweep_speeds(settings) for row in sweep_rows(settings, v)])


def plot_speed(table: pd.DataFrame):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for k, (name, group) in enumerate(table.groupby("film", sort=False)):
        ax.loglog(group.velocity, group.central_spacing * 1e6, "o-", color=f"C{k}",
                  label=f"central, {name}")
        ax.loglog(group.velocity, group.minimum_spacing * 1e6, "s--", color=f"C{k}", ms=4,
                  label=f"minimum, {name}")
    law = table.groupby("velocity").foil_law.first()
    ax.loglog(law.index, law.values * 1e6, "k:", label="0.643 R (6μV/(T−ρV²))^(2/3)")
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("spacing (µm)")
    ax.set_title("Infinitely wide tape, 15° wrap, R = 20 mm, T = 90 N/m")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return fig


def two_dimensional(settings: Settings):
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, wrap_angle=WRAP,
                         nx=settings.pick(None, 120), ny=settings.pick(None, 40))
    return solve_steady(model)


def transient(settings: Settings):
    model = BearingModel(TapeParameters(tension=TENSION_STEP[0]), AirParameters(),
                         velocity=4.0, wrap_angle=WRAP, infinitely_wide=True,
                         nx=settings.pick(300, 120))
    start = solve_steady(model)
    after = solve_steady(model, tension=TENSION_STEP[1])
    run = march(start, dt=1e-5, steps=settings.pick(500, 150),
                tension=tension_step(*TENSION_STEP), record_every=1,
                beta=0.3025, gamma=0.6, progress=settings.progress)
    return run, start, after


def plot_transient(run, start, after):
    plt = pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.2))
    t = run.t * 1e3
    a.plot(t, run.central_spacing * 1e6, label="central spacing")
    a.plot(t, run.minimum_spacing * 1e6, label="minimum spacing")
    for sol, ls in ((start, ":"), (after, "--")):
        a.axhline(sol.central_spacing * 1e6, color="C0", ls=ls, lw=0.8)
        a.axhline(sol.minimum_spacing * 1e6, color="C1", ls=ls, lw=0.8)
    a.set_xlabel("time after the step (ms)")
    a.set_ylabel("spacing (µm)")
    a.set_title(f"tension step {TENSION_STEP[0]:g} → {TENSION_STEP[1]:g} N/m at t = 0 "
                "(dotted: steady before, dashed: after)", fontsize=9)
    a.legend()
    picks = np.unique(np.linspace(0, len(run.t) - 1, 6).astype(int))
    for k in picks:
        b.plot(run.x * 1e3, run.centreline[k] * 1e6, label=f"t = {run.t[k] * 1e3:.2f} ms")
    b.plot(after.x * 1e3, after.spacing[:, 0] * 1e6, "k--", lw=0.8, label="steady, after")
    half = 0.5 * start.model.params.radius * start.model.wrap_angle * 1e3
    b.set_xlim(-1.3 * half, 1.3 * half)
    b.set_ylim(0, 3 * start.central_spacing * 1e6)
    b.set_xlabel("x from the middle of the wrap (mm), tape moves →")
    b.set_ylabel("spacing (µm)")
    b.legend(fontsize=8)
    return fig


def parts(settings: Settings) -> tuple:
    """The independent parts: ("sweep", V) per speed of the sweep, the 2-D maps, the
    transient."""
    return (*(("sweep", v) for v in sweep_speeds(settings)), ("maps",), ("transient",))


def compute_part(settings: Settings, key: tuple):
    """A speed's sweep rows, the 2-D solution, or the transient (run, start, after)."""
    if key[0] == "sweep":
        return sweep_rows(settings, key[1])
    return two_dimensional(settings) if key[0] == "maps" else transient(settings)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    from ..bearing import plots

    *sweep, sol, (tr, start, after) = results
    written = []
    table = pd.DataFrame([row for rows in sweep for row in rows])
    written += [save_csv(table, out / "bearing_speed.csv"),
                save_figure(plot_speed(table), out / "bearing_speed.png")]
    plt = pyplot()
    fig, axes = plt.subplots(2, 1, figsize=(8, 7.5))
    plots.spacing_map(sol, axes[0])
    plots.spacing_map(sol, axes[1], field="pressure")
    axes[0].set_title(f"{sol.model.params.width * 1e3:g} mm tape, V = 4 m/s, 15° wrap: "
                      f"h_c = {sol.central_spacing * 1e6:.3f} µm, "
                      f"h_min = {sol.minimum_spacing * 1e6:.3f} µm "
                      f"({sol.model.nx}x{sol.model.ny} grid)", fontsize=9)
    fig.tight_layout()
    written.append(save_figure(fig, out / "bearing_maps.png"))
    cross = pd.DataFrame({"y": sol.model.y, "spacing": sol.cross_width_spacing})
    written.append(save_csv(cross, out / "bearing_cross_width.csv"))
    ax = plots.cross_width(sol)
    ax.set_title("spacing across the width at the middle of the wrap", fontsize=9)
    written.append(save_figure(ax.figure, out / "bearing_cross_width.png"))
    frame = pd.DataFrame({"t": tr.t, "tension": tr.tension,
                          "central_spacing": tr.central_spacing,
                          "minimum_spacing": tr.minimum_spacing,
                          "newton_iterations": tr.newton_iterations})
    written += [save_csv(frame, out / "bearing_transient.csv"),
                save_figure(plot_transient(tr, start, after), out / "bearing_transient.png")]
    return written


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
