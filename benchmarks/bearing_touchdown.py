"""Where the free edges of a 2-D tape touch the head (Table 1 tape, air at 20 °C).

    PYTHONPATH=. python benchmarks/bearing_touchdown.py paper-grid   # ~3 min
    PYTHONPATH=. python benchmarks/bearing_touchdown.py variants     # ~1.5 min
    PYTHONPATH=. python benchmarks/bearing_touchdown.py map          # ~4 min

``paper-grid``: the 12.65 mm tape at 4 m/s over a 15° wrap on uniform grids from the seed
paper's spacing (Δx = Δy = 1.549e-4 m) down to 19 × 39 µm, and on the graded default: the
edges "touch down" only while Δy is too coarse for the film's free-edge layer.

``variants``: the 6.35 mm tape at 4 m/s, 15°, on the default graded grid, with the
modelling choices switched one at a time (shell stiffness k, slip, Poisson coupling, the
bending reference load of the wrap). The last three rows change the model's private
reference load ``f_kappa`` (they are modelling experiments, not options of the API).

``map``: the 6.35 mm tape on default grids for wraps 5°, 15°, 30° and V = 0.25–16 m/s:
minimum spacing, contact nodes, Newton iterations and whether pseudo-time or continuation
was needed.

Prints Markdown table rows (spacings in µm; x from the wrap centre, > 0 downstream).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel, solve_steady

WRAP = math.radians(15.0)


def _row(*cells) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


def paper_grid() -> None:
    tape = TapeParameters(width=12.65e-3)
    print(_row("grid nx × ny", "Δx (µm)", "Δy (µm)", "h_c (µm)", "h_min (µm)", "x_min (mm)",
               "contact nodes", "contact force (N)", "s"))
    for nx, ny, grading in ((60, 82, "uniform"), (120, 82, "uniform"), (240, 82, "uniform"),
                            (240, 164, "uniform"), (480, 328, "uniform"),
                            (None, None, None)):
        start = time.perf_counter()
        model = BearingModel(tape, velocity=4.0, wrap_angle=WRAP, nx=nx, ny=ny,
                             grading=grading)
        sol = solve_steady(model)
        dx, dy = np.diff(model.x), np.diff(model.y)
        name = f"{model.nx} × {model.ny}" + (" graded" if grading is None else "")
        print(_row(name, f"{dx.min() * 1e6:.0f}–{dx.max() * 1e6:.0f}",
                   f"{dy.min() * 1e6:.0f}–{dy.max() * 1e6:.0f}",
                   f"{sol.central_spacing * 1e6:.3f}", f"{sol.minimum_spacing * 1e6:.4f}",
                   f"{sol.minimum_location[0] * 1e3:.2f}", sol.contact_nodes,
                   f"{sol.contact_force:.2g}", f"{time.perf_counter() - start:.0f}"),
              flush=True)


def _no_poisson_moment(model: BearingModel) -> None:
    t, p = model.tape, model.params
    ny = len(t.y) - 1
    inner = t._w_inner * np.repeat(model.kappa, ny - 1)
    edge = t._w_edge * np.repeat(model.kappa, 2)
    model.f_kappa = p.D * (t._dxx.T @ inner + t._dxx_edge.T @ edge)


def _stress_free_wrap(model: BearingModel) -> None:
    model.f_kappa = np.zeros_like(model.f_kappa)


def variants() -> None:
    tape = TapeParameters()
    same_plate = {"bending_rigidity": tape.D}
    cases = [
        ("this model (Table 1 k, ν = 0.3, slip)", {}, {}, None),
        ("k = 0", {"foundation_stiffness": 0.0}, {}, None),
        ("no slip (λ = 0)", {}, {"mean_free_path": 0.0}, None),
        ("ν = 0 (no Poisson coupling)",
         {"poisson": 0.0, "foundation_stiffness": tape.k, **same_plate}, {}, None),
        ("k = 0, ν = 0", {"poisson": 0.0, "foundation_stiffness": 0.0, **same_plate}, {},
         None),
        ("wrap curvature without its Poisson moment", {}, {}, _no_poisson_moment),
        ("wrapped configuration stress-free (seed paper's shell)", {}, {},
         _stress_free_wrap),
        ("same, k = 0", {"foundation_stiffness": 0.0}, {}, _stress_free_wrap),
    ]
    print(_row("variant", "h_c (µm)", "h_min (µm)", "x_min (mm)", "y_min (mm)",
               "contact nodes", "s"))
    for name, tape_changes, air_changes, patch in cases:
        start = time.perf_counter()
        model = BearingModel(tape.replace(**tape_changes), AirParameters(**air_changes),
                             velocity=4.0, wrap_angle=WRAP)
        if patch is not None:
            patch(model)
        sol = solve_steady(model)
        x, y = sol.minimum_location
        print(_row(name, f"{sol.central_spacing * 1e6:.3f}", f"{sol.minimum_spacing * 1e6:.3f}",
                   f"{x * 1e3:.2f}", f"{y * 1e3:.2f}", sol.contact_nodes,
                   f"{time.perf_counter() - start:.0f}"), flush=True)


def speed_wrap_map() -> None:
    tape = TapeParameters()
    print(_row("wrap (°)", "V (m/s)", "grid", "h_c (µm)", "h_min (µm)", "contact nodes",
               "Newton iterations", "pseudo-time steps", "continuation stages", "s"))
    for wrap in (5.0, 15.0, 30.0):
        for velocity in (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0):
            start = time.perf_counter()
            model = BearingModel(tape, velocity=velocity, wrap_angle=math.radians(wrap))
            sol = solve_steady(model)
            print(_row(f"{wrap:g}", f"{velocity:g}", f"{model.nx} × {model.ny}",
                       f"{sol.central_spacing * 1e6:.3f}", f"{sol.minimum_spacing * 1e6:.4f}",
                       sol.contact_nodes, sol.info.iterations, len(sol.info.pseudo_time),
                       len(sol.info.continuation), f"{time.perf_counter() - start:.1f}"),
                  flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study", choices=("paper-grid", "variants", "map"))
    study = parser.parse_args().study
    {"paper-grid": paper_grid, "variants": variants, "map": speed_wrap_map}[study]()


if __name__ == "__main__":
    main()
