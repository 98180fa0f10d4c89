"""Time and memory of the refusals of hostile requests, on the CLI and the Python API.

CLI: every case runs in a fresh process and must exit with code 2 in one stderr line; the
table gives the median and maximum wall time of several rounds (cases alternate within a
round) and the peak resident memory. `gyroshell --help` is the baseline: a refusal should
cost no more than starting up. API: every case is a call that must raise ParameterError;
they run in one interpreter after `import gyroshell` (and the objects they need), and the
table gives the median and maximum time of the call alone.

    python benchmarks/bench_refusals.py [--rounds 5] [--only cli|api]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

STUDY = ["study", "--vary", "velocity=0:10:2", "--compute", "static", "--spacing", "7.9e-4"]

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
    # issue 18: the newer surfaces
    "bearing --nx 50000 --ny 100000": ["bearing", "--velocity", "4", "--nx", "50000",
                                       "--ny", "100000"],
    "bearing --span 1e-12": ["bearing", "--infinitely-wide", "--velocity", "4",
                             "--span", "1e-12"],
    "bearing --nx 8 --ny 8": ["bearing", "--velocity", "4", "--nx", "8", "--ny", "8"],
    "bearing --infinitely-wide --ny 9": ["bearing", "--infinitely-wide", "--velocity", "4",
                                         "--ny", "9"],
    "bearing --edges simply-supported": ["bearing", "--velocity", "4", "--edges",
                                         "simply-supported"],
    "bearing --out-dir missing/dir": ["bearing", "--velocity", "4", "--out-dir", "missing/dir"],
    "bearing --config folder": ["bearing", "--config", "."],
    "bearing --config binary": ["bearing", "--config", "binary.toml"],
    "frf --frequencies 1e300:1e301:3": ["frf", "--frequencies", "1e300:1e301:3"],
    "frf --frequencies -5,10": ["frf", "--frequencies", "-5,10"],
    "frf --tol 2": ["frf", "--frequencies", "0:1000:5", "--tol", "2"],
    "transient --contact-ramp alone": ["transient", "--steps", "5", "--dt", "2e-6",
                                       "--contact-ramp", "1e-4"],
    "campbell --velocity 5": ["campbell", "--velocity", "5"],
    "campbell --orders 0,-1": ["campbell", "--orders", "0,-1"],
    "study --scheduler http://...": [*STUDY, "--scheduler", "http://127.0.0.1:8786"],
    "study --scheduler port 99999": [*STUDY, "--scheduler", "tcp://127.0.0.1:99999"],
    "study --scheduler closed port": [*STUDY, "--scheduler", "tcp://127.0.0.1:9"],
    "study --cache binary": [*STUDY, "--cache", "binary.toml"],
}

#: Python API refusals: (setup, call), each call must raise gyroshell's ParameterError.
API_SETUP = r"""
import math
import numpy as np
import gyroshell as g
from gyroshell import bearing
params = g.TapeParameters()
air = bearing.AirParameters()
strip = bearing.BearingModel(params, air, velocity=4.0, wrap_angle=math.radians(15),
                             infinitely_wide=True)
