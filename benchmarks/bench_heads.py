"""Benchmark the steady air bearing over a flat head against the cylinder, same tape, same run.

    PYTHONPATH=. python benchmarks/bench_heads.py [--rounds 3] [--width 12.65e-3] [--no-2d]
        [--low-speed]

The Table 1 tape at V = 4 m/s, air at 20 °C. Prints medians (s) over alternating rounds
(one BLAS thread) of:

* the 1-D (infinitely wide) steady solve over a flat module (land 1 mm, sharp corners,
  2° of wrap either side, a transducer in the middle) on its default grid, and of the same
  tape over the cylinder of its radius (15° wrap) on its default grid: the baseline;
* the 2-D steady solve of a ``--width`` wide tape over the same flat module, and over the
  cylinder, each on its default grid (the starting state included, as the CLI runs it);

with Newton's iteration counts, the grids, and the median ratio flat / cylinder of each.
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


def timed(model: BearingModel):
    """(seconds, solution) of one steady solve from the CLI's starting state."""
    start = time.perf_counter()
    sol = solve_steady(model, z0=initial_state(model))
    return time.perf_counter() - start, sol


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--width", type=float, default=12.65e-3, help="2-D tape width, m")
    parser.add_argument("--no-2d", action="store_true", help="the 1-D solves only")
    parser.add_argument("--low-speed", action="store_true",
                        help="add a 3 mm land at 4 deg/4 deg at 0.3, 0.5, 1 m/s (1-D)")
    args = parser.parse_args(argv)
    air = AirParameters()
    models = {}
    for name, head in (("flat", FLAT), ("cylinder", CYLINDER)):
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
    sols = {}
    with blas_threads(1):
        timed(models["1-D flat"])                                   # warm-up
        for r in range(args.rounds):
            for name, m in models.items():
                t, sols[name] = timed(m)
                times[name].append(t)
            print(f"round {r + 1}: " + ", ".join(f"{k} {v[-1]:.3f} s"
                                                for k, v in times.items()), flush=True)
    med = {k: statistics.median(v) for k, v in times.items()}
    print(f"\nmedians over {args.rounds} rounds:")
    for name, v in med.items():
        print(f"  {name:13s} {v:8.3f} s ({sols[name].info.iterations} Newton iterations)")
    for dim in ("1-D", "2-D"):
        if f"{dim} flat" in med:
            print(f"  {dim} flat / cylinder = {med[f'{dim} flat'] / med[f'{dim} cylinder']:.2f}")
    print()
    for name, sol in sols.items():
        lines = "".join(f", read line min {line.minimum:.4e} m, mean {line.mean:.4e} m"
                        for line in sol.transducer_lines)
        print(f"{name}: h_c = {sol.central_spacing:.4e} m, h_min = "
              f"{sol.minimum_spacing:.4e} m{lines}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
