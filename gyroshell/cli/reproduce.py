"""``gyroshell reproduce``: the paper's figures and tables, and our studies, into a folder."""

from __future__ import annotations

import argparse
import sys
import time

from .common import UserError, add_out_dir_option, positive_int, print_json


def register(sub, common: argparse.ArgumentParser,
             common_without_velocity: argparse.ArgumentParser) -> None:
    from ..reproduce import STUDIES

    p = sub.add_parser(
        "reproduce", help="reproduce the paper's Figs. 2-6 and the critical-speed and "
                          "period studies (PNG + CSV)",
        description="Run studies and write their tables (CSV, Markdown) and figures (PNG) "
                    "into --out-dir (every file of the run, or none if it fails). 'all' runs every "
                    "study (under a minute on 2 cores). The "
                    "tape is the paper's Table 1 tape; --quick uses a coarse grid and short "
                    "records to preview in seconds (numbers are then not the paper's).")
    p.add_argument("studies", nargs="+", choices=(*STUDIES, "all"), metavar="STUDY",
                   help=f"one or more of: {', '.join(STUDIES)}, all (a study named twice "
                        "runs once)")
    add_out_dir_option(p, "the folder the tables and figures go to (created if missing; "
                          "its parent must exist; required)")
    p.add_argument("--quick", action="store_true",
                   help="coarse grid (12 intervals across) and short records")
    p.add_argument("--quiet", action="store_true", help="no progress bars or log lines")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (the folder, the files each study wrote, "
                        "seconds) instead of the last line; the log lines go to stderr")
    p.add_argument("--workers", type=positive_int, default=None, metavar="N",
                   help="local processes running the studies' independent parts at once, "
                        "one BLAS thread each, at most 4 per CPU (default: the machine's "
                        "CPUs; the files are the same for every N)")
    p.set_defaults(func=run)


def default_workers() -> int:
    """The default of --workers: the machine's CPUs."""
    import os

    return max(1, os.cpu_count() or 1)


def run(args: argparse.Namespace) -> int:
    from ..core.files import check_output_folder_with_files, folder_transaction
    from ..core.parallel import check_process_count
    from ..reproduce import Settings, output_files, run_studies

    if args.out is None:
        raise UserError("reproduce needs --out-dir DIR: the folder its files go to")
    # as bearing --out-dir: the folder and every file the studies write, before any work
    out = check_output_folder_with_files(args.out, output_files(args.studies),
                                         option="--out-dir")
    workers = check_process_count("--workers", args.workers or default_workers())
    settings = Settings(quick=args.quick, progress=False if args.quiet else None)
    start = time.perf_counter()
    stream = sys.stderr if args.json else sys.stdout
    log = None if args.quiet else (lambda msg: print(msg, file=stream, flush=True))
    with folder_transaction(out):  # every file of the run, or none (and no new folder)
        written = run_studies(args.studies, out, settings, log=log,
                              workers=workers)
    seconds = time.perf_counter() - start
    if args.json:
        print_json({"out_dir": str(out), "seconds": seconds,
                    "files": {name: [path.name for path in paths]
                              for name, paths in written.items()}})
    elif not args.quiet:
        n = sum(len(v) for v in written.values())
        print(f"wrote {n} files to {out} in {seconds:.1f} s")
    return 0


def script(name: str, argv: list[str] | None = None) -> int:
    """Entry point of ``studies/<name>.py``: ``gyroshell reproduce <name>``, default
    ``--out-dir results``."""
    import sys

    from . import main

    args = list(sys.argv[1:] if argv is None else argv)
    if "--out" not in args and "--out-dir" not in args:
        args += ["--out-dir", "results"]
    return main(["reproduce", name, *args])
