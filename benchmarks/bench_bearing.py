"""Benchmark the steady air-bearing solves (Table 1 tape, V = 4 m/s, 15° wrap, air at 20 °C).

    PYTHONPATH=. python benchmarks/bench_bearing.py [--rounds 3] [--width 12.65e-3]

Prints medians (s) over alternating rounds of:

* the infinitely wide (1-D) steady solve on its default grid;
* the 2-D steady solve of a ``--width`` wide tape on its default grid;

with Newton's iteration counts, and as a same-run baseline one sparse LU of the 2-D
coupled Jacobian (half width, as Newton factors it): the 2-D solve costs about
"iterations × LU". Timings on a shared machine vary: read the medians.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import scipy.sparse.linalg as spla

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.steady import _Residual, solve_steady
from gyroshell.threads import blas_threads


def one_lu(model: BearingModel) -> float:
    """Seconds for one factorization of the folded 2-D Jacobian at Newton's start."""
    F = _Residual(model, None, None)
    _, _, J = F(model.initial_state(), jacobian=True)
    P, rows = model.mirror
    Jh = (J[rows, :] @ P).tocsc()
    start = time.perf_counter()
    spla.splu(Jh, permc_spec="COLAMD")
    return time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--width", type=float, default=12.65e-3, help="2-D tape width, m")
    args = parser.parse_args(argv)
    wrap = math.radians(15.0)
    strip = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, wrap_angle=wrap,
                         infinitely_wide=True)
    plate = BearingModel(TapeParameters(width=args.width), AirParameters(), velocity=4.0,
                         wrap_angle=wrap)
    print(f"1-D: {strip!r}, {strip.size} unknowns")
    print(f"2-D: {plate!r}, {plate.size} unknowns ({plate.size // 2 + plate.nx} solved, "
          "half width)")
    times = {"1-D steady": [], "2-D steady": [], "2-D one LU": []}
    its = {}
    with blas_threads(1):
        solve_steady(strip)                                     # warm-up
        for r in range(args.rounds):
            start = time.perf_counter()
            s1 = solve_steady(strip)
            times["1-D steady"].append(time.perf_counter() - start)
            start = time.perf_counter()
            s2 = solve_steady(plate)
            times["2-D steady"].append(time.perf_counter() - start)
            times["2-D one LU"].append(one_lu(plate))
            its = {"1-D steady": s1.info.iterations, "2-D steady": s2.info.iterations}
            print(f"round {r + 1}: " + ", ".join(f"{k} {v[-1]:.3f} s" for k, v in times.items()),
                  flush=True)
    med = {k: statistics.median(v) for k, v in times.items()}
    print("\nmedians over", args.rounds, "rounds:")
    for k, v in med.items():
        extra = f" ({its[k]} Newton iterations)" if k in its else ""
        print(f"  {k:12s} {v:8.3f} s{extra}")
    print(f"  2-D steady / one LU = {med['2-D steady'] / med['2-D one LU']:.1f}")
    print(f"\n1-D: h_c = {s1.central_spacing:.5e} m, h_min = {s1.minimum_spacing:.5e} m")
    print(f"2-D: h_c = {s2.central_spacing:.5e} m, h_min = {s2.minimum_spacing:.5e} m at "
          f"{s2.minimum_location}, contact nodes {s2.contact_nodes}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
