"""Benchmark the steady air bearing over a flat head against the cylinder, same tape, same run.

    PYTHONPATH=. python benchmarks/bench_heads.py [--rounds 3] [--width 12.65e-3] [--no-2d]
        [--corner-radius 5e-6] [--low-speed]

The Table 1 tape at V = 4 m/s, air at 20 °C. Prints medians (s) over alternating rounds
(one BLAS thread) of:

* the 1-D (infinitely wide) steady solve over a flat module (land 1 mm, sharp corners,
  2° of wrap either side, a transducer in the middle) on its default grid, and of the same
  tape over the cylinder of its radius (15° wrap) on its default grid: the baseline;
* the 2-D steady solve of a ``--width`` wide tape over the same flat module, and over the
  cylinder, each on its default grid (the starting state included, as the CLI runs it);
* the same 1-D and 2-D solves over the module with rounded corners (``--corner-radius``,
  5 µm by default: the contacts adapted by regridding, ``gyroshell.bearing.corners``);

with Newton's iteration counts (every grid of the coarse-grid start and every pass of the
rounded corners included; the fine grid's own in brackets), the grids, the median ratios
flat / cylinder and rounded / sharp of each.
``--low-speed`` adds the 1-D solves of a 3 mm land at 4°/4° at 0.3, 0.5 and 1 m/s on their
default grids (the continuation up from the dry tape included; before it they failed after
~90 s, so there is no baseline to divide by).
Timings on a shared machine vary: read the medians.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import Cylinder, FlatHead, Module
from gyroshell.bearing.steady import initial_state, solve_steady
from gyroshell.core.parallel import blas_threads

VELOCITY = 4.0
FLAT = FlatHead((Module(1e-3),), math.radians(2.0), math.radians(2.0), transducers=(0.0,))
CYLINDER = Cylinder(math.radians(15.0))
LONG = FlatHead((Module(3e-3),), math.radians(4.0), math.radians(4.0), transducers=(0.0,))
LOW_SPEEDS = (0.3, 0.5, 1.0)


def rounded(radius: float) -> FlatHead:
    """The flat module with both corners rounded to ``radius``, m."""
    return FlatHead((Module(1e-3, corner_radius=radius),), math.radians(2.0),
                    math.radians(2.0), transducers=(0.0,))


class Counted:
    """Newton's iterations over every grid a solve touches (the coarse-grid starts, each
    rounded-corner pass), counted from the iteration log."""

    def __init__(self) -> None:
        self.count = 0

    def __call__(self, message: str) -> None:
        self.count += 1


def timed(model: BearingModel):
    """(seconds, solution, all Newton iterations) of one steady solve as the CLI runs it
    (a sharp head from :func:`initial_state`; rounded corners from their own start)."""
    log = Counted()
    start = time.perf_counter()
    z0 = None if model.corner_contacts else initial_state(model, iteration_log=log)
    sol = solve_steady(model, z0=z0, iteration_log=log)
    return time.perf_counter() - start, sol, log.count


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--width", type=float, default=12.65e-3, help="2-D tape width, m")
    parser.add_argument("--no-2d", action="store_true", help="the 1-D solves only")
    parser.add_argument("--corner-radius", type=float, default=5e-6,
                        help="the rounded corners' radius, m (0: no rounded solves)")
    parser.add_argument("--low-speed", action="store_true",
                        help="add a 3 mm land at 4 deg/4 deg at 0.3, 0.5, 1 m/s (1-D)")
    args = parser.parse_args(argv)
    air = AirParameters()
    models = {}
    heads = [("flat", FLAT), ("cylinder", CYLINDER)]
    if args.corner_radius > 0.0:
        heads.append(("rounded", rounded(args.corner_radius)))
    for name, head in heads:
        models[f"1-D {name}"] = BearingModel(TapeParameters(), air, velocity=VELOCITY,
                                             head=head, infinitely_wide=True)
        if not args.no_2d:
            models[f"2-D {name}"] = BearingModel(TapeParameters(width=args.width), air,
                                                 velocity=VELOCITY, head=head)
    if args.low_speed:
        for v in LOW_SPEEDS:
            models[f"1-D 3mm {v:g}"] = BearingModel(TapeParameters(), air, velocity=v,
                                                    head=LONG, infinitely_wide=True)
    for name, m in models.items():
        grid = f"nx = {m.nx}" + ("" if m.infinitely_wide else f", ny = {m.ny}")
        print(f"{name}: {grid}, {m.unknowns} unknowns")
    times: dict[str, list[float]] = {name: [] for name in models}
    sols, counts = {}, {}
    with blas_threads(1):
        timed(models["1-D flat"])                                   # warm-up
        for r in range(args.rounds):
            for name, m in models.items():
                t, sols[name], counts[name] = timed(m)
                times[name].append(t)
            print(f"round {r + 1}: " + ", ".join(f"{k} {v[-1]:.3f} s"
                                                for k, v in times.items()), flush=True)
    med = {k: statistics.median(v) for k, v in times.items()}
    print(f"\nmedians over {args.rounds} rounds:")
    for name, v in med.items():
        passes = getattr(sols[name].info, "contact_passes", None)
        extra = "" if passes is None else f", {passes} contact passes"
        print(f"  {name:13s} {v:8.3f} s ({counts[name]} Newton iterations "
              f"[{sols[name].info.iterations}]{extra})")
    for dim in ("1-D", "2-D"):
        if f"{dim} flat" in med:
            print(f"  {dim} flat / cylinder = {med[f'{dim} flat'] / med[f'{dim} cylinder']:.2f}")
        if f"{dim} rounded" in med:
            print(f"  {dim} rounded / sharp = {med[f'{dim} rounded'] / med[f'{dim} flat']:.2f}")
    print()
    for name, sol in sols.items():
        lines = "".join(f", read line min {line.minimum:.4e} m, mean {line.mean:.4e} m"
                        for line in sol.transducer_lines)
        print(f"{name}: h_c = {sol.central_spacing:.4e} m, h_min = "
              f"{sol.minimum_spacing:.4e} m{lines}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
