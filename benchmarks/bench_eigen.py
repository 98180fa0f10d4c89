"""Benchmark the quadratic eigen-solver, speed sweeps and the critical speed (L_x/L_y = 19).

    PYTHONPATH=. python benchmarks/bench_eigen.py [--rounds 3] [--sweep-rounds 3]

Prints medians (s) over alternating rounds of:

* ``modes`` at V = 50 m/s, 6 modes: gyroshell's default (the mirror-symmetric halves,
  Lanczos on the Hermitian energy pencil, inertia-certified shift, CHOLMOD where cvxopt is
  installed), the full problem with the default factorization and with SuperLU, and the
  ARPACK path, split into the factorization, the
  substitutions and the eigen-iteration's own overhead, beside the floor (one
  factorization plus the substitutions the converged modes needed);
* SLEPc's PEP solver on the same matrices (TOAR, shift-and-invert at a target just below the
  lowest frequency, MUMPS LU with the AMF ordering, tol 1e-8), run by
  ``benchmarks/slepc_pep.py`` in its own virtual environment as a separate process (set-up
  with the factorization and solve timed inside it); the column is skipped when that
  environment is missing. Its interpreter: $GYROSHELL_SLEPC_PYTHON, default
  .venv-slepc/bin/python in the repository (``python3.12 -m venv .venv-slepc &&
  .venv-slepc/bin/pip install dolfinx-solver-complex``);
* a 20-speed sweep (0-95 m/s, 6 modes) by continuation against 20 separate ``modes`` calls
  on fresh models, and the continued sweep split over 2 local processes (``workers=2``);
* the sweep's budget: factorizations, the Lanczos iteration (its substitutions inside)
  and the rest, for the continued sweep and the separate calls, and the two bounds on their
  ratio that the solves each makes imply (docs/performance.md, "the sweep's 2x");
* the critical speed (both routes);
* with ``--baseline DIR`` (a tree of the state before a change, e.g. ``git archive main |
  tar -x -C DIR``): the same ``modes`` call, sweep, separate calls and critical speed on
  this tree and on DIR, each round in a fresh process per tree (PYTHONPATH = the tree),
  alternating which tree goes first, with the medians side by side.

Timings on a shared machine vary: read the medians and the ratios measured in one run.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from gyroshell import TapeModel, TapeParameters
from gyroshell.engines.critical import critical_speeds
from gyroshell.engines.eigen import modes
from gyroshell.linalg import cholesky
from gyroshell.studies.sweep import solve_speeds, sweep

SLEPC_PYTHON = os.environ.get(
    "GYROSHELL_SLEPC_PYTHON",
    str(Path(__file__).resolve().parents[1] / ".venv-slepc" / "bin" / "python"))
SLEPC_DRIVER = Path(__file__).with_name("slepc_pep.py")


def fresh_model(ratio: float) -> TapeModel:
    model = TapeModel(TapeParameters(length_ratio=ratio))
    model.A, model.B  # assemble outside the timings  # noqa: B018
    return model


def export(model: TapeModel, velocity: float, target: float, path: Path) -> None:
    parts = {}
    for name, A in (("K", model.K(velocity)), ("G", model.G(velocity)),
                    ("M", sp.diags(model.mass_diagonal))):
        A = sp.csr_matrix(A)
        A.sort_indices()
        parts.update({f"{name}_indptr": A.indptr, f"{name}_indices": A.indices,
                      f"{name}_data": A.data})
    np.savez(path, target=target, **parts)


def slepc_round(path: Path, count: int) -> dict | None:
    if not Path(SLEPC_PYTHON).exists():
        return None
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    out = subprocess.run([SLEPC_PYTHON, str(SLEPC_DRIVER), str(path), "--nev", str(count)],
                         capture_output=True, text=True, env=env, check=False)
    if out.returncode != 0:
        print(f"  SLEPc run failed: {out.stderr.strip().splitlines()[-1:]}")
        return None
    return json.loads(out.stdout)["rounds"][0]


def gyroshell_round(ratio: float, velocity: float, count: int, method: str,
                    factorization: str = "auto", symmetry: bool = True) -> dict:
    model = fresh_model(ratio)
    t0, c0 = time.perf_counter(), time.process_time()
    res = modes(model, velocity, count, method=method, factorization=factorization,
                symmetry=symmetry)
    total, cpu = time.perf_counter() - t0, time.process_time() - c0
    info = res.info
    subst = info.get("substitution_time")
    ops = info["operator_applications"]
    return {"total": total, "cpu": cpu, "factor": info["factor_time"],
            "iteration": info["solve_time"],
            "substitutions": subst, "ops": ops, "omega": res.omega,
            "residual": float(res.residuals.max()), "shift": abs(info["shift"]),
            "method": info["method"], "factorization": info.get("factorization"),
            "mirror": info.get("mirror")}


def med(rows: list[dict], key: str) -> float:
    values = [r[key] for r in rows if r.get(key) is not None]
    return statistics.median(values) if values else float("nan")


def bench_modes(args) -> None:
    velocity, count = 50.0, args.count
    model = fresh_model(args.length_ratio)
    print(f"grid {model.grid.nx} x {model.grid.ny}, n = {model.unknowns} unknowns; "
          f"V = {velocity:g} m/s, {count} modes; {args.rounds} alternating rounds")
    ours, halves_superlu, full, superlu, arpack, slepc = [], [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "matrices.npz"
        first = gyroshell_round(args.length_ratio, velocity, count, "auto", symmetry=False)
        export(model, velocity, first["shift"], path)
        for _ in range(args.rounds):
            ours.append(gyroshell_round(args.length_ratio, velocity, count, "auto"))
            slepc.append(slepc_round(path, count))
            halves_superlu.append(gyroshell_round(args.length_ratio, velocity, count,
                                                  "auto", "superlu"))
            full.append(gyroshell_round(args.length_ratio, velocity, count, "auto",
                                        symmetry=False))
            superlu.append(gyroshell_round(args.length_ratio, velocity, count, "auto",
                                           "superlu", symmetry=False))
            arpack.append(gyroshell_round(args.length_ratio, velocity, count, "arpack"))
    print(f"default factorization: {ours[0]['factorization']} "
          f"(cvxopt {'installed' if cholesky.available() else 'not installed'}); default "
          f"split into halves: {ours[0]['mirror']} (its solves are half-size)")
    for name, rows in (("gyroshell default (halves)", ours),
                       ("gyroshell halves, SuperLU", halves_superlu),
                       ("gyroshell full problem", full),
                       ("gyroshell full, SuperLU", superlu),
                       ("gyroshell ARPACK, full", arpack)):
        t = med(rows, "total")
        fac, it = med(rows, "factor"), med(rows, "iteration")
        ops = statistics.median(r["ops"] for r in rows)
        line = (f"{name:30s} total {t:.3f} s = factor {fac:.3f} + iteration {it:.3f} "
                f"({ops:.0f} solves)")
        subst = med(rows, "substitutions")
        if subst == subst:  # not NaN
            line += (f"; substitutions {subst:.3f}, own overhead {it - subst:.3f}; floor "
                     f"(factor + substitutions) {fac + subst:.3f}")
        print(line + f"; max residual {max(r['residual'] for r in rows):.1e}")
    if all(s is not None for s in slepc):
        setup, solve = med(slepc, "setup"), med(slepc, "solve")
        total = statistics.median(s["setup"] + s["solve"] for s in slepc)
        print(f"{'SLEPc PEP (TOAR, MUMPS AMF)':30s} total {total:.3f} s = setup+factor "
              f"{setup:.3f} + solve {solve:.3f}")
        diff = np.max(np.abs(np.array(slepc[-1]["omega"]) - ours[-1]["omega"])
                      / ours[-1]["omega"])
        print(f"  SLEPc/gyroshell time ratio {total / med(ours, 'total'):.2f} (halves with "
              f"SuperLU {total / med(halves_superlu, 'total'):.2f}, full problem "
              f"{total / med(full, 'total'):.2f}, full with SuperLU "
              f"{total / med(superlu, 'total'):.2f}); "
              f"largest relative frequency difference {diff:.1e} (SLEPc tol 1e-8)")
        if all("cpu" in s for s in slepc):
            ours_cpu, slepc_cpu = med(ours, "cpu"), med(slepc, "cpu")
            print(f"  CPU time (process_time; on a loaded machine nearer the work than the "
                  f"wall time): gyroshell default {ours_cpu:.3f} s, SLEPc {slepc_cpu:.3f} s, "
                  f"gyroshell/SLEPc {ours_cpu / slepc_cpu:.2f}")
    else:
        print(f"SLEPc: skipped (no interpreter at {SLEPC_PYTHON}, or the run failed)")
    print(f"  omega (rad/s): {np.array2string(ours[-1]['omega'], precision=8)}")


def bench_sweep(args) -> None:
    speeds = np.linspace(0.0, 95.0, 20)
    cont_times, call_times, par_times = [], [], []

    def continuation():
        model = fresh_model(args.length_ratio)
        t0 = time.perf_counter()
        frame = sweep(model, speeds, args.count, continuation=True).table
        cont_times.append(time.perf_counter() - t0)
        return frame

    def separate():
        t0 = time.perf_counter()
        out = [modes(fresh_model(args.length_ratio), v, args.count) for v in speeds]
        call_times.append(time.perf_counter() - t0)
        return out

    def parallel():
        model = fresh_model(args.length_ratio)
        t0 = time.perf_counter()
        frame = sweep(model, speeds, args.count, continuation=True, workers=2).table
        par_times.append(time.perf_counter() - t0)
        return frame

    for k in range(args.sweep_rounds):  # alternate which goes first
        if k % 2:
            calls = separate()
            frame = continuation()
            pframe = parallel()
        else:
            pframe = parallel()
            frame = continuation()
            calls = separate()
    table = frame.pivot(index="velocity", columns="rank", values="omega").to_numpy()
    omega = np.array([c.omega for c in calls])
    diff = np.max(np.abs(table - omega) / omega)
    solves = sum(c.info["operator_applications"] for c in calls)
    c, s = statistics.median(cont_times), statistics.median(call_times)
    print(f"20-speed sweep 0-95 m/s, {args.count} modes, {args.sweep_rounds} alternating "
          f"rounds: continuation {c:.2f} s, 20 separate modes calls {s:.2f} s ({solves} "
          f"solves; ratio separate/continuation {s / c:.2f}); largest relative frequency "
          f"difference {diff:.1e}")
    p = statistics.median(par_times)
    pdiff = np.max(np.abs(pframe.omega.to_numpy() - frame.omega.to_numpy())
                   / frame.omega.to_numpy())
    print(f"  the same sweep on 2 local processes (workers=2): {p:.2f} s (ratio "
          f"separate/parallel {s / p:.2f}, continuation/parallel {c / p:.2f}); largest "
          f"relative difference from one process {pdiff:.1e}")


def _budget(results: list, wall: float) -> dict:
    """Sums over the speeds' solves: factorizations F, the Lanczos iteration I (its
    substitutions S inside it), the solves n, and the rest R = wall − F − I, s."""
    total = {key: sum(r.info.get(key, 0) or 0 for r in results)
             for key in ("factor_time", "solve_time", "substitution_time",
                         "operator_applications")}
    return {"wall": wall, "F": total["factor_time"], "I": total["solve_time"],
            "S": total["substitution_time"], "n": total["operator_applications"],
            "R": wall - total["factor_time"] - total["solve_time"]}


def bench_sweep_budget(args) -> None:
    """Where the sweep's time goes, beside the separate calls', and the two bounds on
    their ratio that follow from the solves each must make (module notes of
    docs/performance.md, "the sweep's 2x")."""
    speeds = list(np.linspace(0.0, 95.0, 20))
    rows = {"continuation": [], "separate": []}
    for k in range(args.sweep_rounds):
        for name in (("continuation", "separate") if k % 2 == 0 else
                     ("separate", "continuation")):
            if name == "continuation":
                model = fresh_model(args.length_ratio)
                t0 = time.perf_counter()
                results = solve_speeds(model, speeds, args.count, continuation=True,
                                       workers=1, options={}, progress=False,
                                       description="sweep")
            else:
                t0 = time.perf_counter()
                results = [modes(fresh_model(args.length_ratio), v, args.count)
                           for v in speeds]
            rows[name].append(_budget(results, time.perf_counter() - t0))
    med_rows = {name: {key: statistics.median(r[key] for r in rs) for key in rs[0]}
                for name, rs in rows.items()}
    for name, b in med_rows.items():
        print(f"  {name:12s} wall {b['wall']:.2f} s = factorizations {b['F']:.2f} + Lanczos "
              f"{b['I']:.2f} (substitutions {b['S']:.2f}, {b['n']:.0f} solves, "
              f"{1e3 * b['I'] / b['n']:.2f} ms per solve with its iteration work) + rest "
              f"{b['R']:.2f}")
    c, s = med_rows["continuation"], med_rows["separate"]
    shared = c["F"] + c["n"] * s["I"] / s["n"]
    floor_only = (s["F"] + s["S"] + s["R"]) / (c["F"] + c["S"])
    print(f"  ratio separate/continuation {s['wall'] / c['wall']:.2f}; bound with the "
          f"continuation's rest removed and the same iteration work per solve: "
          f"{s['wall'] / shared:.2f}; bound with no iteration work beyond the substitutions "
          f"in either and no rest in the continuation: {floor_only:.2f}")


def bench_critical(args) -> None:
    times, result = [], None
    for _ in range(args.sweep_rounds):
        model = fresh_model(args.length_ratio)
        t0 = time.perf_counter()
        result = critical_speeds(model)
        times.append(time.perf_counter() - t0)
    i = result.info
    print(f"critical speed (a) and (b): median {statistics.median(times):.2f} s; (a) "
          f"{result.critical_speed:.9f} m/s in {i['critical_time']:.2f} s, {i['evaluations']} "
          f"eigen-solves; (b) {result.divergence_speed:.9f} m/s in {i['divergence_time']:.2f} s;"
          f" |a-b|/b = {result.relative_difference:.1e}")


# ----- before / after: each tree in its own process -------------------------------------
def child(task: str, ratio: float, count: int) -> dict:
    """One timed round of ``task`` on the gyroshell this process imports (public API
    only, so that an older tree runs it too)."""
    speeds = np.linspace(0.0, 95.0, 20)
    model = fresh_model(ratio)
    if task == "sweep":
        # the sweep's lazy imports (pandas for its table, scipy.optimize for the branch
        # matching: ~1.7 s, 12 % of a sweep) are a once-per-process cost, not the sweep's;
        # the separate calls never pay them
        import pandas  # noqa: F401
        import scipy.optimize  # noqa: F401
    t0, c0 = time.perf_counter(), time.process_time()
    if task == "modes":
        info = modes(model, 50.0, count).info
        out = {"factor": info["factor_time"], "substitutions": info.get("substitution_time"),
               "ops": info["operator_applications"]}
    elif task == "sweep":
        sweep(model, speeds, count, continuation=True)
        out = {}
    elif task == "separate":
        t0, c0 = time.perf_counter(), time.process_time()   # fresh models inside, as in
        # bench_sweep
        for v in speeds:
            modes(fresh_model(ratio), v, count)
        out = {}
    else:
        result = critical_speeds(model)
        out = {"evaluations": result.info["evaluations"], "speed": result.critical_speed}
    out["total"], out["cpu"] = time.perf_counter() - t0, time.process_time() - c0
    return out


def tree_round(tree: Path, task: str, args) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree))
    out = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--child", task,
                          "--length-ratio", str(args.length_ratio), "--count",
                          str(args.count)], capture_output=True, text=True, env=env,
                         check=False)
    if out.returncode != 0:
        raise RuntimeError(f"{tree}: {out.stderr.strip().splitlines()[-1:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def bench_baseline(args) -> None:
    here, before = Path(__file__).resolve().parents[1], Path(args.baseline).resolve()
    print(f"before/after: this tree against {before}, alternating rounds, a fresh process "
          "per round and tree")
    tasks = [("modes", args.rounds), ("sweep", args.sweep_rounds),
             ("separate", args.sweep_rounds), ("critical", args.sweep_rounds)]
    for task, rounds in tasks:
        if task in args.skip or (task == "separate" and "sweep" in args.skip):
            continue
        rows = {"after": [], "before": []}
        for k in range(rounds):
            order = (("after", here), ("before", before))
            for name, tree in (order if k % 2 == 0 else order[::-1]):
                rows[name].append(tree_round(tree, task, args))
        a, b = med(rows["after"], "total"), med(rows["before"], "total")
        line = f"  {task:9s} before {b:.3f} s, after {a:.3f} s (after/before {a / b:.2f})"
        if all("cpu" in r for r in rows["after"] + rows["before"]):   # older trees: none
            ca, cb = med(rows["after"], "cpu"), med(rows["before"], "cpu")
            line += f"; CPU time before {cb:.3f} s, after {ca:.3f} s ({ca / cb:.2f})"
        if task == "modes":
            fa, sa = med(rows["after"], "factor"), med(rows["after"], "substitutions")
            fb, sb = med(rows["before"], "factor"), med(rows["before"], "substitutions")
            line += (f"; floor before {fb + sb:.3f} s ({(fb + sb) / b:.0%} of its total), "
                     f"after {fa + sa:.3f} s ({(fa + sa) / a:.0%}); solves "
                     f"{rows['before'][0]['ops']} -> {rows['after'][0]['ops']}")
        if task == "critical":
            line += (f"; eigen-solves of route (a) {rows['before'][0]['evaluations']} -> "
                     f"{rows['after'][0]['evaluations']}")
        print(line)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--sweep-rounds", type=int, default=3)
    ap.add_argument("--count", type=int, default=6)
    ap.add_argument("--length-ratio", type=float, default=19.0)
    ap.add_argument("--skip", nargs="*", default=(), choices=("modes", "sweep", "critical"))
    ap.add_argument("--baseline", metavar="DIR",
                    help="a tree of the state before the change, timed beside this one")
    ap.add_argument("--child", choices=("modes", "sweep", "separate", "critical"),
                    help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(child(args.child, args.length_ratio, args.count)))
        return
    print(f"python {sys.version.split()[0]}")
    if args.baseline:
        bench_baseline(args)
    if "modes" not in args.skip:
        bench_modes(args)
    if "sweep" not in args.skip:
        bench_sweep(args)
        bench_sweep_budget(args)
    if "critical" not in args.skip:
        bench_critical(args)


if __name__ == "__main__":
    main()
