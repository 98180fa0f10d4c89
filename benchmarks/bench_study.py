"""Benchmark a 10 x 10 (speed, tension) stability study on the three executors.

    python benchmarks/bench_study.py [--rounds 3] [--spacing 7.9375e-4] [--compute modes]

The study (L_x/L_y = 4, a coarse grid, ``modes`` with the stability of each point) runs in
this process (1 worker), in 2 local worker processes, and on a local Dask cluster of two
single-threaded worker processes, in alternating rounds; prints the medians (s), the
speed-ups over 1 worker, the work per point, and the scheduling overhead per task of each
executor measured with empty tasks (the same chunking, nothing computed). Needs
``pip install "gyroshell[cluster]"``. Timings on a shared machine vary: read the medians.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from gyroshell import TapeParameters, run_study

SPEEDS = np.linspace(0.0, 130.0, 10)
TENSIONS = np.linspace(40.0, 120.0, 10)


def _noop(*args):
    return None


def overhead(executor: str, tasks: int, address: str | None) -> float:
    """Seconds per empty task through the executor (pool start-up included for processes)."""
    t0 = time.perf_counter()
    if executor == "processes":
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(max_workers=2) as pool:
            list(pool.map(_noop, range(tasks)))
    else:
        from distributed import Client

        with Client(address) as client:
            client.gather([client.submit(_noop, i, pure=False) for i in range(tasks)])
    return (time.perf_counter() - t0) / tasks


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--spacing", type=float, default=6.35e-3 / 8, help="m (default 8 across)")
    ap.add_argument("--compute", default="modes")
    args = ap.parse_args(argv)
    from distributed import LocalCluster

    base = TapeParameters(length_ratio=4, spacing=args.spacing)
    vary = {"velocity": list(SPEEDS), "tension": list(TENSIONS)}
    points = len(SPEEDS) * len(TENSIONS)
    t0 = time.perf_counter()
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    startup = time.perf_counter() - t0
    times: dict[str, list[float]] = {"1 worker": [], "2 processes": [], "dask 2 workers": []}
    tables = {}
    chunk = {}
    try:
        for r in range(args.rounds):
            for name, kw in (("1 worker", {"workers": 1}), ("2 processes", {"workers": 2}),
                             ("dask 2 workers", {"scheduler": cluster.scheduler_address})):
                t = time.perf_counter()
                res = run_study(base, vary=vary, compute=args.compute, progress=False, **kw)
                times[name].append(time.perf_counter() - t)
                tables[name], chunk[name] = res.table, res.info["chunk_size"]
                print(f"round {r + 1}: {name:15s} {times[name][-1]:7.2f} s", flush=True)
        null = {"processes": overhead("processes", 200, None),
                "dask": overhead("dask", 200, cluster.scheduler_address)}
    finally:
        cluster.close()
    same = all(tables[n].equals(tables["1 worker"]) for n in tables)
    base_t = statistics.median(times["1 worker"])
    print(f"\n{points} points, L_x/L_y = 4, {base.width / args.spacing:.0f} intervals across, "
          f"compute={args.compute}; identical rows on every executor: {same}")
    print(f"{'executor':16s} {'median (s)':>10s} {'speed-up':>9s} {'chunk':>6s}")
    for name, ts in times.items():
        med = statistics.median(ts)
        print(f"{name:16s} {med:10.2f} {base_t / med:9.2f} {chunk[name]:6d}")
    work = base_t / points
    print(f"work per point (1 worker): {1e3 * work:.1f} ms")
    for name, cost in null.items():
        print(f"scheduling overhead per empty task, {name}: {1e3 * cost:.2f} ms "
              f"({100 * cost / work:.1f} % of a point's work)")
    print(f"Dask LocalCluster start-up (not in the medians): {startup:.2f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
