"""Newton over rounded corners the tape wraps, at speed: this tree against a baseline.

    PYTHONPATH=. python benchmarks/bench_wrapped_newton.py --baseline DIR [--rounds 3]

The 1-D (infinitely wide) Table 1 tape over a 1 mm land at 2°/2° with both corners rounded
(``Module(1e-3, corner_radius=r_c)``), each on its default grid: r_c = 2.5 mm (wrapped by
the automatic choice) at 0.5, 1 and 4 m/s, and r_c = 1.2, 1.4, 1.7 mm at 4 m/s with
``arc_contact="wrapped"`` (the handover radii of ``benchmarks/bearing_arc_handover.py``);
``--point`` adds the point-contact model at 1.4 and 1.7 mm; ``--long`` the 4 mm land with
10 mm arcs on 8° flanks at 4°/4° (``tests/bearing/test_wrapped_arcs.py``) at 0.5 and
4 m/s (r_c column 10). Each solve runs in a fresh
process per round and tree (``DIR``: a tree of the state before the change, e.g.
``git archive main | tar -x -C DIR``), the trees alternating; prints per case the medians
of the wall time (s), Newton's iterations (every stage, pseudo-time step and pass
included), their ratios after/before, and the largest relative differences between the
trees' states: of the spacing h and the pressure p over the grid (the same grid in both),
and of the contact force on each half of the head (the corners'), N/m.
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
from pathlib import Path

CASES = [(2.5e-3, 0.5, "auto"), (2.5e-3, 1.0, "auto"), (2.5e-3, 4.0, "auto"),
         (1.2e-3, 4.0, "wrapped"), (1.4e-3, 4.0, "wrapped"), (1.7e-3, 4.0, "wrapped")]
POINT_CASES = [(1.4e-3, 4.0, "point"), (1.7e-3, 4.0, "point")]
LONG_CASES = [(10e-3, 0.5, "auto"), (10e-3, 4.0, "auto")]


def child(radius: float, velocity: float, mode: str, out: str) -> dict:
    """One solve in this process: its wall time, iterations and state (saved to ``out``)."""
    import time

    import numpy as np

    from gyroshell import TapeParameters
    from gyroshell.bearing import AirParameters, BearingModel
    from gyroshell.bearing.head import FlatHead, Module
    from gyroshell.bearing.steady import solve_steady

    deg = math.pi / 180.0
    if radius >= 10e-3:    # the long land of tests/bearing/test_wrapped_arcs.py
        head = FlatHead((Module(4e-3, corner_radius=radius),), 4 * deg, 4 * deg,
                        flank_angle=8 * deg, transducers=(0.0,))
    else:
        head = FlatHead((Module(1e-3, corner_radius=radius),), 2 * deg, 2 * deg,
                        transducers=(0.0,))
    model = BearingModel(TapeParameters(), AirParameters(), velocity=velocity, head=head,
                         infinitely_wide=True, arc_contact=mode)
    t0 = time.perf_counter()
    sol = solve_steady(model)
    wall = time.perf_counter() - t0
    inner = sol.model.x_head[1:-1]
    forces = [float(sol.contact[inner < 0].sum()), float(sol.contact[inner > 0].sum())]
    np.savez(out, x=sol.model.x, h=sol.spacing, p=sol.pressure, forces=forces)
    return {"wall": wall, "iterations": sol.info.iterations,
            "h0": sol.central_spacing}


def tree_round(tree: Path, case, out: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree))
    r, v, mode = case
    run = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--child", str(r),
                          str(v), mode, out], capture_output=True, text=True, env=env,
                         check=False)
    if run.returncode != 0:
        raise RuntimeError(f"{tree}: {run.stderr.strip().splitlines()[-1:]}")
    return json.loads(run.stdout.strip().splitlines()[-1])


def differences(after: str, before: str) -> tuple[float, float, float]:
    """Largest relative differences of h, p and the corner forces between two states."""
    import numpy as np

    a, b = np.load(after), np.load(before)
    if not np.array_equal(a["x"], b["x"]):
        return math.nan, math.nan, math.nan
    dh = float(np.max(np.abs(a["h"] - b["h"]) / np.abs(b["h"])))
    dp = float(np.max(np.abs(a["p"] - b["p"]) / np.abs(b["p"])))
    fa, fb = a["forces"], b["forces"]
    df = max((abs(x - y) / abs(y) if y else abs(x)) for x, y in zip(fa, fb, strict=True))
    return dh, dp, float(df)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", metavar="DIR", help="a tree of the state before")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--point", action="store_true", help="add the point-contact model")
    ap.add_argument("--long", action="store_true", help="add the 4 mm land, 10 mm arcs")
    ap.add_argument("--child", nargs=4, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        r, v, mode, out = args.child
        print(json.dumps(child(float(r), float(v), mode, out)))
        return
    if not args.baseline:
        ap.error("--baseline DIR is required (a tree of the state before the change)")
    here, before = Path(__file__).resolve().parents[1], Path(args.baseline).resolve()
    cases = CASES + (POINT_CASES if args.point else []) + (LONG_CASES if args.long else [])
    print(f"this tree against {before}: medians of {args.rounds} alternating rounds, a "
          "fresh process per round and tree")
    print(f"{'r_c mm':>6} {'V m/s':>5} {'model':>7} {'iters before':>12} {'after':>5} "
          f"{'wall before s':>13} {'after':>6} {'ratio':>5}  max rel diff h, p, forces")
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases:
            rows = {"after": [], "before": []}
            files = {"after": f"{tmp}/after.npz", "before": f"{tmp}/before.npz"}
            for k in range(args.rounds):
                order = (("after", here), ("before", before))
                for name, tree in (order if k % 2 == 0 else order[::-1]):
                    rows[name].append(tree_round(tree, case, files[name]))
            med = {n: (statistics.median(r["wall"] for r in rows[n]),
                       statistics.median(r["iterations"] for r in rows[n])) for n in rows}
            dh, dp, df = differences(files["after"], files["before"])
            r, v, mode = case
            print(f"{r * 1e3:6.1f} {v:5.1f} {mode:>7} {med['before'][1]:12.0f} "
                  f"{med['after'][1]:5.0f} {med['before'][0]:13.2f} {med['after'][0]:6.2f} "
                  f"{med['after'][0] / med['before'][0]:5.2f}  {dh:.1e}, {dp:.1e}, {df:.1e}",
                  flush=True)


if __name__ == "__main__":
    main()
