"""The bearing's memory estimates (gyroshell/bearing/budget.py) against measured peaks.

Each case runs in a fresh subprocess: it imports gyroshell, solves a tiny infinitely
wide bearing (so that the libraries are loaded), resets its peak resident size to the
present one (Linux: /proc/self/clear_refs; elsewhere the peak so far, ``ru_maxrss``),
then builds and solves the case and reads the peak (VmHWM, the maximum resident set size
``/usr/bin/time -v`` reports); its rise is the case's measured peak (SuperLU's factors
live outside Python's allocator, so tracemalloc would not see them). It also counts the
entries nnz(L) + nnz(U) of the largest LU factor the solve made (with the ordering it
used) against :func:`gyroshell.bearing.budget.factor_entries`. Prints one table: case,
unknowns, factor entries estimated and counted, memory estimated and measured, and
estimate / measured (must be >= 1; the 2-D cases are calibrated to 1.5-2.5 of it,
budget.SAFETY = 1.5).

    PYTHONPATH=. python benchmarks/bench_bearing_memory.py [--quick | --big]

The default cases go up to the 12.65 mm tape's default grid (~3 s of solve); ``--big``
adds a 50 mm tape's default grid (~15 s, 2.1 GB), ``--quick`` keeps three small cases.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

CHILD = r"""
import json, math, re, resource, sys
import gyroshell.linalg.factorization as factorization
from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel, march, solve_steady, budget
case = json.loads(sys.argv[1])
wrap = math.radians(15.0)
solve_steady(BearingModel(TapeParameters(), velocity=4.0, wrap_angle=wrap, nx=60,
                          infinitely_wide=True))
counted = []
plain_splu = factorization.splu
def counting_splu(matrix, **kw):
    lu = plain_splu(matrix, **kw)
    counted.append(lu.L.nnz + lu.U.nnz)
    return lu
factorization.splu = counting_splu
def status(key):
    with open("/proc/self/status") as f:
        return 1024.0 * int(re.search(key + r":\s+(\d+)", f.read()).group(1))
try:                                 # Linux: reset the peak to the present size
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
    base, peak = status("VmRSS"), lambda: status("VmHWM")
except OSError:                      # elsewhere: the peak so far
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0
    peak = lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0
wide = case.get("wide", False)
kw = {k: case[k] for k in ("nx", "ny", "span") if case.get(k) is not None}
model = BearingModel(TapeParameters(width=case["width"]), AirParameters(), velocity=4.0,
                     wrap_angle=wrap, infinitely_wide=wide, **kw)
sol = solve_steady(model)
if case["steps"]:
    march(sol, dt=1e-5, steps=case["steps"], record_every=1, progress=False)
    estimate = budget.march_bytes(model.nx, model.ny, case["steps"], 1, model.factorization)
else:
    estimate = budget.steady_bytes(model.nx, model.ny, model.factorization)
print(json.dumps({"grid": f"{model.nx} x {model.ny}", "unknowns": model.unknowns,
                  "entries": budget.factor_entries(model.nx, model.ny, model.factorization),
                  "counted": max(counted), "estimate": estimate,
                  "measured": peak() - base}))
"""

def _strip(nx: int, steps: int = 0) -> dict:
    """An infinitely wide 6.35 mm tape on nx intervals."""
    return {"nx": nx, "ny": None, "width": 6.35e-3, "steps": steps, "wide": True}


def _plate(width: float, nx: int | None = None, ny: int | None = None, steps: int = 0,
           span: float | None = None) -> dict:
    """A 2-D tape (nx, ny None: the default grid)."""
    return {"nx": nx, "ny": ny, "width": width, "steps": steps, "span": span}


CASES = [
    ("steady 1-D, default grid", _strip(798)),
    ("steady 1-D, nx = 1600", _strip(1600)),
    ("steady 1-D, nx = 3200", _strip(3200)),
    ("steady 1-D, nx = 8000 (822 Newton iterations: a round-off stall)", _strip(8000)),
    ("steady 2-D 3 mm, 96 x 32", _plate(3e-3, 96, 32, span=2e-3)),
    ("steady 2-D 12.65 mm, 96 x 200 (wider than long)",
     _plate(12.65e-3, 96, 200, span=2e-3)),
    ("steady 2-D 6.35 mm, 194 x 74", _plate(6.35e-3, 194, 74)),
    ("steady 2-D 6.35 mm, default grid", _plate(6.35e-3)),
    ("steady 2-D 12.65 mm, default grid", _plate(12.65e-3)),
    ("transient 1-D, nx = 800, 2000 steps", _strip(800, 2000)),
    ("transient 2-D 3 mm, 96 x 32, 50 steps", _plate(3e-3, 96, 32, 50, span=2e-3)),
]
BIG = [("steady 2-D 50 mm, default grid", _plate(50e-3))]
QUICK = {0, 4, 10}


def measure(case: dict) -> dict:
    out = subprocess.run([sys.executable, "-c", CHILD, json.dumps(case)], check=True,
                         capture_output=True, text=True, env=None)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    which = parser.add_mutually_exclusive_group()
    which.add_argument("--quick", action="store_true", help="three small cases only")
    which.add_argument("--big", action="store_true",
                       help="also a 50 mm tape's default grid (~15 s, 2.1 GB)")
    args = parser.parse_args(argv)
    print("| case | grid | unknowns | factor entries est. / counted | estimate (MB) | "
          "measured peak (MB) | ratio |")
    print("|---|---|---|---|---|---|---|")
    worst = float("inf")
    cases = CASES + (BIG if args.big else [])
    for k, (name, case) in enumerate(cases):
        if args.quick and k not in QUICK:
            continue
        r = measure(case)
        ratio = r["estimate"] / max(r["measured"], 1.0)
        worst = min(worst, ratio)
        print(f"| {name} | {r['grid']} | {r['unknowns']} | {r['entries'] / 1e6:.3g}M / "
              f"{r['counted'] / 1e6:.3g}M | {r['estimate'] / 1e6:.1f} | "
              f"{r['measured'] / 1e6:.1f} | {ratio:.2f} |", flush=True)
    print(f"\nsmallest ratio {worst:.2f} ({'ok' if worst >= 1 else 'ESTIMATE TOO LOW'})")
    return 0 if worst >= 1 else 1


if __name__ == "__main__":
    raise SystemExit(main())
