"""Reproductions of the seed paper's results: Figs. 2–6, the critical-speed table, the
period-against-velocity study and the paper's other observations, measured.

Each study is a module with ``run(out, settings) -> list[Path]`` that computes (tables to
CSV) and then plots (PNG) into the folder ``out``. ``studies/*.py`` are runnable scripts over
the same functions, and ``gyroshell reproduce NAME --out DIR`` runs them from the CLI.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from pathlib import Path

from ..core.errors import ParameterError
from ..core.files import check_output_folder, check_output_folder_with_files
from ..core.parallel import check_process_count
from ._common import Settings
from ._files import FILES, output_files
from ._runner import run_here, run_parallel, sharing, study_line

#: Study names in the order ``all`` runs them.
STUDIES: tuple[str, ...] = ("critical", "fig2", "fig3", "fig4", "fig5", "fig6", "period",
                            "observations", "helical", "frf", "bearing", "orthotropy",
                            "heads")


def run_study(name: str, out: str | Path, settings: Settings | None = None) -> list[Path]:
    """Run one study into the folder ``out`` (created if missing); returns written files."""
    if name not in STUDIES:
        raise ParameterError(f"study must be one of {', '.join(STUDIES)}, all; got {name!r}")
    out = check_output_folder(out, option="out")
    out.mkdir(parents=True, exist_ok=True)
    return run_here(name, out, settings or Settings())


def run_studies(names: Iterable[str], out: str | Path, settings: Settings | None = None,
                *, log=print, workers: int = 1) -> dict[str, list[Path]]:
    """Run several studies (``"all"`` expands to every one); logs each one's time.

    Parameters
    ----------
    names : iterable of str
        Study names (:data:`STUDIES`) or ``"all"``; a name given twice runs once (in the
        order of its first mention).
    out : str or path
        Output folder (created if missing; its parent must exist), refused before any
        work if it could not take the studies' files (:data:`FILES`).
    settings : Settings, optional
    log : callable or None
        Called with one line per finished study: its time and CPU time, s, and its files.
    workers : int
        Local processes (>= 1). With more than one, the studies' independent parts run
        concurrently (one BLAS thread each) and the files are the same, number for number,
        as with one; each study's time (and CPU time) is then the sum over its parts on the
        workers.
    """
    names = list(names)
    expanded = list(STUDIES) if "all" in names else list(dict.fromkeys(names))
    for name in expanded:
        if name not in STUDIES:
            raise ParameterError(f"study must be one of {', '.join(STUDIES)}, all; "
                                 f"got {name!r}")
    workers = check_process_count("workers", workers)
    if Path(out).is_dir():  # the files it could not take are refused before any work
        check_output_folder_with_files(out, output_files(expanded), option="out")
    settings = settings or Settings()
    if workers > 1 and expanded:
        out = check_output_folder(out, option="out")
        out.mkdir(parents=True, exist_ok=True)
        return run_parallel(expanded, out, settings, workers, log=log)
    written: dict[str, list[Path]] = {}
    with sharing():
        for name in expanded:
            start, cpu = time.perf_counter(), time.process_time()
            written[name] = run_study(name, out, settings)
            if log is not None:
                log(study_line(name, time.perf_counter() - start,
                               time.process_time() - cpu, written[name]))
    return written


__all__ = ["FILES", "STUDIES", "Settings", "output_files", "run_studies", "run_study"]
