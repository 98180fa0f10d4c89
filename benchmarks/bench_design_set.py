"""A realistic random set of 1-D flat-head designs, solved one per process, with a cap.

    python benchmarks/bench_design_set.py [--count 24] [--seed 1] [--cap 60]
        [--physics new|old|both] [--baseline DIR]

Designs (the issue's space): 1-3 modules of 0.2-3 mm lands, 0.05-0.5 mm gaps, sharp or
rounded corners (r_c 5 µm - 2 mm), wraps 0.3-5° each side, 0.5-10 m/s, 40-150 N/m; Table
1's tape, the infinitely wide tape on its default grid. ``new``: the Boltzmann film with
Patir-Cheng's flow factors over Greenwood-Williamson asperities (``contact="asperity"``);
``old``: first-order slip and the hard wall at 20 nm, today's physics (solved by the tree
given as ``--baseline DIR``, e.g. ``git archive <commit> | tar -x -C DIR``, or by this
one: the hard wall's solver is the one it always was). Each solve runs in a fresh process
killed after ``--cap`` seconds; prints each design's outcome (solved, refused with the
model's reason, failed with the solver's ConvergenceError, or over the cap), its wall time
(model and solve; the modules the solve imports on first use are imported before the
clock starts) and Newton iterations, and the tape's force balance (air and contact force
over the tension's turn between the tape's ends, 1 at a solution: a check the solver does
not know), then the success rate and the median and worst times and iteration counts of
each physics.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def designs(count: int, seed: int) -> list[dict]:
    """``count`` designs drawn with the seed (plain JSON values)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        n = int(rng.integers(1, 4))
        lands = [float(rng.uniform(0.2e-3, 3e-3)) for _ in range(n)]
        radii = [float(rng.choice([0.0, rng.uniform(5e-6, 2e-3)])) for _ in range(n)]
        gaps = [float(rng.uniform(0.05e-3, 0.5e-3)) for _ in range(n - 1)]
        wraps = [float(w) for w in rng.uniform(0.3, 5.0, size=2)]
        out.append({"lands": lands, "radii": radii, "gaps": gaps, "wraps": wraps,
                    "velocity": float(rng.uniform(0.5, 10.0)),
                    "tension": float(rng.uniform(40.0, 150.0))})
    return out


def child(design: dict, physics: str) -> dict:
    """Solve one design in this process: outcome, seconds, iterations."""
    import math
    import warnings

    # scipy.optimize, scipy.special and bearing.smooth: the modules the solve imports on
    # first use (scipy.special alone ~0.1 s), imported before the clock starts so that the
    # time is the solve's, not the interpreter's
    import scipy.optimize  # noqa: F401
    import scipy.special  # noqa: F401

    from gyroshell import ConvergenceError, ParameterError, TapeParameters
    from gyroshell.bearing import AirParameters, BearingModel
    from gyroshell.bearing.head import FlatHead, Module
    from gyroshell.bearing.steady import solve_steady

    try:      # a tree with contact laws: name each physics (the defaults are the new one)
        import gyroshell.bearing.smooth  # noqa: F401
        from gyroshell.bearing.contact import ContactParameters
    except ImportError:      # a tree before them (the baseline): its defaults are the old
        ContactParameters = None
    kw = {}
    air = AirParameters()
    if physics == "new":
        air = AirParameters(rarefaction="fukui-kaneko", flow_factors="patir-cheng")
        kw["contact"] = ContactParameters()
    elif ContactParameters is not None:
        air = AirParameters(rarefaction="first-order")
        kw["contact"] = ContactParameters(law="hard")
    start = time.perf_counter()
    try:
        head = FlatHead(tuple(Module(land, corner_radius=r) for land, r in
                              zip(design["lands"], design["radii"], strict=True)),
                        *(math.radians(w) for w in design["wraps"]),
                        gaps=tuple(design["gaps"]))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = BearingModel(TapeParameters(tension=design["tension"]), air,
                                 velocity=design["velocity"], head=head,
                                 infinitely_wide=True, **kw)
    except ParameterError as exc:
        return {"outcome": "refused", "why": str(exc)[:160]}
    try:
        sol = solve_steady(model)
    except ConvergenceError as exc:
        return {"outcome": "failed", "seconds": time.perf_counter() - start,
                "why": str(exc)[:160]}
    seconds = time.perf_counter() - start
    return {"outcome": "solved", "seconds": seconds, "iterations": sol.info.iterations,
            "h": sol.central_spacing, "balance": force_balance(model, sol)}


