"""Refinement study of the 2-D bearing's edge minimum (Table 1 tape, V = 4 m/s, 15° wrap).

    PYTHONPATH=. python benchmarks/bearing_refinement.py --width 6.35e-3 \
        --grids 156x60 312x120 624x240 [--uniform] [--x-ratio 4 --y-ratio 10 ...]

Solves the tape on each grid (the default grading's mapping, nested refinement when the
counts double) with one BLAS thread and prints one JSON line per grid: nx, ny, unknowns,
the finest and coarsest spacings, h_c, the edge spacing at the wrap centre, h_min and its
place, Newton iterations and seconds. With three grids refined by 2 each way it also
prints the observed order p = log₂(Δ₁/Δ₂) and the Richardson value h* = h₃ − Δ₂/(2^p − 1)
of each quantity.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from dataclasses import replace

import numpy as np

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing import model as bm
from gyroshell.bearing.steady import solve_steady
from gyroshell.core.parallel import blas_threads

KEYS = ("h_c", "h_edge", "h_min")


def solve(width: float, nx: int, ny: int, grading, span=None) -> dict:
    model = BearingModel(TapeParameters(width=width), AirParameters(), velocity=4.0,
                         wrap_angle=math.radians(15.0), nx=nx, ny=ny, grading=grading,
                         span=span)
    start = time.perf_counter()
    sol = solve_steady(model)
    seconds = time.perf_counter() - start
    dx, dy = np.diff(model.x), np.diff(model.y)
    x_min, y_min = sol.minimum_location
    return {"nx": nx, "ny": ny, "unknowns": model.unknowns, "hx": [dx.min(), dx.max()],
            "hy": [dy.min(), dy.max()], "h_c": sol.central_spacing,
            "h_edge": float(sol.cross_width_spacing[0]), "h_min": sol.minimum_spacing,
            "x_min": x_min, "y_min": y_min, "iterations": sol.info.iterations,
            "seconds": seconds}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--width", type=float, default=6.35e-3)
    ap.add_argument("--grids", nargs="+", required=True, help="NXxNY ...")
    ap.add_argument("--uniform", action="store_true")
    ap.add_argument("--span", type=float, default=None)
    for name in ("x_ratio", "x_width", "y_ratio", "y_width"):
        ap.add_argument("--" + name.replace("_", "-"), type=float, default=None)
    args = ap.parse_args(argv)
    grading = "uniform" if args.uniform else bm.DEFAULT_GRADING
    if not args.uniform:
        changes = {k: getattr(args, k) for k in ("x_ratio", "x_width", "y_ratio", "y_width")
                   if getattr(args, k) is not None}
        grading = replace(grading, **changes)
    rows = []
    with blas_threads(1):
        for g in args.grids:
            nx, ny = (int(v) for v in g.split("x"))
            rows.append(solve(args.width, nx, ny, grading, args.span))
            print(json.dumps(rows[-1]), flush=True)
    if len(rows) == 3:
        for k in KEYS:
            v = np.array([r[k] for r in rows])
            d1, d2 = v[1] - v[0], v[2] - v[1]
            p = math.log2(abs(d1 / d2)) if d2 else float("inf")
            star = v[2] + d2 / (2**p - 1)
            print(json.dumps({"quantity": k, "order": p, "richardson": star,
                              "errors": list((v - star) / star)}), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
