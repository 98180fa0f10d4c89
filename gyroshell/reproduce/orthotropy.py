"""Orthotropic tapes on the paper's Table 1 geometry: what the stiffness across the tape
changes.

E_x (along the tape, 4 GPa), G_xy (1.538 GPa, the isotropic E/(2(1 + ν)), so that the ratio
1 is the Table 1 tape exactly), ν_xy (0.3) and the thickness are held while E_y/E_x runs over
[0.25, 4]. Held E_x is not held D11: D11 = E_x c³ / (12 (1 − ν_xy² E_y/E_x)) grows with E_y
through the minor Poisson ratio ν_yx = ν_xy E_y/E_x, and so does A11 and with it k = A11/R².

* ``orthotropy_speeds.csv`` / ``.png``: the critical speed (the gyroscopic eigenvalue's
  zero crossing) beside the width-uniform strip's √((T + 2√(D11 k))/ρ), and the lowest
  frequency at V = 0 and at 50 m/s, against E_y/E_x;
* ``orthotropy_profiles.csv`` / ``.png``: the static deflection under the paper's Gaussian
  load (P₀ = 200 Pa at the centre, V = 0) and the lowest mode shape at V = 0, cut across
  the width, for E_y/E_x = 0.25, 1 and 4;
* ``orthotropy_bearing.csv`` / ``.png``: the steady air bearing's spacing across the width
  at the middle of the wrap (2-D, 4 m/s, 15° wrap, a 120 x 40 grid) for the same tapes.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.critical import critical_speeds
from ..engines.eigen import modes
from ..engines.static import solve_static
from ..tape.model import TapeModel
from ..tape.parameters import TapeParameters
from ._common import Settings, pyplot, save_csv, save_figure
from ._runner import run_parts

#: E_y/E_x of the three tapes drawn side by side (soft across, isotropic, stiff across).
PROFILE_RATIOS = (0.25, 1.0, 4.0)
#: The representative speed of the second frequency column, m/s (half the critical speed).
SPEED = 50.0
#: The bearing's speed (m/s), wrap angle (rad) and grid (intervals along, across).
BEARING_SPEED = 4.0
BEARING_WRAP = math.radians(15.0)
#: (148 across is the default graded ny of the 6.35 mm tape: coarser edge rows touch down
#: falsely; measured at E_y/E_x = 0.25: 40 across gave contact, 148 the default grid's
#: edge spacing to 0.04 % and its minimum to 1.4 %.)
BEARING_GRID = (120, 148)
#: Ticks of the E_y/E_x axes.
RATIO_TICKS = (0.25, 0.5, 1.0, 2.0, 4.0)
#: Ticks of the log spacing axis near the edge, µm.
EDGE_TICKS_UM = (0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0, 2.0, 5.0)
#: Display scales.
UM, NM, MM = 1e6, 1e9, 1e3


def tape(settings: Settings, ratio: float) -> TapeParameters:
    """Table 1 with E_y = ratio × E_x and G_xy, ν_xy held at the isotropic values."""
    p = settings.params()
    shear = p.youngs_modulus / (2.0 * (1.0 + p.poisson))
    return p.replace(youngs_modulus_y=ratio * p.youngs_modulus, shear_modulus=shear)


def speed_ratios(settings: Settings) -> list[float]:
    """The E_y/E_x of the speed table."""
    return [float(r) for r in np.geomspace(0.25, 4.0, settings.pick(9, 3))]


def speed_row(settings: Settings, ratio: float) -> dict:
    """Critical speed, strip formula and lowest frequencies (V = 0, 50 m/s) at E_y/E_x."""
    p = tape(settings, ratio)
    model = TapeModel(p)
    d = p.bending_matrix
    return dict(
        ratio=ratio, youngs_modulus_y=p.youngs_modulus_y, D11=d.D11, D22=d.D22,
        D12=d.D12, D66=d.D66, k=p.k, critical_speed=critical_speeds(model).critical_speed,
        strip_critical_speed=p.strip_critical_speed,
        omega_1_at_rest=float(modes(model, 0.0, 1).omega[0]),
        omega_1_at_speed=float(modes(model, SPEED, 1).omega[0]))


def speeds(settings: Settings) -> pd.DataFrame:
    """Critical speed, strip formula and lowest frequencies (V = 0, 50 m/s) per E_y/E_x."""
    return pd.DataFrame([speed_row(settings, r) for r in speed_ratios(settings)])


def _cut_mode(result) -> np.ndarray:
    """The lowest mode across the width where it is largest, real, scaled to peak 1."""
    shape = result.field(0)
    i, j = np.unravel_index(np.argmax(np.abs(shape)), shape.shape)
    cut = (shape[i, :] * np.conj(shape[i, j]) / abs(shape[i, j])).real
    return cut / np.max(np.abs(cut))


def profile(settings: Settings, ratio: float) -> pd.DataFrame:
    """w(y) under the load at x = x₀ (m) and the lowest mode's cut of one tape."""
    p = tape(settings, ratio)
    model = TapeModel(p)
    grid = model.grid
    static = solve_static(model, 0.0).field
    column = int(np.argmin(np.abs(grid.x - p.load_centroid[0])))
    return pd.DataFrame({"ratio": ratio, "y": grid.y,
                         "static_deflection": static[column, :],
                         "mode_shape": _cut_mode(modes(model, 0.0, 1))})


