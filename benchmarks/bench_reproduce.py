"""Benchmark ``gyroshell reproduce``: per-study times and the total, against a baseline tree.

    PYTHONPATH=. python benchmarks/bench_reproduce.py [--rounds 1] [--quick]
        [--workers 2] [--serial] [--baseline DIR] [STUDY ...]
    PYTHONPATH=. python benchmarks/bench_reproduce.py --compare OLD_OUT NEW_OUT

Each round runs ``gyroshell reproduce STUDY ... --out TMP`` (default ``all``) in a fresh
interpreter for this tree on ``--workers`` processes, with ``--serial`` also on one, and,
with ``--baseline DIR``, for another source tree (e.g. ``git archive main | tar -x -C
DIR``), in alternating order. Prints each study's time as the run logged it (with several
workers: the seconds its parts took on the workers), the wall time of the whole run and the
CPU time of its studies (on a shared machine the better measure of the work done), and
their medians over the rounds with the ratio baseline/new. Then it compares the files of
the last round: byte-identical files, and for the CSV files that differ the largest
relative difference of their numbers and how many cells differ at the precision the studies
show (6 significant digits), for the PNG files the pixels that differ (the reproductions
march the symmetric half of mirror-symmetric tapes since issue 21, in the natural order:
equal to round-off, not bit for bit). ``--compare`` compares two finished runs' folders.
Timings on a shared machine vary: read the medians, measured in the same run.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]
LINE = re.compile(r"^(\w+): ([0-9.]+) s \(CPU ([0-9.]+) s\) -> ")
OLD_LINE = re.compile(r"^(\w+): ([0-9.]+) s -> ")


def run_tree(tree: Path, studies: list[str], out: Path, extra: list[str]) -> dict[str, float]:
    """Per-study seconds (the run's log lines) and the wall time ("total") of one run."""
    env = {**os.environ, "PYTHONPATH": str(tree)}
    start, cpu = time.perf_counter(), _children_cpu()
    proc = subprocess.run([sys.executable, "-m", "gyroshell", "reproduce", *studies,
                           "--out", str(out), *extra], env=env, cwd=tree,
                          capture_output=True, text=True)
    wall, cpu = time.perf_counter() - start, _children_cpu() - cpu
    if proc.returncode:
        raise SystemExit(f"{tree}: exit {proc.returncode}\n{proc.stderr[-2000:]}")
    lines = [m for m in map(LINE.match, proc.stdout.splitlines()) if m]
    if not lines:  # an older tree logs "name: 12.3 s -> files", without the CPU time
        lines = [m for m in map(OLD_LINE.match, proc.stdout.splitlines()) if m]
    times = {m.group(1): float(m.group(2)) for m in lines}
    times.update({f"{m.group(1)} CPU": float(m.group(3)) for m in lines if m.re is LINE})
    times["total"], times["cpu"] = wall, cpu
    study_cpu = [float(m.group(3)) for m in lines if m.re is LINE]
    if study_cpu:  # the workers' CPU time, which the children's usage does not see
        times["cpu"] = sum(study_cpu)
    return times


def _children_cpu() -> float:
    """CPU seconds (user + system) of the finished child processes and their children."""
    import resource

    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


#: Significant digits of the numbers the studies show (Markdown tables: ``.6g``; figure
#: labels and docs/verification.md show fewer).
SHOWN_DIGITS = 6


def shown(values, digits: int = SHOWN_DIGITS) -> list[str]:
    """The numbers as shown: rounded to ``digits`` significant digits (NaN as "nan")."""
    return [format(float(v), f".{digits}g") for v in values]


def compare_csv(a, b) -> tuple[float, str, int]:
    """(largest difference relative to the column's largest value, its column, the number
    of cells that differ at :data:`SHOWN_DIGITS` significant digits, ignoring differences
    below 1e-9 of the column's largest value: round-off on a number near zero)."""
    import numpy as np

    worst, where, cells = 0.0, "", 0
    for col in a.columns:
        if a[col].dtype.kind in "fi":
            x, y = a[col].to_numpy(float), b[col].to_numpy(float)
            scale = (np.nanmax(np.abs(x)) if np.isfinite(x).any() else 1.0) or 1.0
            with np.errstate(invalid="ignore"):  # inf - inf, NaN
                d = np.abs(x - y) / scale
            d[(np.isnan(x) & np.isnan(y)) | (x == y)] = 0.0
            if len(x) and np.nanmax(d) > worst:
                worst, where = float(np.nanmax(d)), col
            big = ~(d <= 1e-9)
            cells += sum(p != q for p, q in zip(shown(x[big]), shown(y[big]), strict=True))
        elif not a[col].equals(b[col]):
            worst, where, cells = float("inf"), col, cells + int((a[col] != b[col]).sum())
    return worst, where, cells


def compare_png(a: Path, b: Path) -> str:
    """Pixels that differ between two PNG files and by how many of 255 levels at most."""
    import numpy as np
    from matplotlib.image import imread

    x, y = imread(a), imread(b)
    if x.shape != y.shape:
        return f"different sizes {x.shape[:2]} and {y.shape[:2]}"
    diff = np.abs(x.astype(float) - y.astype(float)).max(axis=-1) * 255
    return (f"{int((diff > 0.5).sum())} of {diff.size} pixels differ, by at most "
            f"{diff.max():.0f} of 255 levels")


def compare(old: Path, new: Path) -> list[str]:
    """One line per file that is not byte-identical: for CSV files the largest relative
    difference and the cells that differ at the shown precision; for PNG files the
    differing pixels."""
    import pandas as pd

    lines, same = [], 0
    for path in sorted(old.iterdir()):
        other = new / path.name
        if not other.exists():
            lines.append(f"  {path.name}: missing in the new run")
            continue
        if path.read_bytes() == other.read_bytes():
            same += 1
            continue
        if path.suffix == ".png":
            lines.append(f"  {path.name}: {compare_png(path, other)}")
            continue
        if path.suffix != ".csv":
            lines.append(f"  {path.name}: differs")
            continue
        a, b = pd.read_csv(path), pd.read_csv(other)
        if list(a.columns) != list(b.columns) or len(a) != len(b):
            lines.append(f"  {path.name}: different columns or rows")
            continue
        worst, where, cells = compare_csv(a, b)
        lines.append(f"  {path.name}: largest difference {worst:.2e} of the column's "
                     f"largest value ({where}); {cells} of {a.size} cells differ at "
                     f"{SHOWN_DIGITS} significant digits")
    return [f"  {same} files byte-identical"] + lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("studies", nargs="*", default=["all"])
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--quick", action="store_true", help="the studies' quick settings")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--serial", action="store_true", help="also this tree on 1 worker")
    parser.add_argument("--baseline", metavar="DIR", help="source tree timed alongside")
    parser.add_argument("--compare", nargs=2, metavar=("OLD", "NEW"),
                        help="only compare the files of two finished runs' folders")
    args = parser.parse_args(argv)
    if args.compare:
        print("\n".join(compare(Path(args.compare[0]), Path(args.compare[1]))))
        return 0
    studies = args.studies or ["all"]
    quick = ["--quick"] if args.quick else []
    cases = {"new": (HERE, quick + ["--workers", str(args.workers)])}
    if args.serial:
        cases["new, 1 worker"] = (HERE, quick + ["--workers", "1"])
    if args.baseline:
        cases["baseline"] = (Path(args.baseline).resolve(), quick)
    results: dict[str, list[dict[str, float]]] = {name: [] for name in cases}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.rounds):
            order = list(cases) if r % 2 == 0 else list(cases)[::-1]
            for name in order:
                tree, extra = cases[name]
                out = Path(tmp) / name.replace(" ", "_").replace(",", "")
                if out.exists():
                    for f in out.iterdir():
                        f.unlink()
                results[name].append(run_tree(tree, studies, out, extra))
                print(f"round {r + 1}, {name}: total {results[name][-1]['total']:.1f} s",
                      flush=True)
        names = [k for k in results["new"][0] if k not in ("total", "cpu")] + ["total",
                                                                                 "cpu"]
        names.sort(key=lambda k: k.endswith("CPU"))  # the studies' CPU times last
        med = {case: {k: statistics.median(run.get(k, float("nan")) for run in runs)
                      for k in names} for case, runs in results.items()}
        print(f"\nmedians over {args.rounds} round(s), s (studies as logged; total: the "
              "run's wall time; cpu: its studies' CPU time as logged, or the process's CPU "
              "time, imports included, for a tree that does not log it):")
        print(f"  {'study':14s}" + "".join(f"{c:>16s}" for c in cases)
              + ("     baseline/new" if args.baseline else ""))
        for k in names:
            ratio = (f"{med['baseline'][k] / med['new'][k]:17.2f}" if args.baseline
                     and med["new"][k] > 0 else "")
            print(f"  {k:14s}" + "".join(f"{med[c][k]:16.1f}" for c in cases) + ratio)
        for case in cases:
            if case != "new":
                print(f"\nfiles of the last round, {case} against new:")
                print("\n".join(compare(Path(tmp) / case.replace(" ", "_").replace(",", ""),
                                        Path(tmp) / "new")))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
