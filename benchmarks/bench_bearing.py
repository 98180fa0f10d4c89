"""Benchmark the steady air-bearing solves (Table 1 tape, V = 4 m/s, 15° wrap, air at 20 °C).

    PYTHONPATH=. python benchmarks/bench_bearing.py [--rounds 3] [--width 12.65e-3]
        [--uniform] [--baseline DIR]

Prints medians (s) over alternating rounds of:

* the infinitely wide (1-D) steady solve on its default grid;
* the 2-D steady solve of a ``--width`` wide tape on its default grid (graded towards the
  free edges and the wrap corners; its counts and finest spacings are printed);
* with ``--uniform``, the same tape on the uniform grid of the earlier default (about 30 µm
  along, 50 µm across), in the same rounds;

with Newton's iteration counts, and as a same-run baseline one sparse LU of the 2-D
coupled Jacobian (half width, as Newton factors it). ``--baseline DIR`` also times, in the
same alternating rounds, the 2-D solve of another source tree (e.g. an older commit
unpacked with ``git archive <commit> | tar -x -C DIR``) in a subprocess, and prints the
median ratio old/new. Timings on a shared machine vary: read the medians.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np
import scipy.sparse.linalg as spla

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.steady import _Residual, solve_steady
from gyroshell.core.parallel import blas_threads


def one_lu(model: BearingModel) -> float:
    """Seconds for one factorization of the folded 2-D Jacobian at Newton's start."""
    F = _Residual(model, None, None)
    _, _, J = F(model.initial_state(), jacobian=True)
    P, rows = model.mirror
    Jh = (J[rows, :] @ P).tocsc()
    start = time.perf_counter()
    spla.splu(Jh, permc_spec="COLAMD")
    return time.perf_counter() - start


_BASELINE = """
import math, time
from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.steady import solve_steady
from gyroshell.core.parallel import blas_threads
m = BearingModel(TapeParameters(width={width!r}), AirParameters(), velocity=4.0,
                 wrap_angle=math.radians(15.0))
with blas_threads(1):
    t = time.perf_counter()
    s = solve_steady(m)
    print(time.perf_counter() - t, s.info.iterations, s.central_spacing, s.minimum_spacing)
"""


def baseline_2d(source: str, width: float) -> tuple[float, int, float, float]:
    """(seconds, iterations, h_c, h_min) of the 2-D solve by the code under ``source``."""
    env = {**os.environ, "PYTHONPATH": source}
    out = subprocess.run([sys.executable, "-c", _BASELINE.format(width=width)], env=env,
                         cwd=source, capture_output=True, text=True, check=True).stdout
    t, its, hc, hmin = out.split()
    return float(t), int(its), float(hc), float(hmin)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--width", type=float, default=12.65e-3, help="2-D tape width, m")
    parser.add_argument("--uniform", action="store_true",
                        help="also time the uniform grid (the earlier default)")
    parser.add_argument("--baseline", metavar="DIR",
                        help="source tree whose 2-D solve is timed alongside (subprocess)")
    args = parser.parse_args(argv)
    wrap = math.radians(15.0)
    strip = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, wrap_angle=wrap,
                         infinitely_wide=True)
    plate = BearingModel(TapeParameters(width=args.width), AirParameters(), velocity=4.0,
                         wrap_angle=wrap)
    uniform = (BearingModel(TapeParameters(width=args.width), AirParameters(), velocity=4.0,
                            wrap_angle=wrap, grading="uniform") if args.uniform else None)
    print(f"1-D: {strip!r}, {strip.unknowns} unknowns")
    for name, m in (("2-D", plate), ("2-D uniform", uniform)):
        if m is not None:
            print(f"{name}: {m!r}, {m.unknowns} unknowns ({len(m.mirror[1])} solved, half "
                  f"width); spacing {1e6 * np.diff(m.x).min():.1f}-"
                  f"{1e6 * np.diff(m.x).max():.1f} um along, "
                  f"{1e6 * np.diff(m.y).min():.1f}-{1e6 * np.diff(m.y).max():.1f} um across")
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
            if uniform is not None:
                start = time.perf_counter()
                s3 = solve_steady(uniform)
                times.setdefault("2-D uniform", []).append(time.perf_counter() - start)
            if args.baseline:
                t_old, its_old, hc_old, hmin_old = baseline_2d(args.baseline, args.width)
                times.setdefault("2-D baseline", []).append(t_old)
                times.setdefault("ratio", []).append(t_old / times["2-D steady"][-1])
            its = {"1-D steady": s1.info.iterations, "2-D steady": s2.info.iterations}
            if uniform is not None:
                its["2-D uniform"] = s3.info.iterations
            print(f"round {r + 1}: " + ", ".join(
                f"{k} {v[-1]:.3f}" + ("" if k == "ratio" else " s") for k, v in times.items()),
                flush=True)
    med = {k: statistics.median(v) for k, v in times.items()}
    print("\nmedians over", args.rounds, "rounds:")
    for k, v in med.items():
        extra = f" ({its[k]} Newton iterations)" if k in its else ""
        unit = "" if k == "ratio" else " s"
        print(f"  {k:12s} {v:8.3f}{unit}{extra}")
    print(f"  2-D steady / one LU = {med['2-D steady'] / med['2-D one LU']:.1f}")
    if args.baseline:
        print(f"  baseline: {its_old} Newton iterations, h_c = {hc_old:.5e} m, "
              f"h_min = {hmin_old:.5e} m; median ratio baseline/new {med['ratio']:.2f}")
    print(f"\n1-D: h_c = {s1.central_spacing:.5e} m, h_min = {s1.minimum_spacing:.5e} m")
    print(f"2-D: h_c = {s2.central_spacing:.5e} m, h_min = {s2.minimum_spacing:.5e} m at "
          f"{s2.minimum_location}, contact nodes {s2.contact_nodes}")
    if uniform is not None:
        print(f"2-D uniform: h_c = {s3.central_spacing:.5e} m, h_min = "
              f"{s3.minimum_spacing:.5e} m at {s3.minimum_location}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