def vertical_forces(model, sol) -> tuple[float, float, float]:
    """(air, contact, turn), N/m: the head's air force (trapezoidal rule over the nodes)
    and asperity force on the tape, and the tension's turn (T − ρV²)(s_in − s_out)
    between its ends (s the slopes of the first and last intervals): the vertical balance
    of the whole tape pinned at its straight ends (no bending shear there) is air +
    contact = turn, a check the solver does not know."""
    pa = model.air.ambient_pressure
    p = np.concatenate([[pa], sol.p, [pa]])
    air = float(np.sum(0.5 * (p[1:] + p[:-1] - 2.0 * pa) * np.diff(model.x)))
    w = model.head.dry_tape(model.x_head) + np.concatenate([[0.0], sol.u, [0.0]])
    slopes = np.diff(w) / np.diff(model.x)
    tension = model.params.tension - model.params.density * model.velocity ** 2
    return air, sol.contact_force, tension * (slopes[0] - slopes[-1])


def force_balance(model, sol) -> float:
    """(air + contact force) / turn (:func:`vertical_forces`): 1 at a solution."""
    air, contact, turn = vertical_forces(model, sol)
    return (air + contact) / turn


def run(design: dict, physics: str, cap: float, tree: str | None) -> dict:
    """One design in a fresh process (the tree ``tree`` first on the path)."""
    env = dict(os.environ)
    root = tree or str(Path(__file__).resolve().parents[1])
    env["PYTHONPATH"] = root + os.pathsep + env.get("PYTHONPATH", "")
    here = str(Path(__file__).resolve().parent)
    code = (f"import json, sys; sys.path.insert(0, {here!r}); import bench_design_set as b; "
            "print(json.dumps(b.child(json.loads(sys.argv[1]), sys.argv[2])))")
    start = time.perf_counter()
    try:
        # from a folder of neither tree: `python -c` puts the working folder first on the
        # path, before PYTHONPATH (from this tree's folder a baseline run imported it)
        done = subprocess.run([sys.executable, "-c", code, json.dumps(design), physics],
                              capture_output=True, text=True, timeout=cap, env=env,
                              cwd=tempfile.gettempdir())
    except subprocess.TimeoutExpired:
        return {"outcome": "over the cap", "seconds": time.perf_counter() - start}
    if done.returncode != 0:
        return {"outcome": "crashed", "why": done.stderr.strip().splitlines()[-1][:160]}
    return json.loads(done.stdout.strip().splitlines()[-1])


def summary(name: str, results: list[dict]) -> str:
    solved = [r for r in results if r["outcome"] == "solved"]
    refused = sum(r["outcome"] == "refused" for r in results)
    asked = len(results) - refused
    times = [r["seconds"] for r in solved]
    its = [r["iterations"] for r in solved]
    over = [r["seconds"] for r in results if r["outcome"] != "refused" and "seconds" in r]
    return (f"{name}: {len(solved)} of {asked} designs solved ({refused} refused by the "
            f"model); solve time median {statistics.median(times) if times else math.nan:.2f} s, "
            f"worst {max(times) if times else math.nan:.2f} s (any outcome: "
            f"{max(over) if over else math.nan:.2f} s); Newton iterations median "
            f"{statistics.median(its) if its else math.nan:g}, worst "
            f"{max(its) if its else math.nan}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--count", type=int, default=24)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--cap", type=float, default=60.0, help="seconds per solve")
    p.add_argument("--physics", choices=("new", "old", "both"), default="both")
    p.add_argument("--baseline", default=None, help="the tree that solves 'old'")
    args = p.parse_args()
    kinds = ("old", "new") if args.physics == "both" else (args.physics,)
    results = {k: [] for k in kinds}
    for i, design in enumerate(designs(args.count, args.seed)):
        for k in kinds:
            r = run(design, k, args.cap, args.baseline if k == "old" else None)
            results[k].append(r)
            balance = f"balance {r['balance']:.6f}" if "balance" in r else ""
            print(f"{i:3d} {k}: {r['outcome']:12s} {r.get('seconds', math.nan):7.2f} s "
                  f"{r.get('iterations', '')!s:>5} {balance}{r.get('why', '')[:100]}",
                  flush=True)
    for k in kinds:
        print(summary(k, results[k]))


if __name__ == "__main__":
    main()
