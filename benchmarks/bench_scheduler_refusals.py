"""Time of the refusals of `study`, `campbell` and `sweep` (issue 18): scheduler addresses
(malformed, a closed port, servers that are not Dask's), damaged caches, ignored options.

Each CLI case runs in a fresh process (`python -m gyroshell ...`) and must exit with code 2
in one stderr line; each API case calls `run_study` (or `campbell`) in this process and must
raise ParameterError. Cases alternate within a round; the table gives the median and the
maximum over the rounds. The fake servers answer after `--connect-timeout 1` at the latest
(silent ones: by design, the timeout is what they cost), everything else at once.

    python benchmarks/bench_scheduler_refusals.py [--rounds 5]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from fake_servers import FakeServer, closed_port  # noqa: E402 - the tests' real sockets

WIDTH = 6.35e-3
COARSE = ["--spacing", str(WIDTH / 8), "--length-ratio", "2"]
STUDY = ["study", *COARSE, "--vary", "tension=80,90", "--compute", "modes", "--quiet"]


def cli_cases(servers: dict[str, FakeServer], cwd: Path) -> dict[str, list[str]]:
    """Command lines, by name (the cache files they name are written in ``cwd``)."""
    (cwd / "binary.jsonl").write_bytes(bytes(range(256)))
    (cwd / "edited.jsonl").write_text('{"key": "' + "0" * 32 + '", "row": {}}\n[1]\n')
    cases = {"--help (baseline)": ["--help"],
             "scheduler http://": [*STUDY, "--scheduler", "http://127.0.0.1:8786"],
             "scheduler port 99999": [*STUDY, "--scheduler", "tcp://127.0.0.1:99999"],
             "scheduler closed port": [*STUDY, "--scheduler",
                                       f"tcp://127.0.0.1:{closed_port()}"],
             "cache binary": [*STUDY, "--workers", "1", "--cache", "binary.jsonl"],
             "cache restructured": [*STUDY, "--workers", "1", "--cache", "edited.jsonl"],
             "campbell --velocity 5": ["campbell", *COARSE, "--velocity", "5"],
             "campbell --orders 0,-1": ["campbell", *COARSE, "--circumference", "0.01",
                                        "--orders=0,-1"]}
    for mode, server in servers.items():
        cases[f"fake server: {mode}"] = [*STUDY, "--scheduler",
                                         f"tcp://127.0.0.1:{server.port}",
                                         "--connect-timeout", "1"]
    return cases


def run_cli(argv: list[str], cwd: Path) -> tuple[float, int, str]:
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "gyroshell", *argv], cwd=cwd,
                          capture_output=True, text=True)
    return time.perf_counter() - start, proc.returncode, proc.stderr


def api_cases(servers: dict[str, FakeServer], cwd: Path) -> dict[str, dict]:
    cases = {"scheduler http://": {"scheduler": "http://127.0.0.1:8786"},
             "scheduler port 99999": {"scheduler": "tcp://127.0.0.1:99999"},
             "scheduler closed port": {"scheduler": f"tcp://127.0.0.1:{closed_port()}"},
             "cache binary": {"workers": 1, "cache": cwd / "binary.jsonl"},
             "cache restructured": {"workers": 1, "cache": cwd / "edited.jsonl"}}
    for mode, server in servers.items():
        cases[f"fake server: {mode}"] = {"scheduler": f"tcp://127.0.0.1:{server.port}",
                                         "connect_timeout": 1.0}
    return cases


def run_api(kwargs: dict) -> float:
    from gyroshell import ParameterError, TapeParameters, run_study

    base = TapeParameters(length_ratio=2, spacing=WIDTH / 8)
    start = time.perf_counter()
    try:
        run_study(base, vary={"tension": [80.0, 90.0]}, compute="modes", progress=False,
                  **kwargs)
    except ParameterError:
        return time.perf_counter() - start
    raise SystemExit(f"{kwargs}: not refused")


def table(title: str, times: dict[str, list[float]]) -> None:
    print(f"\n{title}\n{'case':30} {'median s':>9} {'max s':>9}")
    for name, values in times.items():
        print(f"{name:30} {statistics.median(values):9.3f} {max(values):9.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    servers = {mode: FakeServer(mode) for mode in FakeServer.REPLIES}
    try:
        with tempfile.TemporaryDirectory() as tmp:
            cwd = Path(tmp)
            cli, api = cli_cases(servers, cwd), api_cases(servers, cwd)
            cli_times = {name: [] for name in cli}
            api_times = {name: [] for name in api}
            run_api(api["cache binary"])  # the imports, before the rounds
            for _ in range(args.rounds):
                for name, argv in cli.items():
                    wall, code, err = run_cli(argv, cwd)
                    expected = 0 if name.startswith("--help") else 2
                    if code != expected or (expected and len(err.strip().splitlines()) != 1):
                        raise SystemExit(f"{name}: exit {code}, stderr {err!r}")
                    cli_times[name].append(wall)
                for name, kwargs in api.items():
                    api_times[name].append(run_api(kwargs))
    finally:
        for server in servers.values():
            server.stop()
    print(f"{os.cpu_count()} CPUs, {args.rounds} rounds")
    table("CLI (fresh process, start-up included)", cli_times)
    table("API (run_study in this process)", api_times)


if __name__ == "__main__":
    main()
