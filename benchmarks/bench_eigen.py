"""Benchmark the quadratic eigen-solver and the critical speed on the L_x/L_y = 19 grid.

    PYTHONPATH=. python benchmarks/bench_eigen.py [--repeat 3] [--count 6] [--naive-repeat 1]

Prints medians (s) of:

* ``modes``: the lowest ``count`` frequencies at V = 0 with :func:`gyroshell.eigen.modes`
  (inertia-certified complex shift, one n × n factorization);
* the naive approach: assemble the 2n × 2n linearization [[0, I], [−K, −G]] z = λ diag(I, M) z
  and call ``scipy.sparse.linalg.eigs(k=2·count, sigma=0)`` (scipy factors the 2n pencil);
* ``critical``: both critical-speed routes (a) and (b) with :func:`critical_speeds`.

Timings on a shared machine vary: run with nothing else busy, and read the medians.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from gyroshell import TapeModel, TapeParameters
from gyroshell.critical import critical_speeds
from gyroshell.eigen import modes
from gyroshell.threads import blas_threads


def naive(model: TapeModel, velocity: float, count: int) -> np.ndarray:
    """Lowest ``count`` ω from eigs on the assembled 2n × 2n pencil, sigma = 0, rad/s."""
    n = model.size
    K, G, M = model.K(velocity), model.G(velocity), model.M
    eye = sp.identity(n, format="csr")
    A = sp.bmat([[None, eye], [-K, -G]], format="csc")
    B = sp.bmat([[eye, None], [None, M]], format="csc")
    with blas_threads(1):  # the same BLAS setting as the solver, for a fair race
        lam = spla.eigs(A, k=2 * count, M=B, sigma=0.0, which="LM",
                        return_eigenvectors=False)
    w = np.sort(np.abs(lam.imag))
    return w[::2][:count]


def timed(fn, repeat: int):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), times, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--naive-repeat", type=int, default=1)
    ap.add_argument("--count", type=int, default=6)
    ap.add_argument("--length-ratio", type=float, default=19.0)
    args = ap.parse_args()

    model = TapeModel(TapeParameters(length_ratio=args.length_ratio))
    model.A, model.B  # assemble once, outside the timings  # noqa: B018
    n = model.size
    print(f"grid {model.grid.nx} x {model.grid.ny}, n = {n} unknowns, {2 * n} states")

    t_fast, all_fast, res = timed(lambda: modes(model, 0.0, args.count), args.repeat)
    print(f"modes (count={args.count}, V=0):  median {t_fast:.3f} s  "
          f"(runs {', '.join(f'{t:.3f}' for t in all_fast)})")
    print(f"  omega (rad/s): {np.array2string(res.omega, precision=8)}")
    print(f"  max residual {res.residuals.max():.1e}; info: factor "
          f"{res.info['factor_time']:.3f} s, solve {res.info['solve_time']:.3f} s, "
          f"{res.info['operator_applications']} operator applications, ncv {res.info['ncv']}")

    t_naive, all_naive, w = timed(lambda: naive(model, 0.0, args.count), args.naive_repeat)
    print(f"naive 2n x 2n eigs(sigma=0):    median {t_naive:.3f} s  "
          f"(runs {', '.join(f'{t:.3f}' for t in all_naive)})")
    print(f"  omega (rad/s): {np.array2string(w, precision=8)}")
    print(f"  largest relative difference from modes: "
          f"{np.max(np.abs(w - res.omega) / res.omega):.1e}")
    print(f"speed-up: {t_naive / t_fast:.1f}x")

    t_crit, all_crit, c = timed(lambda: critical_speeds(model), args.repeat)
    print(f"critical speed (a) and (b):     median {t_crit:.3f} s  "
          f"(runs {', '.join(f'{t:.3f}' for t in all_crit)})")
    print(f"  (a) {c.critical_speed:.9f} m/s in {c.info['critical_time']:.2f} s, "
          f"{c.info['evaluations']} eigen-solves; (b) {c.divergence_speed:.9f} m/s in "
          f"{c.info['divergence_time']:.2f} s; |a-b|/b = {c.relative_difference:.1e}")


if __name__ == "__main__":
    main()