def profiles(settings: Settings) -> pd.DataFrame:
    """w(y) under the load at x = x₀ (m) and the lowest mode's cut, per tape."""
    return pd.concat([profile(settings, r) for r in PROFILE_RATIOS], ignore_index=True)


def bearing_cut(settings: Settings, ratio: float) -> pd.DataFrame:
    """The bearing's cross-width spacing (m) at the middle of the wrap of one tape."""
    import warnings

    from ..bearing import AirParameters, BearingModel
    from ..bearing.model import BearingGridWarning
    from ..bearing.steady import solve_steady

    nx, ny = settings.pick(BEARING_GRID, (60, 20))
    with warnings.catch_warnings():  # the quick grid is coarse on purpose
        if settings.quick:
            warnings.simplefilter("ignore", BearingGridWarning)
        model = BearingModel(tape(Settings(), ratio), AirParameters(),
                             velocity=BEARING_SPEED, wrap_angle=BEARING_WRAP, nx=nx, ny=ny)
    sol = solve_steady(model)
    return pd.DataFrame({"ratio": ratio, "y": model.y,
                         "spacing": sol.cross_width_spacing,
                         "minimum_spacing": sol.minimum_spacing,
                         "central_spacing": sol.central_spacing})


def bearing(settings: Settings) -> pd.DataFrame:
    """The bearing's cross-width spacing (m) at the middle of the wrap, per tape."""
    return pd.concat([bearing_cut(settings, r) for r in PROFILE_RATIOS], ignore_index=True)


def _label(ratio: float) -> str:
    return "isotropic (Table 1)" if ratio == 1.0 else f"E_y/E_x = {ratio:g}"


def plot_speeds(table: pd.DataFrame):
    plt = pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    a.semilogx(table.ratio, table.critical_speed, "o-", label="critical speed (eigenvalue "
               "crosses zero)")
    a.semilogx(table.ratio, table.strip_critical_speed, "k--",
               label="strip √((T + 2√(D11 k))/ρ)")
    a.set_xlabel("E_y / E_x (E_x = 4 GPa, G_xy = 1.54 GPa, ν_xy = 0.3 held)")
    a.set_ylabel("speed (m/s)")
    a.set_title("critical speed, Table 1 geometry (free edges, L_x/L_y = 4)", fontsize=9)
    a.legend(fontsize=8)
    b.semilogx(table.ratio, table.omega_1_at_rest / (2e3 * math.pi), "o-", label="V = 0")
    b.semilogx(table.ratio, table.omega_1_at_speed / (2e3 * math.pi), "s-",
               label=f"V = {SPEED:g} m/s")
    b.set_xlabel("E_y / E_x")
    b.set_ylabel("lowest frequency (kHz)")
    b.set_title("lowest natural frequency", fontsize=9)
    b.legend(fontsize=8)
    for ax in (a, b):
        ax.grid(True, which="major", alpha=0.3)
        ax.set_xticks([], minor=True)
        ax.set_xticks(RATIO_TICKS, [f"{t:g}" for t in RATIO_TICKS])
    fig.tight_layout()
    return fig


