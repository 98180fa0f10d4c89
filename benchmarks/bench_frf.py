"""Benchmark: 1,000-frequency response at L_x/L_y = 19, direct solves against the reduced model.

The reduced (rational Krylov) model runs on all 1,000 frequencies; the direct route (one
sparse complex LU per frequency) is timed on a sample spread over the band and its median
per-frequency time is multiplied by 1,000 (running all 1,000 would take most of an hour on
a shared 2-core machine). Rounds alternate; medians are printed with the speed-up, and
the reduced model's actual error against the sampled direct solves beside its estimate.
Usage::

    PYTHONPATH=. python benchmarks/bench_frf.py [--repeats 3] [--sample 20] [--quick]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

from gyroshell import TapeModel, TapeParameters
from gyroshell.engines.frequency_response import direct_response, frequency_response

VELOCITY = 50.0  # m/s
DAMPING = 100.0  # N s/m^3
OMEGA_MAX = 1.5e5  # rad/s
COUNT = 1000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="alternating rounds (median)")
    parser.add_argument("--sample", type=int, default=20, help="direct solves timed per round")
    parser.add_argument("--quick", action="store_true", help="L_x/L_y = 4, for a smoke test")
    args = parser.parse_args()
    ratio = 4.0 if args.quick else 19.0
    model = TapeModel(TapeParameters(length_ratio=ratio))
    omega = np.linspace(0.0, OMEGA_MAX, COUNT)
    sample = np.linspace(0, COUNT - 1, args.sample).astype(int)
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; L_x/L_y = "
          f"{ratio:g}, {model.unknowns} unknowns, V = {VELOCITY:g} m/s, c = {DAMPING:g} N s/m^3, "
          f"{COUNT} frequencies in [0, {OMEGA_MAX:g}] rad/s")
    reduced_t, direct_t, errors, estimates, info = [], [], [], [], {}
    for _ in range(args.repeats):
        start = time.perf_counter()
        res = frequency_response(model, VELOCITY, omega, damping=DAMPING, progress=False)
        reduced_t.append(time.perf_counter() - start)
        info = res.info
        start = time.perf_counter()
        direct = direct_response(model, VELOCITY, omega[sample], damping=DAMPING,
                                 progress=False)
        direct_t.append((time.perf_counter() - start) / len(sample))
        ref = direct.response[:, 0]
        errors.append(float(np.max(np.abs(res.response[sample, 0] - ref) / np.abs(ref))))
        estimates.append(float(res.error_estimate.max()))
    r, d = statistics.median(reduced_t), statistics.median(direct_t)
    print(f"reduced (auto): {r:.2f} s for {COUNT} frequencies ({info['factorizations']} "
          f"factorizations, basis {info['basis_size']}, {info['direct_solves']} direct "
          f"fall-backs); largest estimated error {max(estimates):.1e}, actual error at the "
          f"{len(sample)} sampled frequencies {max(errors):.1e}")
    print(f"direct: {d:.3f} s per frequency, {COUNT * d:.0f} s for {COUNT} (extrapolated)")
    print(f"speed-up: {COUNT * d / r:.0f}x")


if __name__ == "__main__":
    main()
