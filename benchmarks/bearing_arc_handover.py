"""The rounded corners' handover at speed: point contact vs wrapped arc.

1 mm land, 2°/2°, the default (Table 1) tape, 4 m/s, infinitely wide: r_c = 1.4 mm
(r_c θ_c = 0.27 ℓ_bend, auto picks the point contact) and 1.7 mm (0.33 ℓ_bend, auto wraps
it), both models forced, on the default grid times 1, 2, 4 (``--factors``). Prints per
case h(0), the contact force on each half of the head (N/m: the corners'), the Newton
iterations and the wall time (one run each: a measurement of accuracy, not a timing).

Run: ``PYTHONPATH=. python benchmarks/bearing_arc_handover.py [--factors 1 2 4]``.
"""

from __future__ import annotations

import argparse
import math
import time

from gyroshell import ConvergenceError, TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import solve_steady

DEG = math.pi / 180.0


def _case(radius: float, mode: str, factor: int, velocity: float):
    head = FlatHead((Module(1e-3, corner_radius=radius),), 2 * DEG, 2 * DEG,
                    transducers=(0.0,))
    base = BearingModel(TapeParameters(), AirParameters(), velocity=velocity, head=head,
                        infinitely_wide=True, arc_contact=mode)
    model = base if factor == 1 else base.rebuilt(nx=factor * base.nx)
    t0 = time.perf_counter()
    sol = solve_steady(model)
    wall = time.perf_counter() - t0
    inner = model.x_head[1:-1]   # the contact on each half (the corner zones' readings
    forces = [float(sol.contact[inner < 0].sum()),    # miss a contact near the arc's end)
              float(sol.contact[inner > 0].sum())]
    return model.nx, sol.central_spacing, forces, sol.info.iterations, wall


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--factors", type=int, nargs="+", default=[1, 2, 4])
    ap.add_argument("--radii", type=float, nargs="+", default=[1.4e-3, 1.7e-3])
    ap.add_argument("--models", nargs="+", default=["point", "wrapped"])
    ap.add_argument("--velocity", type=float, default=4.0)
    args = ap.parse_args()
    print(f"{'r_c mm':>7} {'model':>8} {'x':>2} {'nx':>6} {'h(0) nm':>10} "
          f"{'F_lead N/m':>12} {'F_trail N/m':>12} {'iters':>6} {'wall s':>7}")
    for r in args.radii:
        for mode in args.models:
            for f in args.factors:
                try:
                    nx, h0, force, its, wall = _case(r, mode, f, args.velocity)
                except ConvergenceError as exc:
                    print(f"{r * 1e3:7.2f} {mode:>8} {f:2d} failed: {exc}", flush=True)
                    continue
                print(f"{r * 1e3:7.2f} {mode:>8} {f:2d} {nx:6d} {h0 * 1e9:10.4f} "
                      f"{force[0]:12.6f} {force[-1]:12.6f} {its:6d} {wall:7.2f}", flush=True)


if __name__ == "__main__":
    main()
