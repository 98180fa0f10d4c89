"""Benchmark the 2-D heads and a 100-point map as the CLI runs them, one fresh process each.

    PYTHONPATH=. python benchmarks/bench_heads_2d.py
        [--cases flat1d,cyl1d,flat1,cyl,cyl12,flat2,flat3,tiny1d,tiny,map] [--repeats 3]
        [--cap 300] [--baseline DIR [--baseline-physics old|new]]

The Table 1 tape at 4 m/s, air at 20 °C, the Boltzmann film over Greenwood-Williamson
asperities given explicitly (``--rarefaction fukui-kaneko --contact asperity``, whatever
the defaults are). Cases (the issue's targets):

* ``flat1``: a 12.65 mm tape over one flat module (1 mm land, 2° of wrap either side),
  2-D on its default grid: at most 10 s;
* ``cyl``: the 2-D cylinder default (``gyroshell bearing --velocity 4``, 6.35 mm tape) and
  ``cyl12`` the 12.65 mm tape over it: at most 3 s;
* ``flat2``, ``flat3``: the same tape over 2 and 3 such modules 0.3 mm apart: each within
  3 minutes on 2 cores, and not refused by the memory estimate;
* ``flat1d``, ``cyl1d``: the infinitely wide tape over the module and the cylinder (the
  time estimate's check only);
* ``tiny``, ``tiny1d``: 0.01° wraps over the module (6.35 mm tape; infinitely wide), where
  one film covers the head and the tape flies over its corners: the 2-D within 30 s
  (it ran past 300 s on 906,648 unknowns), both within the CLI's time band;
* ``map``: ``gyroshell study --compute bearing`` of a 1-D flat module over 10 wraps x 10
  speeds on 2 workers: under 60 s.

Each run is ``/usr/bin/time`` over the command in a fresh interpreter, killed after
``--cap`` s. Printed per case: the unknowns, the time band the CLI printed before the
solve and its centre (the CLI's "about", else the band's geometric mean), the solve's
seconds (the CLI's own, its start included; median over ``--repeats``, taken only where
the first run is under :data:`CHEAP` s), the whole command's wall and CPU time (the CPU
time, its interpreter's start included, is what a quiet machine's wall time would be),
Newton iterations on the model's grid and on the start's coarser grids, the peak resident
size against the memory estimate, the ratio actual / centre and whether the target is
met. ``--baseline DIR`` runs the same
cases with DIR's tree (``git archive main | tar -x -C DIR``) on the physics before the
change (``--rarefaction first-order --contact hard``; ``--baseline-physics new``: the
same physics as this tree's, to time a solver change alone) and prints the ratios. Timings on a
shared machine vary: the load is printed with each table.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NEW = ("--rarefaction", "fukui-kaneko", "--contact", "asperity")
OLD = ("--rarefaction", "first-order", "--contact", "hard")
FLAT = ("--head", "flat", "--land-length", "1e-3", "--wrap-in", "2", "--wrap-out", "2")
WIDE = ("--width", "12.65e-3")
#: 0.01° wraps over the same land: one film covers the head (issue 32)
TINY = ("--head", "flat", "--land-length", "1e-3", "--wrap-in", "0.01", "--wrap-out", "0.01")
#: case: (command after ``gyroshell``, target seconds, what the target times)
CASES = {
    "flat1d": (("bearing", "--velocity", "4", *FLAT, "--infinitely-wide"), None, "solve"),
    "cyl1d": (("bearing", "--velocity", "4", "--infinitely-wide"), None, "solve"),
    "flat1": (("bearing", "--velocity", "4", *FLAT, *WIDE), 10.0, "solve"),
    "cyl": (("bearing", "--velocity", "4"), 3.0, "solve"),
    "cyl12": (("bearing", "--velocity", "4", *WIDE), 3.0, "solve"),
    "flat2": (("bearing", "--velocity", "4", *FLAT, *WIDE, "--modules", "2",
               "--module-gap", "0.3e-3"), 180.0, "wall"),
    "flat3": (("bearing", "--velocity", "4", *FLAT, *WIDE, "--modules", "3",
               "--module-gap", "0.3e-3"), 180.0, "wall"),
    "tiny1d": (("bearing", "--velocity", "4", *TINY, "--infinitely-wide"), None, "solve"),
    "tiny": (("bearing", "--velocity", "4", *TINY), 30.0, "wall"),
    "map": (("study", "--compute", "bearing", *FLAT[:4], "--infinitely-wide",
             "--vary", "wrap=0.5:4:10", "--vary", "velocity=1:10:10", "--workers", "2"),
            60.0, "wall"),
}
#: Repeat a case (for a median) only if its first run took less than this, s.
CHEAP = 15.0
GRID = re.compile(r"(\d+) x (\d+) intervals|(\d+) intervals along x")
ESTIMATE = re.compile(r"(\d+) unknowns; estimated (\S+ \S+) to (\S+ \S+?)(?:, about (\S+ \S+))? \(")
DONE = re.compile(r"done: (\d+) Newton iterations(?: \((\d+) more)?")
SOLVE = re.compile(r"Newton:\s+\d+ iterations(?: \(\+\d+ on the start's grids\))?, ([\d.]+) s")
STUDY = re.compile(r"(\d+) points \((\d+) computed.*?(\d+) with errors\) in ([\d.]+) s")
UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}


def seconds(text: str) -> float:
    """'7.3 s', '2.5 min' as seconds."""
    value, unit = text.split()
    return float(value) * UNITS[unit]


def run(command: tuple, physics: tuple, cap: float, tree: Path) -> dict:
    """One run of ``gyroshell COMMAND PHYSICS`` with ``tree`` first on the path."""
    env = dict(os.environ, PYTHONPATH=str(tree), OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as tmp:
        peak = Path(tmp) / "peak"
        argv = ["/usr/bin/time", "-o", str(peak), "-f", "%U %S %M", sys.executable, "-m",
                "gyroshell", *command, *physics]
        if command[0] == "study":
            argv += ["--out", str(Path(tmp) / "map.csv")]
        start = time.perf_counter()
        try:
            done = subprocess.run(argv, capture_output=True, text=True, timeout=cap, env=env,
                                  cwd=tmp)     # not the caller's folder: its tree first
        except subprocess.TimeoutExpired:
            return {"outcome": f"over the {cap:g} s cap", "wall": time.perf_counter() - start}
        wall = time.perf_counter() - start
        text = peak.read_text().split()
    out = {"wall": wall, "peak_mb": float(text[-1]) / 1024.0 if text else math.nan,
           "cpu": float(text[-3]) + float(text[-2]) if len(text) >= 3 else math.nan,
           "outcome": "ok" if done.returncode == 0 else f"exit {done.returncode}"}
    err, std = done.stderr, done.stdout
    if done.returncode != 0:
        out["why"] = (err.strip().splitlines() or [""])[-1][:150]
    if m := GRID.search(err):
        out.update(nx=int(m[1] or m[3]), ny=None if m[2] is None else int(m[2]))
    if m := ESTIMATE.search(err):
        out.update(unknowns=int(m[1]), low=seconds(m[2]), high=seconds(m[3]))
        out["centre"] = (seconds(m[4]) if m[4] else math.sqrt(out["low"] * out["high"]))
    if m := DONE.search(err):
        out.update(its=int(m[1]), start_its=int(m[2] or 0))
    if m := SOLVE.search(std):
        out["solve"] = float(m[1])
    if m := STUDY.search(std):
        out.update(points=int(m[2]), errors=int(m[3]), solve=float(m[4]))
    return out


def memory_estimate_mb(r: dict) -> float:
    """The memory estimate of the run's grid (MB, :func:`gyroshell.bearing.budget.steady_bytes`
    of this tree)."""
    from gyroshell.bearing import budget

    if "nx" not in r:
        return math.nan
    return budget.steady_bytes(r["nx"], r["ny"]) / 2**20


def case_results(name: str, physics: tuple, args, tree: Path) -> dict:
    """The case's runs (the first, then repeats if cheap) summarized."""
    command, target, what = CASES[name]
    runs = [run(command, physics, args.cap, tree)]
    if runs[0]["outcome"] == "ok" and runs[0].get("solve", math.inf) < CHEAP:
        runs += [run(command, physics, args.cap, tree) for _ in range(args.repeats - 1)]
    ok = [r for r in runs if r["outcome"] == "ok"]
    out = dict(runs[0])
    for key in ("solve", "wall", "cpu", "peak_mb"):
        values = [r[key] for r in ok if key in r]
        if values:
            out[key] = statistics.median(values)
    out["repeats"] = len(ok)
    timed = out.get(what if what == "wall" else "solve", math.nan)
    if target is None:                  # the estimate's check only
        out["met"], out["target"] = None, "-"
    else:
        out["met"] = out["outcome"] == "ok" and timed <= target
        out["target"] = f"{what} <= {target:g} s"
    return out


