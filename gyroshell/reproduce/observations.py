"""The paper's other observations, measured.

1. **First reflection from the free edges** (the paper: near t = 28 µs, Figs. 3–4). The
   time the front (2 % of the static deflection) reaches the free edge beside the load,
   and the time its reflection is back at the load point: the load-point history of the
   L_x/L_y = 4 tape is compared with that of a tape about four times as wide under the
   same load (same α, same spacing): until waves come back from the free
   edges the two agree; the first time they differ by 1 % of the peak is the arrival.
2. **Wavelength asymmetry** at V = 50 m/s (Fig. 4; Bogy et al.): the dominant wavelength of
   the centre-line disturbance w − w_static upstream and downstream of the load at 320 µs.
3. **Apparent wave-front speed**: the farthest point on the centre line where |w| exceeds
   2 % of the static load-point deflection, tracked in time; a straight-line fit gives the
   apparent front speed downstream and upstream (lab frame), at V = 0 and 50 m/s.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.newmark import march
from ..engines.static import solve_static
from ..studies.signal import dominant_wavelength, first_departure, front_position
from ..tape.loads import gaussian_exponent, gaussian_load
from ..tape.model import TapeModel
from ._common import PAPER_DT, Settings, pyplot, save_csv, save_figure
from ._marches import step_response
from ._runner import run_parts

REFLECTION_DT, REFLECTION_STEPS = 0.5e-6, 140
DEPARTURE_FRACTION = 0.01
WAVELENGTH_TIME = 320e-6
FRONT_TIMES = tuple(k * 4e-6 for k in range(19))     # 0 .. 72 µs
FRONT_FRACTION = 0.02
FRONT_FIT_FROM = 20e-6


def edge_reflection(settings: Settings) -> dict:
    """Load-point histories of the real tape and a ~4x wider reference, and the departure."""
    narrow_p = settings.params(length_ratio=4)
    narrow = TapeModel(narrow_p)
    # About four times as wide, with the same spacing and the load centroid in the same
    # place relative to the nodes (between two nodes on the paper's 41-interval grid).
    ny = narrow.grid.ny
    extra = round(1.5 * ny)
    wide_p = narrow_p.replace(width=narrow_p.width * (ny + 2 * extra) / ny,
                              length_ratio=narrow_p.length / (narrow_p.width
                                                              * (ny + 2 * extra) / ny))
    wide_grid_model = TapeModel(wide_p)
    load = gaussian_load(wide_grid_model.grid, wide_p,
                         exponent=gaussian_exponent(narrow_p.width))
    wide = TapeModel(wide_p, force=load)
    runs = [march(m, 0.0, dt=REFLECTION_DT, steps=REFLECTION_STEPS, progress=False,
                  snapshot_every=1 if m is narrow else None) for m in (narrow, wide)]
    t = runs[0].times
    t_ref = first_departure(t, runs[0].load_point, runs[1].load_point, DEPARTURE_FRACTION)
    # Arrival of the front at the free edge beside the load, (x0, 0): the same 2 % threshold
    # as the front tracking below.
    i0 = int(round(narrow.params.load_centroid[0] / narrow.grid.hx))
    edge = runs[0].snapshots.fields[:, i0, 0]
    threshold = FRONT_FRACTION * abs(solve_static(narrow, 0.0).load_point_deflection)
    t_edge = float(t[np.argmax(np.abs(edge) > threshold)])
    return dict(t=t, narrow=runs[0].load_point, wide=runs[1].load_point, t_reflection=t_ref,
                t_edge=t_edge)


def wavelengths(settings: Settings, velocity: float = 50.0) -> dict:
    model = TapeModel(settings.params(length_ratio=19))
    steps = int(round(WAVELENGTH_TIME / PAPER_DT))
    s = step_response(settings, velocity, PAPER_DT, steps, centerline_times=[WAVELENGTH_TIME],
                      progress=settings.progress)
    static_line = model.grid.centerline(solve_static(model, velocity).field)
    dist = s.centerlines[0] - static_line
    x, x0 = s.x, model.params.load_centroid[0]
    span = 0.2 * model.params.length
    up = (x < x0 - 1e-3) & (x > x0 - span)
    down = (x > x0 + 1e-3) & (x < x0 + span)
    return dict(upstream=dominant_wavelength(x[up], dist[up]),
                downstream=dominant_wavelength(x[down], dist[down]))


def fronts(settings: Settings, velocity: float) -> pd.DataFrame:
    model = TapeModel(settings.params(length_ratio=19))
    steps = int(round(FRONT_TIMES[-1] / PAPER_DT))
    s = step_response(settings, velocity, PAPER_DT, steps, centerline_times=FRONT_TIMES,
                      progress=False)
    threshold = FRONT_FRACTION * abs(solve_static(model, velocity).load_point_deflection)
    x0 = model.params.load_centroid[0]
    rows = [dict(velocity=velocity, t=t,
                 downstream=front_position(s.x, line, x0, threshold, +1) - x0,
                 upstream=x0 - front_position(s.x, line, x0, threshold, -1))
            for t, line in zip(s.centerline_times, s.centerlines, strict=False)]
    return pd.DataFrame(rows)


def front_speed(frame: pd.DataFrame, column: str) -> float:
    late = frame[frame["t"] >= FRONT_FIT_FROM]
    return float(np.polyfit(late["t"], late[column], 1)[0])


#: The speeds of the front tracking, m/s.
FRONT_SPEEDS = (0.0, 50.0)


def parts(settings: Settings) -> tuple:
    """The independent parts: the edge reflection, the wavelengths, the fronts per speed."""
    return ("reflection", "wavelengths", *(("fronts", v) for v in FRONT_SPEEDS))


def compute_part(settings: Settings, key):
    """One part's result: a dict (reflection, wavelengths) or a front table."""
    if key == "reflection":
        return edge_reflection(settings)
    if key == "wavelengths":
        return wavelengths(settings)
    return fronts(settings, key[1])


