"""The same calls timed on two source trees of gyroshell, in alternating subprocesses.

    python benchmarks/compare_trees.py OLD_TREE NEW_TREE [ROUNDS]

OLD_TREE and NEW_TREE are checkouts (e.g. ``git worktree add ../old 24513fb``). Each round
runs both, in alternating order, each in a fresh interpreter with its tree first on
PYTHONPATH. Prints the median of each case (s), the ratio new/old, and a few computed
numbers of each tree (they agree to round-off when a change is a refactoring). Table 1 tape;
L_x/L_y = 19 (32,676 unknowns) for the large cases, 4 for the sweep and critical speed.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile

#: Rounds when none is given (each runs both trees once).
DEFAULT_ROUNDS = 3

CASES = r'''
import json, math, time
import gyroshell as g
from gyroshell import bearing

def timed(out, name, call):
    start = time.perf_counter()
    value = call()
    out[name] = time.perf_counter() - start
    return value

out = {}
long = timed(out, "assemble L19", lambda: g.TapeModel(g.TapeParameters(length_ratio=19)))
run = timed(out, "march 250 steps L19",
            lambda: g.march(long, 50.0, dt=2e-6, steps=250, progress=False))
modes = timed(out, "modes 6 L19", lambda: g.modes(long, 90.0, count=6))
short = g.TapeModel(g.TapeParameters(length_ratio=4))
crit = timed(out, "critical_speeds L4", lambda: g.critical_speeds(short))
timed(out, "sweep 5 speeds L4",
      lambda: g.sweep(short, [0.0, 20.0, 40.0, 60.0, 80.0], count=4, progress=False))
static = timed(out, "static L19", lambda: g.solve_static(long, 50.0))
strip = bearing.BearingModel(g.TapeParameters(), bearing.AirParameters(), velocity=4.0,
                             wrap_angle=math.radians(15), infinitely_wide=True)
timed(out, "bearing 1-D", lambda: bearing.solve_steady(strip))
out["numbers"] = [float(run.load_point[-1]), float(modes.omega[0]),
                  float(crit.critical_speed), float(static.load_point_deflection)]
print(json.dumps(out))
'''


def run_tree(tree: str) -> dict:
    """One run of the cases on ``tree``, in a fresh interpreter outside any source tree."""
    env = {**os.environ, "PYTHONPATH": tree}
    proc = subprocess.run([sys.executable, "-c", CASES], env=env, capture_output=True,
                          text=True, cwd=tempfile.gettempdir())
    if proc.returncode:
        sys.exit(f"{tree}: {proc.stderr.strip().splitlines()[-1]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main() -> None:
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    trees = {"old": os.path.abspath(sys.argv[1]), "new": os.path.abspath(sys.argv[2])}
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else DEFAULT_ROUNDS
    runs: dict[str, list[dict]] = {name: [] for name in trees}
    for k in range(rounds):
        for name in (list(trees) if k % 2 == 0 else list(trees)[::-1]):
            runs[name].append(run_tree(trees[name]))
    print(f"{'case':24s} {'old (s)':>10s} {'new (s)':>10s} {'new/old':>8s}  ({rounds} rounds)")
    for case in runs["old"][0]:
        if case == "numbers":
            continue
        old = statistics.median(r[case] for r in runs["old"])
        new = statistics.median(r[case] for r in runs["new"])
        print(f"{case:24s} {old:10.3f} {new:10.3f} {new / old:8.2f}")
    for name in trees:
        print(f"numbers {name}: {runs[name][0]['numbers']}")


if __name__ == "__main__":
    main()
