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
measured on the full settings); parts whose step-load runs are prefixes of one run
(:data:`SHARED_RUNS`) go to one worker together, longest run first, so that the others are
sliced from it (:mod:`gyroshell.reproduce._marches`). Each study's ``write`` runs on a
worker as soon as its parts are in. Workers write into a hidden staging folder inside
``out``; the files are then moved into place through
:func:`gyroshell.core.files.atomic_path` (inside the CLI's transaction: every file of the
run, or none), and the staging folder is removed, whatever happens.
"""

from __future__ import annotations

import dataclasses
import importlib
import os
import shutil
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

from ..core.files import atomic_path
from ..core.parallel import blas_threads, process_pool
from ..core.progress import stage_progress
from ._common import Settings
from ._files import check_written

#: CPU seconds of the parts (or studies without parts, key None) on the full settings,
#: measured one after another in one process (``reproduce all``'s order, so that fig2 at
#: V = 0 and 50, fig5, fig6 and the observations' runs are sliced from longer runs) at a
#: load average of about 8: only their ratios matter. Only the order of the work depends
#: on them (costliest first, so that the workers finish together; the rest keep the study
#: order). Unlisted work counts :data:`UNLISTED_COST`.
COST: dict[tuple[str, object], float] = {
    **{("period", v): c for v, c in ((0.0, 1.5), (25.0, 1.5), (50.0, 2.0), (75.0, 2.3),
                                      (90.0, 2.4), (95.0, 2.3), (100.0, 3.2))},
    ("fig2", 0.0): 0.5, ("fig2", 50.0): 0.5, ("fig2", 90.0): 1.6, ("fig2", 100.0): 1.5,
    ("frf", 0.0): 0.65, ("frf", 50.0): 1.3, ("frf", 90.0): 3.6,
    ("critical", ("free", 19.0)): 0.4, ("critical", ("simply-supported", 19.0)): 0.4,
    ("bearing", ("maps",)): 3.4, ("bearing", ("transient",)): 2.3,
    ("heads", ("width", 2.0)): 2.5, ("heads", ("width", 4.0)): 1.35,
    ("heads", ("width", 8.0)): 1.0, ("heads", ("wraps",)): 1.7,
    ("orthotropy", ("bearing", 0.25)): 1.2, ("orthotropy", ("bearing", 1.0)): 1.0,
    ("orthotropy", ("bearing", 4.0)): 0.9,
    ("helical", None): 2.2, ("observations", "reflection"): 0.7,
    ("observations", "wavelengths"): 0.2, ("fig3", None): 1.4, ("fig4", None): 1.4,
    ("fig5", None): 0.3, ("fig6", None): 0.6,
}
#: The cost of unlisted work (each part below about 0.2 s), CPU seconds as in COST.
UNLISTED_COST = 0.1


#: Parts (study, key) whose step-load run is a prefix of another's (the same tape, V and
#: Δt: :mod:`gyroshell.reproduce._marches`), by the V (m/s) of the run they share: the
#: parts of one V run on one worker, one after another, costliest (longest run) first, so
#: that the shorter runs are sliced from the longest. Only the time depends on it.
SHARED_RUNS: dict[tuple[str, object], float] = {
    ("period", 0.0): 0.0, ("fig2", 0.0): 0.0, ("observations", ("fronts", 0.0)): 0.0,
    ("period", 50.0): 50.0, ("fig2", 50.0): 50.0, ("fig5", None): 50.0,
    ("observations", "wavelengths"): 50.0, ("observations", ("fronts", 50.0)): 50.0,
    ("fig2", 100.0): 100.0, ("fig6", None): 100.0,
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
        return check_written(name, study_module(name).run(out, settings))


@contextmanager
def sharing() -> Iterator[None]:
    """A block in which transients of the same tape and (V, Δt, β, γ, C) share one
    factorization (:func:`gyroshell.engines.newmark.sharing_factorizations`), and the
    step-load runs of the L_x/L_y = 19 tape one march per (V, Δt), the shorter ones sliced
    from the longest (:func:`gyroshell.reproduce._marches.sharing_marches`): fig2, period,
    fig5, fig6 and observations march that tape at the paper's Δt."""
    from ..engines.newmark import sharing_factorizations
    from ._marches import sharing_marches

    with sharing_factorizations(), sharing_marches():
        yield


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


