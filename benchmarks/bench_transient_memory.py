"""Benchmark: the transient's memory estimate against the measured peak, fixed and moving loads.

Each row is one ``gyroshell transient`` command line (``--out`` CSV written, ``--quiet``) run
in a fresh process on a small grid (L_x/L_y = 2, 16 x 8 intervals, so that what the run
keeps per step dominates): the fixed step load, one moving head, and one moving head with
intermittent contact (ramped windows, each contact restarting the track), at a few step
counts. Two processes per row measure the peak:

* ``tracemalloc``: the peak of the Python and NumPy allocations during the command, after
  a warm-up command has imported everything;
* ``ru_maxrss``: the growth of the process's resident peak over the same warm-up (without
  tracemalloc, whose own bookkeeping would count).

The estimate is :func:`gyroshell.core.budget.transient_bytes` for the same run (the model's
operators and factorization, an upper bound, plus the bytes kept per step and head). The
table prints the estimate, both peaks and estimate / max(peaks), which must be >= 1.
Usage::

    PYTHONPATH=. python benchmarks/bench_transient_memory.py [--steps 50000,200000,400000]
        [--cases 'moving head']
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

WIDTH = 6.35e-3
GRID = ["--spacing", str(WIDTH / 8), "--length-ratio", "2"]
DT = "1e-6"
#: (name, moving heads, extra options)
CASES = (
    ("fixed load", 0, []),
    ("moving head", 1, ["--load-position", "0.002,0.001", "--load-velocity", "0.02,0.01"]),
    ("intermittent head", 1, ["--load-position", "0.002,0.001", "--load-velocity", "100,20",
                              "--contact-period", "40e-6", "--contact-duration", "30e-6",
                              "--contact-ramp", "3e-6", "--damping", "100"]),
)

#: Run in the child: a warm-up command, then the measured one; prints the peaks as JSON.
CHILD = r"""
import json, os, resource, sys, tempfile, tracemalloc
from gyroshell.cli import main
argv, traced = json.loads(sys.argv[1]), sys.argv[2] == "tracemalloc"
folder = tempfile.mkdtemp()
def run(steps):
    code = main(["transient", *argv, "--steps", str(steps), "--quiet",
                 "--out", os.path.join(folder, f"h{steps}.csv")])
    assert code == 0, code
run(50)
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
if traced:
    tracemalloc.start()
run(int(sys.argv[3]))
peak = tracemalloc.get_traced_memory()[1] if traced else 0
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 - base
print(json.dumps({"tracemalloc": peak, "rss": rss}))
"""


def measure(argv: list[str], steps: int, how: str) -> int:
    """Peak bytes of one command in a fresh process, by ``how`` (tracemalloc or rss)."""
    env = {**os.environ, "GYROSHELL_TIME_LIMIT": "1e6"}
    proc = subprocess.run([sys.executable, "-c", CHILD, json.dumps(argv), how, str(steps)],
                          capture_output=True, text=True, env=env, check=True)
    return int(json.loads(proc.stdout.strip().splitlines()[-1])[
        "tracemalloc" if how == "tracemalloc" else "rss"])


def estimate(steps: int, heads: int) -> float:
    """The budget's estimate for the run, bytes."""
    from gyroshell.core import budget
    from gyroshell.tape.grid import Grid
    from gyroshell.tape.parameters import TapeParameters

    g = Grid.from_parameters(TapeParameters(spacing=WIDTH / 8, length_ratio=2))
    return budget.transient_bytes(g.nx, g.ny, g.edges, steps, heads=heads)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", default="50000,200000,400000",
                        help="comma-separated step counts (default 50000,200000,400000)")
    parser.add_argument("--cases", default=",".join(c[0] for c in CASES),
                        help="comma-separated cases (default all)")
    args = parser.parse_args()
    counts = [int(float(s)) for s in args.steps.split(",")]
    print(f"{'case':>18} {'steps':>8} {'estimate MB':>12} {'tracemalloc MB':>15} "
          f"{'ru_maxrss MB':>13} {'ratio':>6}")
    worst = float("inf")
    for name, heads, extra in (c for c in CASES if c[0] in args.cases.split(",")):
        for steps in counts:
            argv = [*GRID, "--dt", DT, *extra]
            traced, rss = measure(argv, steps, "tracemalloc"), measure(argv, steps, "rss")
            est = estimate(steps, heads)
            ratio = est / max(traced, rss, 1)
            worst = min(worst, ratio)
            print(f"{name:>18} {steps:>8} {est / 1e6:12.1f} {traced / 1e6:15.1f} "
                  f"{rss / 1e6:13.1f} {ratio:6.2f}", flush=True)
    print(f"smallest estimate / peak: {worst:.2f} ({'ok' if worst >= 1 else 'TOO LOW'})")


if __name__ == "__main__":
    main()