def plot_profiles(table: pd.DataFrame):
    plt = pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, (ratio, rows) in enumerate(table.groupby("ratio", sort=True)):
        style = dict(color=f"C{k}", label=_label(ratio))
        a.plot(rows.y * MM, rows.static_deflection * NM, **style)
        b.plot(rows.y * MM, rows.mode_shape, **style)
    a.set_ylabel("static deflection w (nm)")
    a.set_title("under the Gaussian load (P₀ = 200 Pa), V = 0, cut at x = L_x/2", fontsize=9)
    b.set_ylabel("lowest mode, scaled to peak 1")
    b.set_title("lowest mode at V = 0, cut where it is largest", fontsize=9)
    for ax in (a, b):
        ax.set_xlabel("y across the width (mm)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def plot_bearing(table: pd.DataFrame):
    plt = pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), width_ratios=(2, 1))
    for k, (ratio, rows) in enumerate(table.groupby("ratio", sort=True)):
        label = (f"{_label(ratio)}: minimum over the tape "
                 f"{rows.minimum_spacing.iloc[0] * UM:.3f} µm")
        a.plot(rows.y * MM, rows.spacing * UM, color=f"C{k}", marker=".", ms=3, label=label)
        edge = rows[rows.y <= rows.y.min() + 0.6e-3]
        b.plot(edge.y * MM, edge.spacing * UM, color=f"C{k}", marker=".", ms=4)
    a.set_xlabel("y across the width (mm)")
    a.set_ylabel("spacing at the wrap centre (µm)")
    a.set_ylim(bottom=0)
    a.set_title(f"air bearing, V = {BEARING_SPEED:g} m/s, 15° wrap, "
                f"{BEARING_GRID[0]} x {BEARING_GRID[1]} grid", fontsize=9)
    a.legend(fontsize=8, loc="lower center")
    b.set_yscale("log")
    low, high = b.get_ylim()
    b.set_yticks([], minor=True)
    b.set_yticks(EDGE_TICKS_UM, [f"{t:g}" for t in EDGE_TICKS_UM])
    b.set_ylim(low, high)
    b.set_xlabel("y (mm), the edge y = 0")
    b.set_ylabel("spacing (µm, log)")
    b.set_title("near the free edge", fontsize=9)
    for ax in (a, b):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    return fig


def parts(settings: Settings) -> tuple:
    """The independent parts: ("speed", E_y/E_x) per row of the speed table, then
    ("profile", E_y/E_x) and ("bearing", E_y/E_x) per drawn tape."""
    return (*(("speed", r) for r in speed_ratios(settings)),
            *(("profile", r) for r in PROFILE_RATIOS),
            *(("bearing", r) for r in PROFILE_RATIOS))


def compute_part(settings: Settings, key: tuple[str, float]):
    """A row of the speed table (dict), or one tape's profile or bearing cut (frame)."""
    what, ratio = key
    return {"speed": speed_row, "profile": profile, "bearing": bearing_cut}[what](
        settings, ratio)


def write(out: Path, settings: Settings, results: list) -> list[Path]:
    keys = parts(settings)
    table = pd.DataFrame([r for (what, _), r in zip(keys, results, strict=True)
                          if what == "speed"])
    cuts, spacing = (pd.concat([r for (what, _), r in zip(keys, results, strict=True)
                                if what == kind], ignore_index=True)
                     for kind in ("profile", "bearing"))
    written = [save_csv(table, out / "orthotropy_speeds.csv"),
               save_csv(cuts, out / "orthotropy_profiles.csv"),
               save_csv(spacing, out / "orthotropy_bearing.csv")]
    return written + [save_figure(plot_speeds(table), out / "orthotropy_speeds.png"),
                      save_figure(plot_profiles(cuts), out / "orthotropy_profiles.png"),
                      save_figure(plot_bearing(spacing), out / "orthotropy_bearing.png")]


def run(out: Path, settings: Settings) -> list[Path]:
    return run_parts(sys.modules[__name__], out, settings)
