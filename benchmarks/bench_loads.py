"""Benchmark: a moving, intermittent load costs no more per Newmark step than the step load.

Per-step time (march loop / steps) of the same stepper under (a) the paper's fixed step
load and (b) a head crossing the tape obliquely with contact windows, in alternating
rounds; medians and the ratio b / a. Also the load update alone (adding the head's cells
into a right-hand side) against a full-vector fixed-load update. Usage::

    PYTHONPATH=. python benchmarks/bench_loads.py [--repeats 5] [--quick]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

from gyroshell import TapeModel, TapeParameters
from gyroshell.engines.newmark import Newmark
from gyroshell.tape.moving_loads import ContactWindows, MovingLoad, PreparedLoads, StraightPath

VELOCITY = 50.0  # m/s
DT = 2e-6  # s


def head(model: TapeModel) -> MovingLoad:
    """A head crossing from near x = 0.1 L_x, y = 0.1 L_y obliquely, on 30 of every 40 µs."""
    p = model.params
    steps_span = 0.8 * p.width / 200.0  # s to cross 80 % of the width at 200 m/s across
    return MovingLoad(StraightPath((0.1 * p.length, 0.1 * p.width),
                                   (0.5 * p.length / steps_span, 200.0)),
                      contact=ContactWindows(40e-6, 30e-6, ramp=3e-6), restart_path=True)


def update_times(model: TapeModel, repeats: int = 2000) -> tuple[float, float]:
    """Median seconds per call: fixed rhs += s f(t) F versus the moving head's add()."""
    rhs, tmp, force = np.zeros(model.unknowns), np.empty(model.unknowns), model.force
    prepared = PreparedLoads(model, [head(model)], DT * np.arange(repeats))

    def fixed(n):
        np.multiply(force, 1e-12, out=tmp)
        rhs.__iadd__(tmp)

    out = []
    for fn in (fixed, lambda n: prepared.add(n, 1e-12, rhs)):
        samples = []
        for _ in range(5):
            start = time.perf_counter()
            for n in range(repeats):
                fn(n)
            samples.append((time.perf_counter() - start) / repeats)
        out.append(statistics.median(samples))
    return out[0], out[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="alternating rounds (median)")
    parser.add_argument("--quick", action="store_true", help="fewer steps, for a smoke test")
    args = parser.parse_args()
    cases = [(4.0, 250), (19.0, 250)] if not args.quick else [(4.0, 20)]
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; V = {VELOCITY:g} "
          f"m/s, dt = {DT:g} s, medians of {args.repeats} alternating rounds")
    for ratio, steps in cases:
        model = TapeModel(TapeParameters(length_ratio=ratio))
        stepper = Newmark(model, VELOCITY, dt=DT)
        moving = head(model)
        stepper.march(10, progress=False)  # warm-up
        fixed_t, moving_t = [], []
        for _ in range(args.repeats):
            fixed_t.append(stepper.march(steps, progress=False).info["step_time"])
            moving_t.append(stepper.march(steps, load=moving, progress=False)
                            .info["step_time"])
        a, b = statistics.median(fixed_t), statistics.median(moving_t)
        fu, mu = update_times(model)
        print(f"L_x/L_y = {ratio:g} ({model.unknowns} unknowns, {steps} steps): step load "
              f"{1e3 * a:.3f} ms/step, moving intermittent head {1e3 * b:.3f} ms/step, "
              f"ratio {b / a:.3f}; load update alone: fixed {1e6 * fu:.1f} us, "
              f"moving head {1e6 * mu:.1f} us")


if __name__ == "__main__":
    main()
