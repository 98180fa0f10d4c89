"""Time and memory of the CLI's refusals of hostile requests (each in a fresh process).

Every case must exit with code 2 in one stderr line; the table gives the median wall time of
several rounds (cases alternate within a round) and the peak resident memory of the process.
`gyroshell --help` is the baseline: a refusal should cost no more than starting up.

    python benchmarks/bench_refusals.py [--rounds 5]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

CASES = {
    "--help (baseline)": ["--help"],
    "static --spacing 1e-9": ["static", "--spacing", "1e-9"],
    "static --length-ratio 1e12": ["static", "--length-ratio", "1e12"],
    "static --spacing 5e-6 (memory)": ["static", "--spacing", "5e-6"],
    "critical --length-ratio 1e-6": ["critical", "--length-ratio", "1e-6"],
    "transient --steps 1e12": ["transient", "--steps", "1e12", "--dt", "2e-6"],
    "transient snapshots every step": ["transient", "--length-ratio", "19", "--steps",
                                       "200000", "--dt", "2e-6", "--snapshot-every", "1",
                                       "--snapshots", "s.npz"],
    "sweep --velocities 0:100:1e-12": ["sweep", "--velocities", "0:100:1e-12"],
    "sweep --velocities 0:inf:10": ["sweep", "--velocities", "0:inf:10"],
    "static --velocity 1e200": ["static", "--velocity", "1e200"],
    "transient --dt 1e-170": ["transient", "--steps", "5", "--dt", "1e-170"],
    "static --youngs-modulus 1e-300": ["static", "--youngs-modulus", "1e-300"],
    "sweep --plot s.xyz": ["sweep", "--plot", "s.xyz"],
    "critical --velocity 5": ["critical", "--velocity", "5"],
}


def run_once(argv: list[str], cwd: str) -> tuple[float, float, int, str]:
    """(wall s, peak RSS MB, exit code, stderr) of one `python -m gyroshell argv`."""
    start = time.perf_counter()
    env = {**os.environ, "GYROSHELL_MEMORY_LIMIT": "8e9"}  # the same refusals on any machine
    proc = subprocess.Popen([sys.executable, "-m", "gyroshell", *argv], cwd=cwd, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    return wall, usage.ru_maxrss / 1024.0, proc.returncode, err


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    times: dict[str, list[float]] = {name: [] for name in CASES}
    memory: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as cwd:
        for _ in range(args.rounds):
            for name, argv in CASES.items():
                wall, rss, code, err = run_once(argv, cwd)
                expected = 0 if name.startswith("--help") else 2
                if code != expected or (expected and len(err.strip().splitlines()) != 1):
                    raise SystemExit(f"{name}: exit {code}, stderr {err!r}")
                times[name].append(wall)
                memory[name] = max(memory.get(name, 0.0), rss)
    base = statistics.median(times["--help (baseline)"])
    print(f"{'case':36} {'median s':>9} {'x --help':>9} {'peak RSS MB':>12}")
    for name in CASES:
        med = statistics.median(times[name])
        print(f"{name:36} {med:9.3f} {med / base:9.2f} {memory[name]:12.1f}")


if __name__ == "__main__":
    main()
