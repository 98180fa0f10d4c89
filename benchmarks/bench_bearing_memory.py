"""The bearing's memory estimates (gyroshell/bearing/budget.py) against measured peaks.

Each case runs in a fresh subprocess: it imports gyroshell, solves a tiny infinitely wide
bearing (so that the libraries are loaded), reads its peak resident size
(``resource.getrusage(...).ru_maxrss``), then builds and solves the case and reads the peak
again; the difference is the case's measured peak (SuperLU's factors live outside
Python's allocator, so tracemalloc would not see them). Prints one table: case, unknowns,
estimate, measured peak, estimate / measured (must be >= 1).

    PYTHONPATH=. python benchmarks/bench_bearing_memory.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

CHILD = r"""
import json, math, resource, sys
from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel, march, solve_steady, budget
case = json.loads(sys.argv[1])
wrap = math.radians(15.0)
solve_steady(BearingModel(TapeParameters(), velocity=4.0, wrap_angle=wrap, nx=60,
                          infinitely_wide=True))
def rss():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0
base = rss()
wide = case["ny"] is None
kw = {} if case.get("span") is None else {"span": case["span"]}
model = BearingModel(TapeParameters(width=case["width"]), AirParameters(), velocity=4.0,
                     wrap_angle=wrap, infinitely_wide=wide, nx=case["nx"], ny=case["ny"], **kw)
sol = solve_steady(model)
if case["steps"]:
    march(sol, dt=1e-5, steps=case["steps"], record_every=1, progress=False)
    estimate = budget.march_bytes(model.nx, model.ny, case["steps"], 1)
else:
    estimate = budget.steady_bytes(model.nx, model.ny)
print(json.dumps({"unknowns": model.unknowns, "estimate": estimate,
                  "measured": rss() - base}))
"""

CASES = [
    ("steady 1-D, default grid", {"nx": 798, "ny": None, "width": 6.35e-3, "steps": 0}),
    ("steady 1-D, nx = 1600", {"nx": 1600, "ny": None, "width": 6.35e-3, "steps": 0}),
    ("steady 1-D, nx = 3200", {"nx": 3200, "ny": None, "width": 6.35e-3, "steps": 0}),
    ("steady 1-D, nx = 8000 (822 Newton iterations: a round-off stall)",
     {"nx": 8000, "ny": None, "width": 6.35e-3, "steps": 0}),
    ("steady 2-D 3 mm, 96 x 32", {"nx": 96, "ny": 32, "width": 3e-3, "span": 2e-3,
                                  "steps": 0}),
    ("steady 2-D 6.35 mm, 194 x 74", {"nx": 194, "ny": 74, "width": 6.35e-3, "steps": 0}),
    ("steady 2-D 6.35 mm, 388 x 148 (default)", {"nx": 388, "ny": 148, "width": 6.35e-3,
                                                  "steps": 0}),
    ("transient 1-D, nx = 800, 2000 steps", {"nx": 800, "ny": None, "width": 6.35e-3,
                                             "steps": 2000}),
    ("transient 2-D 3 mm, 96 x 32, 50 steps", {"nx": 96, "ny": 32, "width": 3e-3,
                                               "span": 2e-3, "steps": 50}),
]
QUICK = {0, 4, 7}


def measure(case: dict) -> dict:
    out = subprocess.run([sys.executable, "-c", CHILD, json.dumps(case)], check=True,
                         capture_output=True, text=True, env=None)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="three small cases only")
    args = parser.parse_args(argv)
    print("| case | unknowns | estimate (MB) | measured peak (MB) | ratio |")
    print("|---|---|---|---|---|")
    worst = float("inf")
    for k, (name, case) in enumerate(CASES):
        if args.quick and k not in QUICK:
            continue
        r = measure(case)
        ratio = r["estimate"] / max(r["measured"], 1.0)
        worst = min(worst, ratio)
        print(f"| {name} | {r['unknowns']} | {r['estimate'] / 1e6:.1f} | "
              f"{r['measured'] / 1e6:.1f} | {ratio:.2f} |", flush=True)
    print(f"\nsmallest ratio {worst:.2f} ({'ok' if worst >= 1 else 'ESTIMATE TOO LOW'})")
    return 0 if worst >= 1 else 1


if __name__ == "__main__":
    raise SystemExit(main())
