"""Where the points of a parameter study run: in this process, in local worker processes
(:func:`gyroshell.core.parallel.process_pool`), or on a Dask distributed cluster that the
user started. The rows are the same on every executor.

Points are sent in chunks (several points per task) to amortize the cost of scheduling a
task; a chunk takes points spread over the study, so that chunks cost about the same. With
N local processes, this process is one of them: it computes every N-th point itself, one at a
time (timed: the study's time limit), beside N - 1 worker processes.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from ..core import validation
from ..core.errors import ParameterError
from ..core.parallel import check_process_count, process_pool
from . import evaluation
from .scheduler import check_address, handshake, probe

__all__ = ["CHUNKS_PER_WORKER", "CONNECT_TIMEOUT", "Executor", "StudyTask", "check_executor",
           "chunks", "connected", "evaluate_chunk", "execute", "worker_version"]

#: How long to wait for a Dask scheduler to answer, s.
CONNECT_TIMEOUT = 10.0
#: Longest accepted ``connect_timeout``, s (an hour).
MAX_CONNECT_TIMEOUT = 3600.0
#: Chunks per worker when chunk size is automatic (balances load against overhead).
CHUNKS_PER_WORKER = 4

#: A finished chunk: (index of the point in the study, its row) pairs.
Rows = list[tuple[int, dict]]


@dataclass(frozen=True)
class Executor:
    """Where the points run: ``workers`` local processes (1: this process), or a Dask
    ``scheduler``; ``chunk_size`` points per task (None: automatic) and how long to wait for
    the scheduler, ``connect_timeout`` (s)."""

    workers: int | None
    scheduler: str | None
    chunk_size: int | None
    connect_timeout: float = CONNECT_TIMEOUT


@dataclass(frozen=True)
class StudyTask:
    """What every point of a study shares: the base tape's fields, the speed V (m/s) where
    a point sets none, what to compute and how many frequencies (see
    :func:`gyroshell.studies.evaluation.evaluate`)."""

    base: dict
    velocity: float
    compute: tuple[str, ...]
    count: int
    bearing: object = None   # a BearingStudy for compute="bearing"


def check_executor(workers: int | None, scheduler: str | None, chunk_size: int | None,
                   connect_timeout: float = CONNECT_TIMEOUT) -> Executor:
    """The executor asked for, validated; ``workers=None`` without a scheduler means one
    process per CPU.

    Raises
    ------
    ParameterError
        For a malformed address (:func:`gyroshell.studies.scheduler.check_address`: scheme,
        host, port; no network yet), both ``workers`` and ``scheduler``, or a count or
        timeout out of range.
    """
    if scheduler is not None:
        check_address(scheduler)
    if scheduler is not None and workers is not None:
        raise ParameterError("give workers (local processes) or scheduler (a Dask cluster, "
                             "whose workers run the points), not both")
    workers = _check_workers(workers) if scheduler is None else None
    chunk_size = validation.integer("chunk_size", chunk_size, low=1, optional=True)
    connect_timeout = validation.real("connect_timeout", connect_timeout, low=0.0,
                                      low_open=True, high=MAX_CONNECT_TIMEOUT, unit="s")
    return Executor(workers, scheduler, chunk_size, connect_timeout)


def _check_workers(workers) -> int:
    if workers is None:
        return max(1, os.cpu_count() or 1)
    return check_process_count("workers", workers)


def chunks(tasks: list, size: int) -> list[list]:
    """Tasks dealt round-robin into chunks of about ``size``: neighbouring points (similar
    cost, e.g. all the supercritical speeds) spread over the chunks, balancing the load.

    Examples
    --------
    >>> chunks(list(range(5)), 2)
    [[0, 3], [1, 4], [2]]
    """
    n = max(1, math.ceil(len(tasks) / size))
    return [tasks[i::n] for i in range(n) if tasks[i::n]]


def _automatic_size(todo: list, slots: int, chunk_size: int | None) -> int:
    """``chunk_size``, or about :data:`CHUNKS_PER_WORKER` chunks for each of ``slots``."""
    return chunk_size or max(1, math.ceil(len(todo) / (slots * CHUNKS_PER_WORKER)))


def evaluate_chunk(task: StudyTask, points: list[tuple[int, dict]]) -> Rows:
    """Evaluate several points of one study in one task (:func:`evaluation.evaluate
    <gyroshell.studies.evaluation.evaluate>` on each)."""
    return [(i, evaluation.evaluate(task.base, task.velocity, point, task.compute, task.count,
                                    task.bearing))
            for i, point in points]


def execute(todo: list[tuple[int, dict]], record: Callable[[Rows], None], task: StudyTask,
            where: Executor, client=None, timed: Callable[[int], None] | None = None
            ) -> tuple[str, int]:
    """Run the points ``todo`` ((index, point) pairs) where asked; ``record`` gets each
    finished chunk's rows as it finishes. With a scheduler, ``client`` is the connected
    Dask client (:func:`connected`). Locally, this process computes a share of the points
    itself (all of them with one worker; every N-th with N, beside N - 1 worker
    processes), one at a time, calling ``timed`` with each
    (:class:`gyroshell.core.progress.TimeCheck`: it may refuse the study); no row is
    recorded before its second point, so a refused study records none.

    Returns
    -------
    executor : str
        ``cache`` (nothing to do), ``serial``, ``processes(N)`` or ``dask(ADDRESS)``.
    chunk_size : int
        Points per task (0 with nothing to do).
    """
    if not todo:
        return "cache", 0
    if where.scheduler is not None:
        return _execute_dask(todo, record, task, where, client)
    if where.workers == 1:
        size = where.chunk_size or 1
        _evaluate_here(todo, task, record, timed, size)
        return "serial", size
    from concurrent.futures import as_completed

    here, there = todo[::where.workers], [p for k, p in enumerate(todo) if k % where.workers]
    if not there:
        _evaluate_here(here, task, record, timed, 1)
        return f"processes({where.workers})", 1
    size = _automatic_size(there, where.workers - 1, where.chunk_size)
    with process_pool(where.workers - 1) as pool:
        futures = [pool.submit(evaluate_chunk, task, chunk) for chunk in chunks(there, size)]
        for fut in as_completed(_evaluate_here(here, task, record, timed, 1, futures)):
            record(fut.result())
    return f"processes({where.workers})", size


def _evaluate_here(todo: list[tuple[int, dict]], task: StudyTask,
                   record: Callable[[Rows], None], timed, size: int, futures=()) -> list:
    """The points ``todo`` in this process, ``size`` at a time, each chunk timed; the
    first chunk's rows held back until the second is timed (when ``timed`` may still
    refuse: more than two points here); between chunks, the rows of
    the ``futures`` (other processes' chunks) that are done. Returns the futures not
    recorded yet."""
    held: Rows = []
    pending = list(futures)
    for k, chunk in enumerate(chunks(todo, size)):
        rows = evaluate_chunk(task, chunk)
        if timed is not None:
            timed(len(chunk))
        if k == 0 and timed is not None and len(todo) > 2:   # checked at the second point
            held = rows
            continue
        record(held + rows)
        held = []
        for fut in [f for f in pending if f.done()]:
            pending.remove(fut)
            record(fut.result())
    if held:
        record(held)
    return pending


def worker_version() -> str:
    """The gyroshell version of the process that runs this (a Dask worker), or ``not
    installed``."""
    try:
        from ..core.version import __version__
    except ImportError:
        return "not installed"
    return __version__


def _check_worker_versions(client, scheduler: str) -> None:
    """Refuse workers that run another gyroshell: their rows would not be this version's."""
    from ..core.version import __version__

    versions = client.run(worker_version)
    if not versions:
        raise ParameterError(f"the Dask scheduler at {scheduler} has no workers: start some "
                             f"with 'dask worker {scheduler}'")
    other = {addr: v for addr, v in versions.items() if v != __version__}
    if other:
        addr, v = next(iter(other.items()))
        raise ParameterError(f"Dask worker {addr} runs gyroshell {v}, this process "
                             f"{__version__}: install the same version on every worker")


@contextmanager
def connected(where: Executor | None) -> Iterator:
    """A Dask client connected to ``where.scheduler``, its workers checked, closed at the
    end; None (and nothing done) without a scheduler.

    The address is probed first (:mod:`gyroshell.studies.scheduler`): a refused connection
    fails at once, and nothing waits longer than ``where.connect_timeout`` for a server
    that does not speak Dask's protocol.

    Raises
    ------
    ParameterError
        Dask not installed, the scheduler unreachable or not a Dask scheduler, no workers,
        or workers running another gyroshell.
    """
    if where is None or where.scheduler is None:
        yield None
        return
    client = _connect(where)
    try:
        _check_worker_versions(client, where.scheduler)
        yield client
    finally:
        client.close()


def _connect(where: Executor):
    """The Dask client of ``where.scheduler``, after the address is probed."""
    address = check_address(where.scheduler)
    probe(address, where.connect_timeout)
    try:
        from distributed import Client
        from distributed.security import Security
    except ImportError:
        raise ParameterError('--scheduler needs Dask: pip install "gyroshell[cluster]"'
                             ) from None
    connection_args = Security().get_connection_args("client")
    if address.scheme in ("tls", "wss") and connection_args.get("ssl_context") is None:
        raise ParameterError(f"scheduler {where.scheduler}: {address.scheme}:// needs Dask's "
                             "TLS settings (distributed.comm.tls.ca-file, .client.cert and "
                             ".client.key in the Dask configuration), and none are set")
    handshake(address, where.connect_timeout, connection_args)
    try:
        return Client(where.scheduler, timeout=where.connect_timeout)
    except (OSError, TimeoutError) as exc:
        raise ParameterError(f"cannot reach the Dask scheduler at {where.scheduler}: {exc}"
                             ) from None


def _execute_dask(todo, record: Callable[[Rows], None], task: StudyTask, where: Executor,
                  client) -> tuple[str, int]:
    """The points on the workers of the connected Dask ``client``."""
    from distributed import as_completed

    threads = max(1, sum(client.nthreads().values()))
    size = _automatic_size(todo, threads, where.chunk_size)
    futures = [client.submit(evaluate_chunk, task, chunk, pure=False)
               for chunk in chunks(todo, size)]
    for fut in as_completed(futures):
        record(fut.result())
    return f"dask({where.scheduler})", size
