"""Benchmark of the Newmark marcher: factor, whole-run and per-step times, and the floor.

The floor of the method is one forward/back substitution per step with the factor of
K_eq; the per-step time divided by a bare substitution (same factor, same vector length)
says how much the predictors, right-hand side, correctors and recorders add. Target: <= 1.3.

The paper's load sits at mid-width, so by default the march moves only the mirror-symmetric
half (:mod:`gyroshell.engines.newmark`, module notes); the last table times, in alternating
rounds, the full-size step (``symmetry=False``), the half-size step and the bare full-size
substitution. Target: half step <= 0.55 x the full-size bare substitution.

Cases: the paper's run (L_x/L_y = 4 on the Table 1 grid, 250 steps of 2 µs, "about 20
minutes" on its workstation) and L_x/L_y = 19, 500 steps. Every installed LU back-end is
timed; all figures are medians of repeated runs. Usage::

    PYTHONPATH=. python benchmarks/bench_newmark.py [--repeats 5] [--quick] [--orderings]

``--orderings`` prints only the table behind :mod:`gyroshell.linalg.ordering`: for K_eq
of the symmetric halves and the full grids (Table 1 spacing, L_x/L_y = 4 and 19, free and
simply supported edges, and two other spacings), the fill and the CPU time of one
substitution (one BLAS thread, medians of alternating solves) for SuperLU in each ordering
and for LAPACK's banded LU, against minimum degree; CPU time, not wall time, so that other
jobs on a shared machine disturb it less.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from contextlib import nullcontext
from functools import partial

import numpy as np

from gyroshell import TapeModel, TapeParameters
from gyroshell.engines.newmark import Newmark
from gyroshell.linalg.factorization import available_backends

VELOCITY = 50.0  # m/s
DT = 2e-6  # s, Table 1


def median_time(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def blas_one_thread():
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return nullcontext()
    return threadpool_limits(limits=1, user_api="blas")


def bench_backend(model: TapeModel, steps: int, backend: str, repeats: int) -> dict:
    """Medians for one back-end: factor, whole run, per step, bare solve, their ratio.

    The whole run is construction (assembly + factor) plus the march. The per-step time is
    the march's loop time / steps; after each march a burst of bare substitutions with the
    same factor is timed under the same conditions (one BLAS thread), so that a change in
    the machine's load shifts both alike.
    """
    rhs = np.random.default_rng(0).standard_normal(model.unknowns)
    whole, per_step, factor, bare = [], [], [], []
    for _ in range(repeats):
        start = time.perf_counter()
        stepper = Newmark(model, VELOCITY, dt=DT, backend=backend)
        result = stepper.march(steps, progress=False, symmetry=False)
        whole.append(time.perf_counter() - start)
        per_step.append(result.info["step_time"])
        factor.append(result.info["factor_time"])
        with blas_one_thread():
            bare.append(median_time(partial(stepper.factor.solve, rhs), 21))
    step, solve = statistics.median(per_step), statistics.median(bare)
    return {"backend": backend, "factor": statistics.median(factor),
            "whole": statistics.median(whole), "step": step, "bare": solve,
            "ratio": step / solve}


def bench_blas_threads(model: TapeModel, steps: int, repeats: int) -> tuple[float, float]:
    """Per-step time (s) with BLAS left alone and held to one thread (default back-end)."""
    out = []
    for threads in (None, 1):
        stepper = Newmark(model, VELOCITY, dt=DT, blas_threads=threads)
        out.append(statistics.median(
            stepper.march(steps, progress=False, symmetry=False).info["step_time"]
            for _ in range(repeats)))
    return out[0], out[1]


def bench_mirror(model: TapeModel, steps: int, repeats: int) -> dict:
    """Medians over alternating rounds (s): the full-size step, the half-size step, and bare
    substitutions of the full and the half factor (one BLAS thread), with the factor times.

    Each round marches full size, then the half, then times both bare substitutions, so a
    change in the machine's load shifts all four alike.
    """
    stepper = Newmark(model, VELOCITY, dt=DT)
    full_run = stepper.march(steps, progress=False, symmetry=False)
    half_run = stepper.march(steps, progress=False)
    assert half_run.info["symmetry"] == "half", "the paper's load should march the half"
    half_factor = stepper.half_factor
    rng = np.random.default_rng(0)
    rhs_full = rng.standard_normal(model.unknowns)
    rhs_half = rng.standard_normal(half_run.info["marched_unknowns"])
    rounds: dict[str, list[float]] = {"full": [], "half": [], "bare": [], "bare_half": []}
    for _ in range(repeats):
        rounds["full"].append(stepper.march(steps, progress=False, symmetry=False
                                            ).info["step_time"])
        rounds["half"].append(stepper.march(steps, progress=False).info["step_time"])
        with blas_one_thread():
            rounds["bare"].append(median_time(partial(stepper.factor.solve, rhs_full), 21))
            rounds["bare_half"].append(median_time(partial(half_factor.solve, rhs_half), 21))
    out = {k: statistics.median(v) for k, v in rounds.items()}
    out.update(factor_full=full_run.info["factor_time"],
               factor_half=half_run.info["factor_time"],
               unknowns=model.unknowns, half_unknowns=half_run.info["marched_unknowns"],
               difference=float(np.abs(half_run.load_point - full_run.load_point).max()
                                / np.abs(full_run.load_point).max()))
    return out


def print_mirror(r: dict) -> None:
    print(f"  mirror half ({r['half_unknowns']} of {r['unknowns']} unknowns; factor "
          f"{r['factor_half']:.3f} s vs {r['factor_full']:.3f} s; load-point history "
          f"equal to {r['difference']:.1e} relative):")
    print(f"    bare full substitution {1e3 * r['bare']:8.3f} ms")
    print(f"    full-size step         {1e3 * r['full']:8.3f} ms  "
          f"({r['full'] / r['bare']:.2f}x the bare full substitution)")
    print(f"    half-size step         {1e3 * r['half']:8.3f} ms  "
          f"({r['half'] / r['bare']:.2f}x the bare full substitution, target <= 0.55; "
          f"{r['half'] / r['full']:.2f}x the full step)")
    print(f"    bare half substitution {1e3 * r['bare_half']:8.3f} ms  "
          f"(half step / bare half {r['half'] / r['bare_half']:.2f})")


#: K_eq cases of the ordering table: (L_x/L_y, intervals across, half or full, edges).
ORDERING_CASES = ((19, 41, "half", "free"), (4, 41, "half", "free"),
                  (19, 41, "half", "simply-supported"), (19, 12, "full", "free"),
                  (19, 27, "full", "free"), (19, 41, "full", "free"), (4, 41, "full", "free"))


def keq(model: TapeModel, half: bool):
    """K_eq = M + γΔt G + βΔt² K at VELOCITY, DT, β = 1/4, γ = 1/2, full or on the half."""
    import scipy.sparse as sp

    from gyroshell.tape.mirror import mirror_split

    if half:
        M, G, K = mirror_split(model).matrices(model, VELOCITY, "symmetric")
        m = M.diagonal()
    else:
        K, G, m = model.K(VELOCITY), model.G(VELOCITY), model.mass_diagonal
    return (sp.diags(m) + (0.5 * DT) * G + (0.25 * DT * DT) * K).tocsc()


def bench_orderings(repeats: int) -> None:
    """The ordering table (module notes): fill and CPU time per substitution."""
    from gyroshell.linalg.factorization import BandedFactor, SuperLUFactor
    from gyroshell.linalg.ordering import column_ordering, half_bandwidth

    orders = ("MMD_AT_PLUS_A", "NATURAL", "COLAMD")
    print(f"  {'K_eq':34s} {'n':>6s} {'band':>5s} {'rule':>8s} "
          + "".join(f"{o[:8]:>18s}" for o in orders) + f"{'LAPACK band':>18s}")
    for ratio, across, which, edges in ORDERING_CASES:
        p = TapeParameters(length_ratio=ratio, edges=edges)
        A = keq(TapeModel(p.replace(spacing=p.width / across)), which == "half")
        rhs = np.random.default_rng(0).standard_normal(A.shape[0])
        with blas_one_thread():
            factors = [SuperLUFactor(A, ordering=o) for o in orders] + [BandedFactor(A)]
            cpu: list[list[float]] = [[] for _ in factors]
            for _ in range(5 * repeats):
                for k, f in enumerate(factors):
                    start = time.process_time()
                    f.solve(rhs)
                    cpu[k].append(time.process_time() - start)
        t = [statistics.median(c) for c in cpu]
        nnz = [f.nnz for f in factors]
        rule = column_ordering(A)[:8]
        name = f"L{ratio:g}, {across} across, {which}, {edges}"
        print(f"  {name:34s} {A.shape[0]:6d} {half_bandwidth(A):5d} {rule:>8s} "
              + "".join(f"{n / nnz[0]:5.2f} fill {t[k] / t[0]:4.2f}x"
                        for k, n in enumerate(nnz)) + f"   (min. degree {1e3 * t[0]:.2f} ms)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="runs per figure (median)")
    parser.add_argument("--quick", action="store_true", help="fewer steps, for a smoke test")
    parser.add_argument("--orderings", action="store_true",
                        help="only the table of SuperLU orderings on K_eq")
    args = parser.parse_args()
    if args.orderings:
        print(f"load average {os.getloadavg()[0]:.2f}; V = {VELOCITY:g} m/s, dt = {DT:g} s; "
              "fill and CPU time of one substitution against minimum degree")
        bench_orderings(args.repeats)
        return
    cases = [(4.0, 250), (19.0, 500)]
    if args.quick:
        cases = [(4.0, 25), (19.0, 25)]
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; "
          f"V = {VELOCITY:g} m/s, dt = {DT:g} s, beta = 1/4, gamma = 1/2, "
          f"medians of {args.repeats} runs; back-ends: {', '.join(available_backends())}")
    for ratio, steps in cases:
        model = TapeModel(TapeParameters(length_ratio=ratio))
        Newmark(model, VELOCITY, dt=DT).march(min(steps, 50), progress=False,
                                              symmetry=False)  # warm-up
        g = model.grid
        print(f"\nL_x/L_y = {ratio:g}: {g.nx} x {g.ny} intervals, {g.unknowns} unknowns, "
              f"{steps} steps")
        print(f"  {'back-end':9s} {'factor s':>9s} {'whole run s':>12s} {'per step ms':>12s} "
              f"{'bare solve ms':>14s} {'step/solve':>11s}")
        for backend in available_backends():
            r = bench_backend(model, steps, backend, args.repeats)
            print(f"  {r['backend']:9s} {r['factor']:9.3f} {r['whole']:12.3f} "
                  f"{1e3 * r['step']:12.3f} {1e3 * r['bare']:14.3f} {r['ratio']:11.2f}")
        free, one = bench_blas_threads(model, steps, max(3, args.repeats // 2))
        print(f"  BLAS threads (default back-end): as found {1e3 * free:.3f} ms/step, "
              f"held to one {1e3 * one:.3f} ms/step ({free / one:.2f}x)")
        print_mirror(bench_mirror(model, steps, args.repeats))


if __name__ == "__main__":
    main()
