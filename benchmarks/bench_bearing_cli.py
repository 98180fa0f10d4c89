"""`gyroshell bearing`: its time estimate against measured solves, and its refusals' times.

    PYTHONPATH=. python benchmarks/bench_bearing_cli.py [--rounds 5] [--large]
    PYTHONPATH=. python benchmarks/bench_bearing_cli.py --baseline DIR [--rounds 5]

1. For bearings of growing size (1-D and 2-D, the Table 1 tape at 4 m/s over 15°) prints
   the unknowns, the estimated seconds of one Newton iteration that factors afresh
   (:func:`gyroshell.cli.bearing.iteration_seconds`), the measured first Newton iteration
   (a fresh factorization and its line search, after the starting state), the estimated
   range of the whole solve (the progress line's "estimated A to B") and the measured
   whole solve (starting state included), with Newton's iteration count. ``--large`` adds
   the 0.01 m/s 2-D case of issue 18 (about a minute to several on a shared machine).
2. Times the bearing's refusals (issue 18, causes 8, 9, 11) in fresh processes: median and
   largest wall time of ``--rounds`` rounds, beside ``gyroshell --help`` as the baseline.

``--baseline DIR`` instead times ``gyroshell bearing --width 12.65e-3 --velocity 4 --json``
(issue 21) here and on the source tree DIR (e.g. ``git archive main | tar -x -C DIR``) in
fresh processes, alternating, one BLAS thread: medians of wall and CPU seconds (the
child's user + system time), their ratios, and the readings to the digits compared.

Timings on a shared machine vary by factors of two or more: read the ratios, not digits.
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

#: (label, BearingModel keyword arguments) of the estimate table.
SOLVES = [
    ("1-D default", dict(infinitely_wide=True)),
    ("1-D nx 5000", dict(infinitely_wide=True, nx=5000)),
    ("2-D 200 x 20", dict(nx=200, ny=20)),
    ("2-D 200 x 40", dict(nx=200, ny=40)),
    ("2-D 200 x 80", dict(nx=200, ny=80)),
    ("2-D 400 x 80", dict(nx=400, ny=80)),
    ("2-D default 6.35 mm", dict()),
]
LARGE = [("2-D default 6.35 mm, 0.01 m/s", dict(velocity=0.01))]

#: (label, argv) of the refusals, each one line and exit code 2.
REFUSALS = {
    "--help (baseline)": ["--help"],
    "bearing --infinitely-wide --ny 9": ["bearing", "--velocity", "4", "--infinitely-wide",
                                         "--ny", "9"],
    "bearing --infinitely-wide --uniform": ["bearing", "--velocity", "4",
                                            "--infinitely-wide", "--uniform"],
    "bearing --edges simply-supported": ["bearing", "--velocity", "4", "--edges",
                                         "simply-supported"],
    "bearing --spacing 1e-4": ["bearing", "--velocity", "4", "--spacing", "1e-4"],
    "bearing D, k and --thickness": ["bearing", "--velocity", "4", "--bending-rigidity",
                                     "3e-6", "--foundation-stiffness", "2e8", "--thickness",
                                     "1e-5"],
    "bearing --out missing/run": ["bearing", "--velocity", "4", "--out", "missing/run"],
    "bearing --out ro (read-only summary.json)": ["bearing", "--velocity", "4", "--out",
                                                  "ro"],
    "bearing without a velocity": ["bearing", "--infinitely-wide"],
}


def measure(kwargs: dict) -> dict:
    """One solve as the CLI runs it: unknowns, estimates and measured seconds."""
    from gyroshell import TapeParameters
    from gyroshell.bearing import AirParameters, BearingModel
    from gyroshell.bearing.steady import initial_state, solve_steady
    from gyroshell.cli.bearing import iteration_seconds, solve_seconds

    kwargs = {"velocity": 4.0, **kwargs}
    model = BearingModel(TapeParameters(), AirParameters(),
                         wrap_angle=math.radians(15.0), **kwargs)
    stamps: list[float] = []
    start = time.perf_counter()
    z0 = None if model.smooth_contact else initial_state(model)   # as the CLI starts it
    started = time.perf_counter()
    sol = solve_steady(model, z0=z0, iteration_log=lambda _: stamps.append(time.perf_counter()))
    total = time.perf_counter() - start
    each = iteration_seconds(model)
    low, _, high = solve_seconds(model)
    return {"unknowns": model.unknowns, "estimate": each, "first": stamps[0] - started,
            "low": low, "high": high, "total": total,
            "iterations": sol.info.iterations}


def estimate_table(cases) -> None:
    print("| case | unknowns | est. s/iteration | measured 1st | est. range, s | measured, s "
          "| ratio 1st/est. | Newton |")
    print("|---|---|---|---|---|---|---|---|")
    for label, kwargs in cases:
        r = measure(kwargs)
        print(f"| {label} | {r['unknowns']} | {r['estimate']:.3g} | {r['first']:.3g} | "
              f"{r['low']:.3g}-{r['high']:.3g} | {r['total']:.3g} | "
              f"{r['first'] / r['estimate']:.2f} | {r['iterations']} |", flush=True)


def run_once(argv: list[str], cwd: str) -> tuple[float, int, str]:
    """(wall s, exit code, stderr) of one `python -m gyroshell argv` in ``cwd``."""
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "gyroshell", *argv], cwd=cwd,
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    return time.perf_counter() - start, proc.returncode, proc.stderr


def refusal_table(rounds: int) -> None:
    times: dict[str, list[float]] = {name: [] for name in REFUSALS}
    with tempfile.TemporaryDirectory() as cwd:
        os.mkdir(os.path.join(cwd, "ro"))
        summary = os.path.join(cwd, "ro", "summary.json")
        with open(summary, "w") as fh:
            fh.write("{}\n")
        os.chmod(summary, 0o444)
        for _ in range(rounds):
            for name, argv in REFUSALS.items():
                wall, code, err = run_once(argv, cwd)
                lines = err.strip().splitlines()
                expected = 0 if argv == ["--help"] else 2
                if code != expected or (expected and len(lines) != 1):
                    raise SystemExit(f"{name}: exit {code}, stderr {err!r}")
                times[name].append(wall)
    print(f"\n| refusal | median, s | max, s |   ({rounds} rounds, fresh processes)")
    print("|---|---|---|")
    for name, walls in times.items():
        print(f"| {name} | {statistics.median(walls):.3f} | {max(walls):.3f} |")


#: The command timed against a baseline tree (``--baseline``): the 12.65 mm tape's default
#: 2-D grid (issue 21).
WIDE_COMMAND = ["bearing", "--width", "12.65e-3", "--velocity", "4", "--json"]


def timed_command(argv: list[str], source: str) -> dict:
    """Wall and CPU seconds (user + system of the child) of one ``python -m gyroshell
    argv`` run on the code under ``source``, and its JSON summary."""
    env = {**os.environ, "PYTHONPATH": source, "OMP_NUM_THREADS": "1"}
    before = os.times()
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "gyroshell", *argv], cwd=source, env=env,
                          capture_output=True, text=True, check=True)
    wall = time.perf_counter() - start
    after = os.times()
    cpu = (after.children_user - before.children_user
           + after.children_system - before.children_system)
    return {"wall": wall, "cpu": cpu, "summary": json.loads(proc.stdout)}


def baseline_table(baseline: str, rounds: int) -> None:
    """``WIDE_COMMAND`` on this tree and on ``baseline`` in alternating rounds: medians of
    wall and CPU seconds, their ratios, Newton's iterations and the readings' digits."""
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    trees = {"before": baseline, "after": here}
    runs: dict[str, list[dict]] = {k: [] for k in trees}
    print(f"gyroshell {' '.join(WIDE_COMMAND)}: {rounds} alternating rounds, load "
          f"{os.getloadavg()[0]:.2f} at the start", flush=True)
    for r in range(rounds):
        for name in (("before", "after") if r % 2 == 0 else ("after", "before")):
            runs[name].append(timed_command(WIDE_COMMAND, trees[name]))
        print(f"round {r + 1}: " + ", ".join(
            f"{k} wall {v[-1]['wall']:.2f} s cpu {v[-1]['cpu']:.2f} s"
            for k, v in runs.items()) + f" (load {os.getloadavg()[0]:.2f})", flush=True)
    med = {k: {q: statistics.median(run[q] for run in v) for q in ("wall", "cpu")}
           for k, v in runs.items()}
    print("\n| tree | wall, s | CPU, s | Newton | h_c, m | h_min, m | air force, N |")
    print("|---|---|---|---|---|---|---|")
    for k, v in runs.items():
        s = v[-1]["summary"]
        print(f"| {k} | {med[k]['wall']:.2f} | {med[k]['cpu']:.2f} | "
              f"{s['newton_iterations']} | {s['central_spacing']:.10g} | "
              f"{s['minimum_spacing']:.10g} | {s['air_force']:.11g} |")
    print(f"| after/before | {med['after']['wall'] / med['before']['wall']:.2f} | "
          f"{med['after']['cpu'] / med['before']['cpu']:.2f} | | | | |")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--large", action="store_true",
                        help="also the 0.01 m/s 2-D solve of issue 18")
    parser.add_argument("--baseline", metavar="DIR",
                        help="only time the 12.65 mm tape's default 2-D command here and "
                             "on the source tree DIR, in alternating rounds")
    args = parser.parse_args(argv)
    if args.baseline:
        baseline_table(args.baseline, args.rounds)
        return 0
    estimate_table(SOLVES + (LARGE if args.large else []))
    refusal_table(args.rounds)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