def _parts_task(staging: Path, settings: Settings, members: list[tuple]) -> list[tuple]:
    """Run the parts ``members`` ((study, key, whole): ``whole`` a study without parts,
    run into ``staging``) one after another; (study, key, what, value, wall s, CPU s) each."""
    done = []
    for name, key, whole in members:
        module = study_module(name)
        if whole:
            value = _timed(module.run, staging, settings)
        else:
            value = _timed(module.compute_part, settings, key)
        done.append((name, key, "run" if whole else "compute", *value))
    return done


def _write_task(name: str, staging: Path, settings: Settings, results: list) -> list[tuple]:
    return [(name, None, "write", *_timed(study_module(name).write, staging, settings,
                                          results))]


def _units(tasks: list[tuple], studies: dict) -> list[list[tuple]]:
    """The tasks as the workers' units of work: those sharing a run
    (:data:`SHARED_RUNS`) in one unit, costliest first; the units costliest first (a
    stable sort: equal costs keep the study order)."""
    units: dict[object, list[tuple]] = {}
    for name, key in tasks:
        group = SHARED_RUNS.get((name, key))
        unit = units.setdefault(("run", group) if group is not None else (name, key), [])
        unit.append((name, key, studies[name].keys is None))
    for unit in units.values():
        unit.sort(key=lambda m: -COST.get(m[:2], UNLISTED_COST))
    return sorted(units.values(), key=lambda u: -sum(COST.get(m[:2], UNLISTED_COST) for m in u))


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
    _start_fork_server(names)  # its imports overlap this process's imports of the studies
    studies = {}
    for name in names:
        module = study_module(name)
        keys = list(module.parts(settings)) if hasattr(module, "parts") else None
        studies[name] = _Study(name, keys)
    tasks = [(name, key) for name, s in studies.items() for key in (s.keys or [None])]
    staging = Path(tempfile.mkdtemp(prefix=".gyroshell-reproduce-", dir=out))
    try:
        with process_pool(workers) as pool, stage_progress(
                len(tasks) + sum(s.keys is not None for s in studies.values()),
                "reproduce", progress=settings.progress, unit="part") as bar:
            pending = {pool.submit(_parts_task, staging, quiet, unit): unit
                       for unit in _units(tasks, studies)}
            _collect(pool, pending, studies, staging, quiet, bar, log)
        written = {}
        for name in names:
            written[name] = [_move(path, out) for path in studies[name].files]
        return written
    finally:
        shutil.rmtree(staging, ignore_errors=True)


#: Modules the fork server imports before it starts the workers, so that each worker
#: starts with them instead of importing them again (a few seconds per worker); the
#: studies' own modules are added, and ``_headless`` (matplotlib's Agg and pyplot).
PRELOAD = ("numpy", "scipy.sparse.linalg", "scipy.signal", "pandas", "matplotlib",
           "gyroshell.reproduce._common", "gyroshell.engines.newmark", "gyroshell.engines.eigen",
           "gyroshell.reproduce._headless")


def _start_fork_server(names: Sequence[str]) -> None:
    """Where workers start from a fork server: start it now, importing PRELOAD and the
    modules of the studies ``names``, while this process imports them too (two cores
    instead of one after the other). Nothing to do if it runs already or there is none
    (spawn)."""
    import multiprocessing

    if "forkserver" not in multiprocessing.get_all_start_methods():
        return
    from multiprocessing import forkserver

    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload([*PRELOAD, *(f"{__package__}.{n}" for n in names)])
    forkserver.ensure_running()


def _collect(pool, pending: dict, studies: dict, staging: Path, settings: Settings, bar,
             log) -> None:
    """Wait for the tasks; submit each study's ``write`` once its parts are in."""
    from concurrent.futures import FIRST_COMPLETED, wait

    while pending:
        done, _ = wait(pending, return_when=FIRST_COMPLETED)
        for future in done:
            pending.pop(future)
            for name, key, what, value, seconds, cpu in future.result():
                study = studies[name]
                study.seconds += seconds
                study.cpu += cpu
                bar.update(1)
                if what == "compute":
                    study.results[key] = value
                    if len(study.results) == len(study.keys):
                        results = [study.results[k] for k in study.keys]
                        pending[pool.submit(_write_task, name, staging, settings,
                                            results)] = [(name, None, False)]
                    continue
                study.files = check_written(name, value)
                if log is not None:
                    log(study_line(name, study.seconds, study.cpu, study.files))


def _move(staged: Path, out: Path) -> Path:
    """Move a file a worker wrote into the staging folder to ``out`` (staged with the
    active transaction, if any)."""
    target = out / Path(staged).name
    with atomic_path(target, option="out") as tmp:
        os.replace(staged, tmp)
    return target