def compute(settings: Settings):
    return combine([compute_part(settings, key) for key in parts(settings)])


def combine(results: list):
    """The observations table, the reflection's histories and the front table."""
    refl, lam, *front_tables = results
    rows = [
        dict(quantity="wave front reaches the free edge beside the load", value=
             refl["t_edge"] * 1e6, unit="us", paper="first reflection near 28 us",
             how="|w(x0, 0)| > 2 % of the static load-point deflection, L_x/L_y = 4, V = 0"),
        dict(quantity="reflection from the free edges back at the load point", value=
             refl["t_reflection"] * 1e6, unit="us", paper="(not given)",
             how="load point vs a 4x wider tape, 1 % departure, L_x/L_y = 4, V = 0"),
        dict(quantity="dominant wavelength upstream of the load, V = 50", value=
             lam["upstream"] * 1e3, unit="mm", paper="shorter upstream",
             how="centre line w - w_static at 320 us, L_x/L_y = 19"),
        dict(quantity="dominant wavelength downstream of the load, V = 50", value=
             lam["downstream"] * 1e3, unit="mm", paper="longer downstream",
             how="centre line w - w_static at 320 us, L_x/L_y = 19"),
    ]
    for ft in front_tables:
        v = ft["velocity"].iloc[0]
        for side in ("downstream", "upstream"):
            rows.append(dict(quantity=f"apparent front speed {side}, V = {v:g}",
                             value=front_speed(ft, side), unit="m/s",
                             paper="downstream front faster when V increases",
                             how="2 % of static deflection, centre line, fit 20-72 us"))
    return pd.DataFrame(rows), refl, pd.concat(front_tables, ignore_index=True)


def plot(refl: dict, front_table: pd.DataFrame, path: Path) -> Path:
    from .. import plot as gplot

    plt = pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
    gplot.edge_reflection(refl["t"], refl["narrow"], refl["wide"], t_edge=refl["t_edge"],
                          t_reflection=refl["t_reflection"], ax=a)
    a.lines[1].set_label("reference, width ~4 L_y")
    a.legend(fontsize=8)
    a.set_title("Reflection from the free edges (V = 0, L_x/L_y = 4)", fontsize=10)
    speeds = {(v, side): front_speed(ft, side)
              for v, ft in front_table.groupby("velocity") for side in ("downstream", "upstream")}
    gplot.wave_fronts(front_table, speeds=speeds, ax=b)
    b.set_title("Apparent wave fronts on the centre line (L_x/L_y = 19)", fontsize=10)
    fig.tight_layout()
    return save_figure(fig, path)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    table, refl, front_table = combine(results)
    return [save_csv(table, out / "observations.csv"),
            save_csv(front_table, out / "wave_fronts.csv"),
            plot(refl, front_table, out / "observations.png")]


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
