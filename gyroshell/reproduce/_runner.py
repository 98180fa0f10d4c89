"""Running studies: one after another in this process, or their parts on local workers.

A study module either has ``run(out, settings)`` only (one piece of work), or splits its
computation into independent parts:

* ``parts(settings)``: the parts' keys (hashable, picklable), in the order the study
  computes them;
* ``compute_part(settings, key)``: one part's numbers (picklable: frames, dicts, arrays);
* ``write(out, settings, results)``: the tables and figures from the parts' results, given
  in the order of ``parts``; returns the written files.

``run(out, settings)`` of such a study is ``write(out, settings, [compute_part(settings,
key) for key in parts(settings)])``, so the same code computes every number whether the
parts run here or on workers. Workers hold BLAS to one thread, and so does the run in this
process: the numbers do not depend on the number of workers.

On workers (:func:`run_parallel`), the parts go to a pool of local processes
(:func:`gyroshell.core.parallel.process_pool`), the costliest first (:data:`COST`, seconds
measured on the full settings), and each study's ``write`` runs on a worker as soon as its
parts are in. Workers write into a hidden staging folder inside ``out``; the files are then
moved into place through :func:`gyroshell.core.files.atomic_path` (inside the CLI's
transaction: every file of the run, or none), and the staging folder is removed, whatever
happens.
"""

from __future__ import annotations

import dataclasses
import importlib
import os
import shutil
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from ..core.files import atomic_path
from ..core.parallel import blas_threads, process_pool
from ..core.progress import stage_progress
from ._common import Settings

#: Rough CPU seconds of the costliest parts (or studies without parts, key None) on the full
#: settings: only the order of the work depends on them (costliest first, so that the
#: workers finish together; the rest keep the study order). Unlisted work counts 1 s.
COST: dict[tuple[str, object], float] = {
    **{("period", v): c for v, c in ((0.0, 8), (25.0, 8), (50.0, 9), (75.0, 11), (90.0, 12),
                                      (95.0, 12), (100.0, 16))},
    **{("fig2", v): 5.0 for v in (0.0, 50.0, 90.0, 100.0)},
    ("critical", ("free", 19.0)): 6.0, ("critical", ("simply-supported", 19.0)): 6.0,
    ("critical", ("free", 4.0)): 2.0, ("critical", ("simply-supported", 4.0)): 2.0,
    ("bearing", ("maps",)): 6.0, ("bearing", ("transient",)): 4.0,
    **{("heads", ("width", v)): 4.0 for v in (2.0, 4.0, 8.0)},
    ("heads", ("wraps",)): 3.0, ("heads", ("modules",)): 2.0,
    **{("orthotropy", ("bearing", r)): 3.0 for r in (0.25, 1.0, 4.0)},
    ("helical", None): 6.0, ("observations", "reflection"): 3.0,
    ("observations", "wavelengths"): 2.0, ("fig3", None): 2.0, ("fig4", None): 2.0,
    ("fig5", None): 2.0, ("fig6", None): 2.0,
}


def study_module(name: str):
    """The module of study ``name`` (imported on first use)."""
    return importlib.import_module(f"{__package__}.{name}")


def run_parts(module, out: Path, settings: Settings) -> list[Path]:
    """``run`` of a study with parts: every part here, in order, then ``write``."""
    results = [module.compute_part(settings, key) for key in module.parts(settings)]
    return module.write(out, settings, results)


def run_here(name: str, out: Path, settings: Settings) -> list[Path]:
    """Study ``name`` in this process, BLAS held to one thread (as on the workers), its
    transients sharing factorizations (with those of the studies before it, inside
    :func:`sharing`)."""
    with blas_threads(1), sharing():
        return study_module(name).run(out, settings)


def sharing():
    """A block in which transients of the same tape and (V, Δt, β, γ, C) share one
    factorization (:func:`gyroshell.engines.newmark.sharing_factorizations`): fig2, period,
    fig5, fig6 and observations march the L_x/L_y = 19 tape at the paper's Δt."""
    from ..engines.newmark import sharing_factorizations

    return sharing_factorizations()


#: This worker's sharing block, entered by its first task and kept open for its life, so
#: that every part it runs shares factorizations with the parts it ran before.
_WORKER_SHARING: list = []


def _share_in_worker() -> None:
    if not _WORKER_SHARING:
        block = sharing()
        block.__enter__()
        _WORKER_SHARING.append(block)


# ----- the workers' tasks ------------------------------------------------------------------
def _timed(function: Callable, *args):
    """(the call's value, its wall seconds, its CPU seconds in this process)."""
    _share_in_worker()
    start, cpu = time.perf_counter(), time.process_time()
    value = function(*args)
    return value, time.perf_counter() - start, time.process_time() - cpu


