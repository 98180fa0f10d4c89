"""Benchmark the steady air-bearing solves (Table 1 tape, V = 4 m/s, 15° wrap, air at 20 °C).

    PYTHONPATH=. python benchmarks/bench_bearing.py [--rounds 3] [--width 12.65e-3]
        [--uniform] [--baseline DIR] [--backends [grid,metis,mmd,colamd,pardiso]]

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

``--backends`` instead compares the Jacobian's factorizations (``factorization=`` of
BearingModel; those installed), in alternating rounds on the 2-D tape: per back-end the
whole solve (median), its Newton iterations and factorizations, one factorization and
one substitution of the folded Jacobian at the converged state (the nested dissection of
"grid" and "metis" timed apart: it is computed once per grid; their LU in the precision
Newton uses and in double), the fill of L + U, the relative backward
error, and the largest state difference from SuperLU with partial pivoting ("colamd",
the earlier default), relative to max|u| and max|p − p_a|.
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
from gyroshell.bearing import AirParameters, BearingModel, steady
from gyroshell.bearing.jacobian import JacobianPattern
from gyroshell.bearing.steady import _PATTERNS, _Residual, pattern_ordering, solve_steady
from gyroshell.core.parallel import blas_threads
from gyroshell.linalg.factorization import (
    DiagonalPivotLU,
    PardisoFactor,
    SuperLUFactor,
    metis_available,
    resolve_pattern_lu,
)


def folded_jacobian(model: BearingModel, z: np.ndarray):
    """The folded 2-D Jacobian at the state z, as Newton factors it."""
    F = _Residual(model, None, None)
    J = F(z, jacobian=True)[2].matrix
    P, rows = model.mirror
    return F, (J[rows, :] @ P).tocsc()


def one_factorization(model: BearingModel, z: np.ndarray, backend: str) -> dict:
    """Seconds of one factorization and one substitution of the folded Jacobian at z by
    ``backend``, its fill (L + U entries, where the back-end tells) and backward error.
    "grid" and "metis": the ordering timed apart (computed once per grid), the LU in the
    precision Newton uses (``steady.SINGLE_LU``) and, for comparison, in double."""
    F, J = folded_jacobian(model, z)
    rhs = np.random.default_rng(0).standard_normal(J.shape[0])
    out = {"ordering": 0.0, "double": float("nan")}
    kind = resolve_pattern_lu(backend)
    if kind in ("grid", "metis"):
        _, active, lin = F(z, jacobian=True)
        pattern = JacobianPattern(F.tape_rows, lin.J_h, lin.J_p, model.nc, model.mirror)
        start = time.perf_counter()
        pattern.order(pattern_ordering(pattern, model, kind))
        out["ordering"] = time.perf_counter() - start
        J = pattern.matrix(F.tape_rows.data, active, F.c, lin.J_h, lin.J_p)
        start = time.perf_counter()
        DiagonalPivotLU(J, ordered=True)
        out["double"] = time.perf_counter() - start
    start = time.perf_counter()
    if kind in ("grid", "metis"):
        lu = DiagonalPivotLU(J, ordered=True, single=steady.SINGLE_LU)
        fill = lu._lu.nnz
    elif kind == "mmd":
        lu = DiagonalPivotLU(J)
        fill = lu._lu.nnz
    elif kind == "pardiso":
        lu = PardisoFactor(J)
        fill = int(lu._solver.iparm[17])
    else:
        lu = SuperLUFactor(J, ordering="COLAMD")
        fill = lu._lu.nnz
    out["factor"] = time.perf_counter() - start
    start = time.perf_counter()
    x = lu.solve(rhs)
    out["solve"] = time.perf_counter() - start
    out["fill"] = fill
    scale = np.max(abs(J) @ np.abs(x) + np.abs(rhs))
    out["backward error"] = float(np.max(np.abs(J @ x - rhs)) / scale)
    return out


def compare_backends(args, wrap: float) -> int:
    """The ``--backends`` comparison (module notes)."""
    names = [b for b in args.backends.split(",") if b]
    installed = [b for b in names if b not in ("metis", "pardiso")
                 or (metis_available() if b == "metis" else PardisoFactor.available())]
    for b in set(names) - set(installed):
        print(f"{b}: not installed, skipped")
    if "colamd" not in installed:
        installed.append("colamd")
    models = {b: BearingModel(TapeParameters(width=args.width), AirParameters(),
                              velocity=4.0, wrap_angle=wrap, factorization=b)
              for b in installed}
    m = models["colamd"]
    print(f"2-D: {m!r}, {m.unknowns} unknowns ({len(m.mirror[1])} solved, half width)")
    times = {b: [] for b in installed}
    parts = {b: [] for b in installed}
    sols, counts = {}, {}
    with blas_threads(1):
        for r in range(args.rounds):
            for b in (installed if r % 2 == 0 else installed[::-1]):
                calls = []
                original = _Residual.factor

                def counted(self, J, _calls=calls, _original=original):
                    start = time.perf_counter()
                    solver = _original(self, J)
                    _calls.append(time.perf_counter() - start)
                    return solver
                _Residual.factor = counted
                _PATTERNS.clear()           # each solve orders its grids afresh
                models[b].jacobian_patterns.clear()
                try:
                    start = time.perf_counter()
                    sols[b] = solve_steady(models[b])
                    times[b].append(time.perf_counter() - start)
                finally:
                    _Residual.factor = original
                counts.setdefault(b, []).append((sols[b].info.iterations, len(calls),
                                                 sum(calls)))
            z = np.concatenate([sols["colamd"].u, sols["colamd"].p])
            for b in installed:
                parts[b].append(one_factorization(m, z, b))
            print(f"round {r + 1}: " + ", ".join(f"{b} {times[b][-1]:.3f} s"
                                                 for b in installed), flush=True)
    ref = sols["colamd"]
    pa = m.air.ambient_pressure
    u_scale, p_scale = np.max(np.abs(ref.u)), np.max(np.abs(ref.p - pa))
    base = statistics.median(times["colamd"])
    print(f"\nmedians over {args.rounds} alternating rounds (s; 'in LUs': the solve's "
          "factorizations together, 'order' the nested dissection once (grid, metis); "
          "one LU (grid and metis: single precision if steady.SINGLE_LU, 'f64' the same "
          "LU in double) and one "
          "substitution of the folded Jacobian at the converged state):")
    print(f"  {'back-end':9s} {'solve':>7s} {'x colamd':>8s} {'iters':>5s} {'LUs':>4s} "
          f"{'in LUs':>7s} {'order':>6s} {'one LU':>7s} {'f64':>6s} {'subst':>6s} {'fill':>7s} "
          f"{'bwd err':>8s} {'du/u':>8s} {'dp/p':>8s}")
    for b in installed:
        med = {k: statistics.median(p[k] for p in parts[b]) for k in parts[b][0]}
        t = statistics.median(times[b])
        its, lus = counts[b][-1][:2]
        in_lus = statistics.median(c[2] for c in counts[b])
        du = np.max(np.abs(sols[b].u - ref.u)) / u_scale
        dp = np.max(np.abs(sols[b].p - ref.p)) / p_scale
        print(f"  {b:9s} {t:7.3f} {t / base:8.2f} {its:5d} {lus:4d} {in_lus:7.3f} "
              f"{med['ordering']:6.3f} {med['factor']:7.3f} {med['double']:6.3f} "
              f"{med['solve']:6.3f} "
              f"{med['fill'] / 1e6:6.1f}M {med['backward error']:8.1e} {du:8.1e} {dp:8.1e}")
    return 0


def one_lu(model: BearingModel) -> float:
    """Seconds for one factorization of the folded 2-D Jacobian at Newton's start."""
    F = _Residual(model, None, None)
    J = F(model.initial_state(), jacobian=True)[2].matrix
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
    parser.add_argument("--backends", nargs="?", const="grid,metis,mmd,colamd,pardiso",
                        default=None, metavar="LIST",
                        help="compare the Jacobian's factorizations (comma-separated)")
    args = parser.parse_args(argv)
    wrap = math.radians(15.0)
    if args.backends is not None:
        return compare_backends(args, wrap)
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