def row(name: str, r: dict, memory: float) -> str:
    low, high = r.get("low", math.nan), r.get("high", math.nan)
    centre = r.get("centre", math.nan)
    solve = r.get("solve", math.nan)
    band = "" if math.isnan(low) else f"{low:.3g}-{high:.3g} ({centre:.3g})"
    ratio = solve / centre if centre == centre else math.nan
    inside = "" if math.isnan(ratio) else ("in" if low <= solve <= high else "OUT")
    met = "-" if r["met"] is None else "yes" if r["met"] else "NO"
    its = f"{r.get('its', '')}" + (f" [+{r['start_its']}]" if r.get("start_its") else "")
    if r.get("points") is not None:
        its = f"{r['points']} pts, {r['errors']} err"
    return (f"{name:6s} {r.get('unknowns', ''):>8} {band:>22s} {solve:8.2f} {r['wall']:8.2f}"
            f" {r.get('cpu', math.nan):7.2f}"
            f" {ratio:6.2f} {inside:>3s} {its:>12s} {r.get('peak_mb', math.nan):8.0f}"
            f" {memory:8.0f} {r['target']:>16s} {met:>4s}"
            f"  {r['outcome']} x{r['repeats']} {r.get('why', '')}")


HEADER = (f"{'case':6s} {'unknowns':>8} {'estimate s (centre)':>22s} {'solve s':>8} "
          f"{'wall s':>8} {'CPU s':>7} {'/centr':>6} {'':>3s} {'Newton its':>12s} {'peak MB':>8} "
          f"{'est. MB':>8} {'target':>16s} {'met':>4s}")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", default=",".join(CASES),
                   help=f"comma-separated, of {', '.join(CASES)}")
    p.add_argument("--repeats", type=int, default=3, help="runs of a cheap case (median)")
    p.add_argument("--cap", type=float, default=300.0, help="seconds per run")
    p.add_argument("--baseline", type=Path, default=None,
                   help="a tree to run the same cases on with first-order slip and the hard "
                        "wall (the physics before the change)")
    p.add_argument("--baseline-physics", choices=("old", "new"), default="old",
                   help="the baseline's physics: first-order slip and the hard wall (old, "
                        "the default) or the same as this tree's (new)")
    args = p.parse_args(argv)
    names = [n for n in args.cases.split(",") if n]
    unknown = [n for n in names if n not in CASES]
    if unknown:
        p.error(f"unknown case(s) {unknown}; choose among {list(CASES)}")
    trees = [("new physics, this tree", NEW, ROOT)]
    if args.baseline is not None:
        physics = OLD if args.baseline_physics == "old" else NEW
        trees.append((f"{args.baseline_physics} physics, {args.baseline}", physics,
                      args.baseline))
    results: dict[str, dict] = {}
    for label, physics, tree in trees:
        print(f"\n{label} ({' '.join(physics)}); load {os.getloadavg()[0]:.1f}", flush=True)
        print(HEADER, flush=True)
        for name in names:
            r = case_results(name, physics, args, tree)
            results[(label, name)] = r
            print(row(name, r, memory_estimate_mb(r)), flush=True)
        print(f"load at the end {os.getloadavg()[0]:.1f}")
    if args.baseline is not None:
        print("\nnew / old (solve seconds; Newton iterations on the model's grid):")
        new_label, old_label = trees[0][0], trees[1][0]
        for name in names:
            a, b = results[(new_label, name)], results[(old_label, name)]
            ratio = a.get("solve", math.nan) / b.get("solve", math.nan)
            print(f"  {name:6s} {ratio:6.2f}  its {a.get('its', '')} vs {b.get('its', '')}"
                  f"  ({b['outcome']})")
    print("\nthe map's command: gyroshell " + " ".join((*CASES["map"][0], *NEW)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