flying = bearing.solve_steady(strip)
small = g.TapeModel(g.TapeParameters(spacing=7.9375e-4))
"""
API_CASES = {
    "BearingModel(params, {'viscosity': 1e-5})":
        "bearing.BearingModel(params, {'viscosity': 1e-5}, velocity=4.0, wrap_angle=0.26)",
    "BearingModel(None)": "bearing.BearingModel(None, air, velocity=4.0, wrap_angle=0.26)",
    "BearingModel nx=50000 ny=100000":
        "bearing.BearingModel(params, air, velocity=4.0, wrap_angle=0.26, nx=50000, "
        "ny=100000)",
    "solve_steady(None)": "bearing.solve_steady(None)",
    "solve_steady(tension=-5)": "bearing.solve_steady(strip, tension=-5.0)",
    "gyroshell.load(folder)": "g.load('.')",
    "gyroshell.load(empty .nc)": "g.load('empty.nc')",
    "gyroshell.load(binary .nc)": "g.load('binary.nc')",
    "TapeParameters(tension=-5)": "g.TapeParameters(tension=-5.0)",
    "bearing.march(model)": "bearing.march(strip, dt=1e-6, steps=10)",
    "bearing.march(steps=1e8)": "bearing.march(flying, dt=1e-6, steps=10**8)",
    "bearing.march(dt=1e-300)": "bearing.march(flying, dt=1e-300, steps=10)",
    "march(path of the wrong shape)":
        "g.march(small, 10.0, dt=1e-6, steps=20, "
        "load=g.MovingLoad(lambda t: np.zeros((3, np.size(t)))))",
    "march(steps=3e7, moving head)":
        "g.march(small, 10.0, dt=1e-6, steps=3 * 10**7, "
        "load=g.MovingLoad(g.StraightPath((0.005, 0.003))))",
    "frequency_response(1e300 rad/s)":
        "g.frequency_response(small, 10.0, [1e300, 1e301], method='direct')",
    "scheduler address port 99999":
        "gyroshell.studies.scheduler.check_address('tcp://127.0.0.1:99999')",
    "scheduler address http://": "gyroshell.studies.scheduler.check_address('http://a:1')",
}

API_RUNNER = r"""
import json, statistics, sys, time
import gyroshell.studies.scheduler
from gyroshell.core.errors import ParameterError
cases = json.loads(sys.argv[1]); rounds = int(sys.argv[2])
out = {}
for name, call in cases.items():
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        try:
            eval(call)
        except ParameterError:
            times.append(time.perf_counter() - start)
        else:
            raise SystemExit(f"{name}: no ParameterError")
    out[name] = times
print(json.dumps(out))
"""


def make_hostile_files(cwd: str) -> None:
    """The broken files the cases read: binary bytes, an empty .nc."""
    with open(os.path.join(cwd, "binary.toml"), "wb") as fh:
        fh.write(bytes(range(256)) * 4)
    with open(os.path.join(cwd, "binary.nc"), "wb") as fh:
        fh.write(bytes(range(256)) * 4)
    open(os.path.join(cwd, "empty.nc"), "wb").close()


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


def cli_table(rounds: int, cwd: str) -> None:
    """Median and maximum wall time and peak RSS of every CLI case."""
    times: dict[str, list[float]] = {name: [] for name in CASES}
    memory: dict[str, float] = {}
    for _ in range(rounds):
        for name, argv in CASES.items():
            wall, rss, code, err = run_once(argv, cwd)
            expected = 0 if name.startswith("--help") else 2
            if code != expected or (expected and len(err.strip().splitlines()) != 1):
                raise SystemExit(f"{name}: exit {code}, stderr {err!r}")
            times[name].append(wall)
            memory[name] = max(memory.get(name, 0.0), rss)
    base = statistics.median(times["--help (baseline)"])
    print(f"{'CLI case':40} {'median s':>9} {'max s':>7} {'x --help':>9} {'peak RSS MB':>12}")
    for name in CASES:
        med = statistics.median(times[name])
        print(f"{name:40} {med:9.3f} {max(times[name]):7.3f} {med / base:9.2f} "
              f"{memory[name]:12.1f}")


def api_table(rounds: int, cwd: str) -> None:
    """Median and maximum time of every API refusal, in one interpreter."""
    import json

    env = {**os.environ, "GYROSHELL_MEMORY_LIMIT": "8e9"}
    proc = subprocess.run([sys.executable, "-c", API_SETUP + API_RUNNER,
                           json.dumps(API_CASES), str(rounds)], cwd=cwd, env=env,
                          capture_output=True, text=True)
    if proc.returncode:
        raise SystemExit(proc.stderr.strip().splitlines()[-1])
    times = json.loads(proc.stdout)
    print(f"{'API case':40} {'median ms':>10} {'max ms':>8}")
    for name, values in times.items():
        print(f"{name:40} {1e3 * statistics.median(values):10.3f} {1e3 * max(values):8.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--only", choices=("cli", "api"), default=None)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as cwd:
        make_hostile_files(cwd)
        if args.only != "api":
            cli_table(args.rounds, cwd)
        if args.only != "cli":
            api_table(max(args.rounds, 20), cwd)


if __name__ == "__main__":
    main()
