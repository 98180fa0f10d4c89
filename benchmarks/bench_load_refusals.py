"""Time of gyroshell.load's and --config's refusals of broken files (medians and maxima).

API: in one process (gyroshell, xarray and h5netcdf imported once), each broken file is
loaded ``--rounds`` times. CLI: ``gyroshell static --config FILE`` in a fresh process per
round, against ``gyroshell --help`` as the start-up baseline.

    python benchmarks/bench_load_refusals.py [--rounds 7]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def broken_results(folder: Path) -> dict[str, Path]:
    import h5py

    from gyroshell import TapeModel, TapeParameters, solve_static

    good = folder / "static.nc"
    solve_static(TapeModel(TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)), 10.0
                 ).save(good)
    data = good.read_bytes()
    cases = {"empty": b"", "truncated": data[: len(data) // 2], "not NetCDF": b"text" * 50}
    files = {}
    for name, content in cases.items():
        files[name] = folder / f"{name.replace(' ', '_')}.nc"
        files[name].write_bytes(content)
    for name, change in (("negative tension", ("parameters", "tension", -5)),
                         ("extra parameter", ("parameters", "colour", "red")),
                         ("grid 10**7", ("grid", "ny", 10**7))):
        path = folder / f"{name.replace(' ', '_').replace('*', '')}.nc"
        path.write_bytes(data)
        with h5py.File(path, "r+") as fh:
            attr, key, value = change
            stored = json.loads(fh.attrs[attr])
            stored[key] = value
            fh.attrs[attr] = json.dumps(stored)
        files[name] = path
    (folder / "folder.nc").mkdir()
    files["folder"] = folder / "folder.nc"
    (folder / "empty.csv").write_bytes(b"")
    files["empty CSV"] = folder / "empty.csv"
    return files


def time_api(files: dict[str, Path], rounds: int) -> None:
    import gyroshell
    from gyroshell import ParameterError

    print(f"{'gyroshell.load of':<22} {'median ms':>10} {'max ms':>8}")
    for name, path in files.items():
        times = []
        for _ in range(rounds):
            t0 = time.perf_counter()
            try:
                gyroshell.load(path)
            except ParameterError:
                pass
            times.append(time.perf_counter() - t0)
        print(f"{name:<22} {1e3 * statistics.median(times):10.2f} {1e3 * max(times):8.2f}")


def time_cli(folder: Path, rounds: int) -> None:
    configs = {"UTF-16": "tension = 75\n".encode("utf-16"), "binary": bytes(range(256)) * 4}
    print(f"\n{'CLI':<28} {'median s':>9} {'max s':>7} {'exit':>5}")
    cases = {"--help (baseline)": ["--help"]}
    for name, content in configs.items():
        path = folder / f"{name}.toml"
        path.write_bytes(content)
        cases[f"static --config {name}"] = ["static", "--config", str(path)]
    (folder / "tape.toml").mkdir()
    cases["static --config FOLDER"] = ["static", "--config", str(folder / "tape.toml")]
    for name, argv in cases.items():
        times, code = [], None
        for _ in range(rounds):
            t0 = time.perf_counter()
            code = subprocess.run([sys.executable, "-m", "gyroshell", *argv],
                                  capture_output=True).returncode
            times.append(time.perf_counter() - t0)
        print(f"{name:<28} {statistics.median(times):9.3f} {max(times):7.3f} {code:5d}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        time_api(broken_results(folder), args.rounds)
        time_cli(folder, args.rounds)


if __name__ == "__main__":
    main()
