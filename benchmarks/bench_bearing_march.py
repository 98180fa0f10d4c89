"""Bearing transient marches timed on this tree and on a baseline tree, alternating.

    PYTHONPATH=. python benchmarks/bench_bearing_march.py --baseline DIR [--rounds 3]

Each round runs both trees, in alternating order, each in a fresh interpreter with its tree
first on PYTHONPATH and one BLAS thread. Cases: the infinitely wide Table 1 tape (nx 160,
4 m/s over 15°) settling from a bump, 400 steps of 10 µs; a free-edged 3 mm tape on the
uniform 60 x 16 grid (its edge rows in contact), 100 steps. Prints the median wall seconds
of each case, the ratio after/before, and the largest difference of the final states
between the trees, relative to the central spacing (0 when the arithmetic is unchanged).

Timings on a shared machine vary by factors of two or more: read the ratios, not digits.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

CASES = r'''
import json, math, sys, time
import numpy as np
from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.steady import BearingSolution, solve_steady
from gyroshell.bearing.transient import march

DAMPED = {"beta": 0.3025, "gamma": 0.6}
out = {}
for name, kw, steps in [
        ("1-D nx 160, 400 steps", dict(infinitely_wide=True, nx=160), 400),
        ("2-D 3 mm 60 x 16, 100 steps",
         dict(tape=TapeParameters(width=3e-3), nx=60, ny=16, span=2e-3, grading="uniform"),
         100)]:
    tape = kw.pop("tape", TapeParameters())
    model = BearingModel(tape, AirParameters(), velocity=4.0,
                         wrap_angle=math.radians(15), **kw)
    steady = solve_steady(model)
    x = steady.x[1:-1]
    bump = 0.3 * steady.central_spacing * np.repeat(np.exp(-((x / 1e-3) ** 2)), model.nc)
    start = BearingSolution(model, steady.u + bump, steady.p, steady.contact, steady.info)
    t0 = time.perf_counter()
    run = march(start, dt=1e-5, steps=steps, record_every=50, **DAMPED)
    out[name] = {"seconds": time.perf_counter() - t0,
                 "u": run.final.u.tolist(), "h": float(steady.central_spacing)}
json.dump(out, open(sys.argv[1], "w"))
'''


def run_tree(tree: str, path: str) -> dict:
    env = dict(os.environ, PYTHONPATH=tree, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               MKL_NUM_THREADS="1")
    subprocess.run([sys.executable, "-c", CASES, path], env=env, check=True, cwd=tree)
    with open(path) as f:
        return json.load(f)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", metavar="DIR", required=True)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    trees = {"before": os.path.abspath(args.baseline), "after": here}
    times: dict = {}
    last: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.rounds):
            order = list(trees) if r % 2 == 0 else list(trees)[::-1]
            for label in order:
                out = run_tree(trees[label], os.path.join(tmp, f"{label}.json"))
                for case, value in out.items():
                    times.setdefault(case, {}).setdefault(label, []).append(value["seconds"])
                last[label] = out
    print(f"| case | before, s | after, s | after/before | max |Δu|/h |   ({args.rounds} "
          "alternating rounds, fresh processes, one BLAS thread)")
    print("|---|---|---|---|---|")
    for case, by in times.items():
        before, after = statistics.median(by["before"]), statistics.median(by["after"])
        ub, ua = (last[t][case]["u"] for t in ("before", "after"))
        diff = max(abs(a - b) for a, b in zip(ua, ub, strict=True)) / last["before"][case]["h"]
        print(f"| {case} | {before:.3f} | {after:.3f} | {after / before:.3f} | {diff:.1e} |")


if __name__ == "__main__":
    main()