def study_line(name: str, seconds: float, cpu: float, files: Sequence[Path]) -> str:
    """The log line of a finished study: its time and CPU time (s), its files."""
    return f"{name}: {seconds:.1f} s (CPU {cpu:.1f} s) -> {', '.join(p.name for p in files)}"


def _compute_task(name: str, settings: Settings, key):
    return _timed(study_module(name).compute_part, settings, key)


def _write_task(name: str, staging: Path, settings: Settings, results: list):
    return _timed(study_module(name).write, staging, settings, results)


def _run_task(name: str, staging: Path, settings: Settings):
    return _timed(study_module(name).run, staging, settings)


# ----- the parent ----------------------------------------------------------------------------
@dataclasses.dataclass
class _Study:
    name: str
    keys: list | None             # None: a study without parts
    results: dict = dataclasses.field(default_factory=dict)
    seconds: float = 0.0
    cpu: float = 0.0
    files: list[Path] | None = None


def run_parallel(names: Sequence[str], out: Path, settings: Settings, workers: int, *,
                 log: Callable[[str], object] | None = print) -> dict[str, list[Path]]:
    """Run the studies ``names`` on ``workers`` local processes into ``out``; logs each
    study's time (the seconds its parts and its writing took on the workers) as it
    finishes. Returns the written files per study, in the order of ``names``."""
    quiet = dataclasses.replace(settings, progress=False)  # no bars from the workers
    studies = {}
    for name in names:
        module = study_module(name)
        keys = list(module.parts(settings)) if hasattr(module, "parts") else None
        studies[name] = _Study(name, keys)
    tasks = [(name, key) for name, s in studies.items() for key in (s.keys or [None])]
    tasks.sort(key=lambda t: -COST.get(t, 1.0))  # stable: equal costs keep the study order
    _preload()
    staging = Path(tempfile.mkdtemp(prefix=".gyroshell-reproduce-", dir=out))
    try:
        with process_pool(workers) as pool, stage_progress(
                len(tasks) + sum(s.keys is not None for s in studies.values()),
                "reproduce", progress=settings.progress, unit="part") as bar:
            pending = {}
            for name, key in tasks:
                if studies[name].keys is None:
                    future = pool.submit(_run_task, name, staging, quiet)
                else:
                    future = pool.submit(_compute_task, name, quiet, key)
                pending[future] = (name, key, "compute")
            _collect(pool, pending, studies, staging, quiet, bar, log)
        written = {}
        for name in names:
            written[name] = [_move(path, out) for path in studies[name].files]
        return written
    finally:
        shutil.rmtree(staging, ignore_errors=True)


#: Modules the fork server imports before it starts the workers, so that each worker
#: starts with them instead of importing them again (a few seconds per worker).
PRELOAD = ("numpy", "scipy.sparse.linalg", "scipy.signal", "pandas", "matplotlib",
           "gyroshell.reproduce._common", "gyroshell.engines.newmark", "gyroshell.engines.eigen")


def _preload() -> None:
    """Ask the fork server (where it is used and not started yet) to import PRELOAD."""
    import multiprocessing

    if "forkserver" in multiprocessing.get_all_start_methods():
        multiprocessing.get_context("forkserver").set_forkserver_preload(list(PRELOAD))


def _collect(pool, pending: dict, studies: dict, staging: Path, settings: Settings, bar,
             log) -> None:
    """Wait for the tasks; submit each study's ``write`` once its parts are in."""
    from concurrent.futures import FIRST_COMPLETED, wait

    while pending:
        done, _ = wait(pending, return_when=FIRST_COMPLETED)
        for future in done:
            name, key, what = pending.pop(future)
            value, seconds, cpu = future.result()
            study = studies[name]
            study.seconds += seconds
            study.cpu += cpu
            bar.update(1)
            if what == "compute" and study.keys is not None:
                study.results[key] = value
                if len(study.results) == len(study.keys):
                    results = [study.results[k] for k in study.keys]
                    pending[pool.submit(_write_task, name, staging, settings, results)] = (
                        name, None, "write")
                continue
            study.files = list(value)
            if log is not None:
                log(study_line(name, study.seconds, study.cpu, study.files))


def _move(staged: Path, out: Path) -> Path:
    """Move a file a worker wrote into the staging folder to ``out`` (staged with the
    active transaction, if any)."""
    target = out / Path(staged).name
    with atomic_path(target, option="out") as tmp:
        os.replace(staged, tmp)
    return target
