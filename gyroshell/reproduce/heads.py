"""Flat heads (issue 19): the spacing and pressure along a three-module head, the read-line
spacing across the width against speed, and a map of the read-line spacing and the drag
over the two wrap angles. The paper's Table 1 tape, air at 20 °C.

(a) ``heads_modules``: a write-read-write head of three 0.6 mm modules 0.4 mm apart, the
    outer modules tilted by 1° towards the middle one (each inner corner then turns the
    tape by 0.5°) and the spans 2° below the datum (the outer corners turn it by 1°), at
    4 m/s; the infinitely wide tape (1-D: the centre line of a wide tape away from its
    edges), the contour drawn under it.
(b) ``heads_width``: the spacing along the read line (the middle of a 1 mm module, 2° of
    wrap either side) across the width of the 2-D 6.35 mm tape at 2, 4 and 8 m/s, on half
    the default grids' intervals each way (measured against the default
    grids: the line's minimum 1.0-1.5 % and its mean 0.2-0.7 % higher, measured with the
    earlier interface, first-order slip over the hard wall).
(c) ``heads_wraps``: the read-line spacing and the drag (viscous and friction μ = 0.2)
    over wrap_in × wrap_out (0.5° to 4° each), the infinitely wide tape at 4 m/s on its
    default grid, computed as a head study
    (:func:`gyroshell.studies.parameter_study.run_study`, ``compute="bearing"``).

Under the default interface (the Boltzmann film over asperities) the three parts took
8.6 s of a worker's time in ``gyroshell reproduce all`` on 2 cores at load 1.8.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from ..bearing import AirParameters, BearingModel
from ..bearing.head_config import HeadDesign, ModuleShape
from ..bearing.steady import solve_steady
from ..tape.parameters import TapeParameters
from ._common import Settings, pyplot, save_csv, save_figure
from ._runner import run_parts

#: The speed of (a) and (c), m/s.
VELOCITY = 4.0
#: The three-module head of (a): lands, gap (m), the outer modules' tilt and the outer
#: wraps (rad).
MODULE_LAND, MODULE_GAP = 0.6e-3, 0.4e-3
MODULE_TILT, OUTER_WRAP = math.radians(1.0), math.radians(2.0)
#: The single module of (b) and (c): land (m), wraps (rad), friction coefficient.
LAND, WRAP, FRICTION = 1e-3, math.radians(2.0), 0.2


def three_modules() -> HeadDesign:
    """The head of (a): the outer modules tilted by MODULE_TILT towards the middle one and
    set so that each inner corner wraps the tape by half of it; transducers in the middle
    of each land."""
    pitch = MODULE_LAND + MODULE_GAP
    # module 1's line, z = h1 + α (x + pitch), meets the chord to module 2's leading
    # corner (−L/2, 0) at its trailing corner with the chord's slope α/2
    height = -MODULE_TILT * (0.5 * MODULE_LAND + 0.5 * MODULE_GAP)
    shapes = (ModuleShape(height=height, tilt=MODULE_TILT), ModuleShape(),
              ModuleShape(height=height, tilt=-MODULE_TILT))
    return HeadDesign(kind="flat", land_length=MODULE_LAND, modules=3, module_gap=MODULE_GAP,
                      module_shapes=shapes, wrap_in=OUTER_WRAP, wrap_out=OUTER_WRAP,
                      transducers=(-pitch, 0.0, pitch), friction=FRICTION)


def one_module(**changes) -> HeadDesign:
    """The single module of (b) and (c), its read line in the middle."""
    return HeadDesign(kind="flat", land_length=LAND, wrap_in=WRAP, wrap_out=WRAP,
                      transducers=(0.0,), friction=FRICTION).replace(**changes)


def modules_solution(settings: Settings):
    """(a): the steady state over the three-module head, on its default grid in both
    settings (a few seconds; within about 1 % of the grid twice as fine's estimate)."""
    del settings
    model = BearingModel(TapeParameters(), AirParameters(), velocity=VELOCITY,
                         head=three_modules().head(), infinitely_wide=True)
    return solve_steady(model)


def modules_table(sol) -> pd.DataFrame:
    """The centre line of (a): head contour, dry tape, flying tape, spacing, pressure."""
    model, head = sol.model, sol.model.head
    x = sol.x
    radius = model.params.radius
    z_head = head.surface(x, radius=radius)
    spacing = sol.spacing[:, 0]
    return pd.DataFrame({"x": x, "head_z": z_head, "dry_tape_z": head.dry_tape(x, radius=radius),
                         "tape_z": z_head + spacing, "spacing": spacing,
                         "pressure": sol.pressure[:, 0]})


def plot_modules(table: pd.DataFrame, sol):
    plt = pyplot()
    fig, (top, mid, low) = plt.subplots(3, 1, figsize=(8, 8.2), sharex=True,
                                        gridspec_kw={"height_ratios": [1, 1.3, 1]})
    model, head = sol.model, sol.model.head
    radius = model.params.radius
    first, last = head.extent(radius=radius)
    near = ((table.x > first - 0.5e-3) & (table.x < last + 0.5e-3)).to_numpy()
    t = table[near]
    x = t.x * 1e3
    floor = t.tape_z.min() * 1e6 - 15.0
    top.fill_between(x, t.head_z * 1e6, floor, color="0.8", label="head")
    top.plot(x, t.dry_tape_z * 1e6, "k--", lw=0.8, label="dry tape")
    top.plot(x, t.tape_z * 1e6, "C0", lw=1.0, label="flying tape")
    top.set_ylim(floor, t.tape_z.max() * 1e6 + 5.0)
    top.set_ylabel("z (µm)")
    top.legend(fontsize=8, loc="lower center", ncol=3)
    turns = ", ".join(f"{math.degrees(a):.2g}" for a in head.corner_turns(radius=radius))
    top.set_title(f"three {MODULE_LAND * 1e3:g} mm modules {MODULE_GAP * 1e3:g} mm apart, "
                  f"outer ones tilted {math.degrees(MODULE_TILT):g}°, spans "
                  f"{math.degrees(OUTER_WRAP):g}° below the datum (the corners turn the tape "
                  f"by {turns}°);\ninfinitely wide tape, V = {VELOCITY:g} m/s, "
                  f"{model.nx} intervals", fontsize=9)
    mid.semilogy(x, t.spacing * 1e6, "C0")
    for line in sol.transducer_lines:
        mid.axvline(line.x * 1e3, color="C3", lw=0.8, ls=":")
        mid.annotate(f"{line.centre * 1e9:.0f} nm", (line.x * 1e3, line.centre * 1e6),
                     xytext=(4, 8), textcoords="offset points", fontsize=8, color="C3")
    for c in head.corners(radius=radius):
        mid.axvline(c * 1e3, color="0.6", lw=0.6)
    mid.set_ylabel("spacing (µm)")
    mid.grid(True, which="both", alpha=0.3)
    low.plot(x, (t.pressure - model.air.ambient_pressure) * 1e-3, "C1")
    low.axhline(0.0, color="k", lw=0.6)
    low.set_ylabel("p − p_a (kPa)")
    low.set_xlabel("x from the head's middle (mm), tape moves →; grey: corners, red: "
                   "transducer lines")
    low.grid(True, alpha=0.3)
    fig.tight_layout()
    return fig


def width_speeds(settings: Settings) -> tuple[float, ...]:
    """The speeds of (b), m/s."""
    return settings.pick((2.0, 4.0, 8.0), (2.0, 8.0))


def width_rows(settings: Settings, v: float) -> list[dict]:
    """(b) at one speed V (m/s): the read line's spacing across the 2-D tape."""
    head = one_module().head()
    default = BearingModel(TapeParameters(), AirParameters(), velocity=v, head=head)
    if settings.quick:     # the default intervals along (the corners' refinement), few across
        nx, ny = default.nx, 24
    else:
        nx, ny = 4 * (default.nx // 8), 2 * (default.ny // 4)
    model = BearingModel(TapeParameters(), AirParameters(), velocity=v, head=head,
                         nx=nx, ny=ny)
    sol = solve_steady(model)
    line = sol.transducer_lines[0]
    return [dict(velocity=v, y=y, spacing=h, line_minimum=line.minimum,
                 line_mean=line.mean, newton_iterations=sol.info.iterations,
                 nx=model.nx, ny=model.ny)
            for y, h in zip(model.y, line.spacing, strict=True)]


def width_sweep(settings: Settings) -> pd.DataFrame:
    """(b): the read line's spacing across the 2-D tape at a few speeds."""
    return pd.DataFrame([row for v in width_speeds(settings)
                         for row in width_rows(settings, v)])


def plot_width(table: pd.DataFrame, grid_label: str = "default 2-D grids"):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for k, (v, group) in enumerate(table.groupby("velocity")):
        ax.plot(group.y * 1e3, group.spacing * 1e9, color=f"C{k}",
                label=f"V = {v:g} m/s (min {group.line_minimum.iloc[0] * 1e9:.0f} nm, "
                      f"mean {group.line_mean.iloc[0] * 1e9:.0f} nm)")
    ax.set_xlabel("y across the tape (mm)")
    ax.set_ylabel("spacing on the read line (nm)")
    ax.set_title("read line in the middle of a 1 mm flat module, 2° wrap either side, "
                 f"6.35 mm tape, {grid_label}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def wrap_map(settings: Settings):
    """(c): the head study over wrap_in × wrap_out (infinitely wide, 1-D)."""
    from ..studies.head_study import BearingStudy
    from ..studies.parameter_study import run_study

    wraps = [math.radians(d) for d in settings.pick((0.5, 1.0, 1.5, 2.0, 3.0, 4.0),
                                                    (1.0, 3.0))]
    setup = BearingStudy(head=one_module(), infinitely_wide=True,
                         nx=settings.pick(None, 400))
    return run_study(TapeParameters(), vary={"wrap_in": wraps, "wrap_out": wraps},
                     compute="bearing", velocity=VELOCITY, workers=1, bearing=setup,
                     progress=settings.progress)


def plot_wraps(table: pd.DataFrame, grid_label: str = "default grid"):
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    w_in = np.degrees(np.unique(table.wrap_in))
    w_out = np.degrees(np.unique(table.wrap_out))
    for ax, column, scale, label in (
            (axes[0], "transducer_1_min_spacing", 1e9, "read-line spacing (nm)"),
            (axes[1], "drag", 1.0, "drag per unit width (N/m), μ = 0.2")):
        grid = table.pivot(index="wrap_out", columns="wrap_in", values=column).to_numpy()
        mesh = ax.pcolormesh(w_in, w_out, grid * scale, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=label)
        low, high = np.nanmin(grid), np.nanmax(grid)
        for i, wo in enumerate(w_out):
            for j, wi in enumerate(w_in):
                bright = (grid[i, j] - low) > 0.6 * (high - low)   # yellow: dark text
                ax.text(wi, wo, f"{grid[i, j] * scale:.3g}", ha="center", va="center",
                        fontsize=7, color="k" if bright else "w")
        ax.set_xlabel("wrap_in (degrees)")
        ax.set_ylabel("wrap_out (degrees)")
    fig.suptitle(f"1 mm flat module, its read line in the middle; infinitely wide tape at "
                 f"{VELOCITY:g} m/s, {grid_label}", fontsize=10)
    fig.tight_layout()
    return fig


def parts(settings: Settings) -> tuple:
    """The independent parts: (a), (b) per speed, (c)."""
    return (("modules",), *(("width", v) for v in width_speeds(settings)), ("wraps",))


def compute_part(settings: Settings, key: tuple):
    """(a)'s solution, (b)'s rows at one speed, or (c)'s study."""
    if key[0] == "width":
        return width_rows(settings, key[1])
    return modules_solution(settings) if key[0] == "modules" else wrap_map(settings)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    sol, *width_parts, study = results
    table = modules_table(sol)
    written = [save_csv(table, out / "heads_modules.csv")]
    width = pd.DataFrame([row for rows in width_parts for row in rows])
    written.append(save_csv(width, out / "heads_width.csv"))
    wraps = study.table.drop(columns=["point"])
    written.append(save_csv(wraps, out / "heads_wraps.csv"))
    written += [save_figure(plot_modules(table, sol), out / "heads_modules.png"),
                save_figure(plot_width(width, settings.pick(
                    "half the default 2-D grids' intervals",
                    "--quick: 24 intervals across")),
                    out / "heads_width.png"),
                save_figure(plot_wraps(wraps, settings.pick(
                    "default grid", "--quick: a coarse 400-interval grid")),
                    out / "heads_wraps.png")]
    return written


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
