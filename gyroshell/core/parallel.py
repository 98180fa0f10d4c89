"""BLAS thread control for the engines' inner loops, and the one pool of worker processes.

Newmark's substitutions and ARPACK's iterations call BLAS on many small blocks, where
OpenBLAS's spinning worker threads compete with other work on a shared machine (measured in
benchmarks/). threadpoolctl (a dependency) holds BLAS to the given number of threads;
without it this does nothing and the engines only run slower.

Studies and sweeps that run on several local processes get them from :func:`process_pool`.
Its workers die with the process that started them (:func:`worker_setup`): a study killed
with ``kill -9`` leaves no worker, no fork server and no held pipe behind. A signal that
stops the study while a worker starts waits until the worker has started
(:func:`held_signals`), so that the worker is stopped with the others instead of starting
after the study is gone (it then failed to open the pool's semaphores and printed a
traceback); workers share no semaphore of their own (:func:`worker_setup`), so a stopped
one leaves none for the resource tracker to report as leaked.
"""

from __future__ import annotations

import functools
import os
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import AbstractContextManager, contextmanager, nullcontext
from typing import TYPE_CHECKING

from . import validation
from .progress import bars_of_this_process

if TYPE_CHECKING:
    from concurrent.futures import ProcessPoolExecutor


def blas_threads(limit: int | None = 1) -> AbstractContextManager:
    """Context manager holding BLAS to ``limit`` threads (None: leave them alone)."""
    if limit is None:
        return nullcontext()
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # pragma: no cover - threadpoolctl missing
        return nullcontext()
    return threadpool_limits(limits=int(limit), user_api="blas")


def one_blas_thread() -> None:
    """Initializer of worker processes: one BLAS (and OpenMP) thread each, since the workers
    already use every core."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # pragma: no cover - threadpoolctl missing
        return
    threadpool_limits(limits=1)


#: Most local processes per CPU a study or sweep may start (more only adds overhead).
MAX_PROCESSES_PER_CPU = 4
#: Seconds between a worker's checks that the process that started it is still alive.
LIFELINE_INTERVAL = 0.25
#: prctl(2) option: the signal the kernel sends a process when its parent dies (Linux).
PR_SET_PDEATHSIG = 1


def max_processes() -> int:
    """The most local processes accepted: :data:`MAX_PROCESSES_PER_CPU` per CPU."""
    return MAX_PROCESSES_PER_CPU * max(1, os.cpu_count() or 1)


def check_process_count(name: str, value: object) -> int:
    """A number of local processes: an integer in [1, :func:`max_processes`].

    Examples
    --------
    >>> check_process_count("workers", 1)
    1
    """
    return validation.integer(name, value, low=1, high=max_processes())


def worker_setup(starter: int) -> None:
    """Initializer of worker processes: one BLAS thread (:func:`one_blas_thread`), progress
    bars' lock of this process only (:func:`gyroshell.core.progress.bars_of_this_process`),
    and death with the process ``starter`` (its pid) that started the pool.

    On Linux the kernel kills the worker when its parent (the fork server) dies
    (``PR_SET_PDEATHSIG``); on every POSIX system a daemon thread checks every
    :data:`LIFELINE_INTERVAL` s that ``starter`` is still alive (not gone, not a zombie)
    and ends the worker at once when it is not. The fork server itself ends when the
    starter and all its workers are gone (Python closes its lifeline pipe then).
    """
    one_blas_thread()
    bars_of_this_process()
    if os.name == "nt":  # no parent death signal, and os.kill(pid, 0) would end the starter
        return
    _die_with_parent()
    parent = os.getppid()
    if not _alive(starter):  # the starter died before this worker was set up
        os._exit(1)
    threading.Thread(target=_watch, args=(starter, parent), name="gyroshell-lifeline",
                     daemon=True).start()


def _die_with_parent() -> None:
    """Ask the kernel for SIGKILL when this process's parent dies (Linux only)."""
    if not sys.platform.startswith("linux"):
        return
    import ctypes
    import signal

    try:
        libc = ctypes.CDLL(None, use_errno=True)
    except OSError:  # pragma: no cover - no C library to call: the thread still watches
        return
    libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)


def _watch(starter: int, parent: int) -> None:
    while _alive(starter) and os.getppid() == parent:
        time.sleep(LIFELINE_INTERVAL)
    os._exit(1)  # the study is gone: nobody will read this worker's results


def _alive(pid: int) -> bool:
    """Whether process ``pid`` exists and is not a zombie (a killed process whose parent
    has not reaped it yet, e.g. one waiting for the pipes the workers hold)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            state = fh.read().rpartition(b")")[2].split()[0]
        return state not in (b"Z", b"X")
    except FileNotFoundError:
        return False
    except OSError:  # no /proc (not Linux): ask the kernel whether the pid exists
        pass
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


#: Signals that stop a run (Ctrl-C, ``kill``, a closed terminal), held while a worker starts.
HELD_SIGNALS = ("SIGINT", "SIGTERM", "SIGHUP")


@contextmanager
def held_signals() -> Iterator[None]:
    """Within the block, :data:`HELD_SIGNALS` are held and acted on when it ends (the first
    one caught, by the handler it had, or its default action); the block is never cut
    short by them. Does nothing outside the main thread (where handlers cannot change)."""
    import signal

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[tuple[int, object]] = []
    previous = {}
    for name in HELD_SIGNALS:
        signum = getattr(signal, name, None)
        if signum is not None and signal.getsignal(signum) not in (signal.SIG_IGN, None):
            previous[signum] = signal.signal(signum, lambda *caught_now: caught.append(
                caught_now))
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        if caught:
            signum, frame = caught[0]
            if callable(previous[signum]):
                previous[signum](signum, frame)
            else:  # SIG_DFL: the default action (usually the end of this process), now
                os.kill(os.getpid(), signum)


@functools.cache
def _pool_class() -> type[ProcessPoolExecutor]:
    """ProcessPoolExecutor whose workers start under :func:`held_signals`: a signal during a
    start comes after the worker is in the pool's list, so that :func:`stop_pool` stops
    it. Cut short, the start left a worker that the pool did not know, which read the
    pool's semaphores after the study had removed them (a FileNotFoundError traceback)."""
    from concurrent.futures import ProcessPoolExecutor

    class Pool(ProcessPoolExecutor):
        def _spawn_process(self) -> None:  # Python 3.10-3.13's one place a worker starts
            with held_signals():
                super()._spawn_process()

    return Pool


@contextmanager
def process_pool(workers: int) -> Iterator[ProcessPoolExecutor]:
    """A :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` local processes.

    The workers start from a fork server (spawn where there is none), not by fork: the
    parent may hold BLAS or Dask threads, and a forked child can deadlock on their locks
    (Python 3.12+ warns). Each worker keeps to one BLAS thread and ends when the calling
    process dies, however it dies (:func:`worker_setup`).
    If the block raises (an error, Ctrl-C, SIGTERM), the tasks not yet started are
    cancelled and the running ones stopped with their workers (:func:`stop_pool`), so the
    error surfaces at once, without waiting for the chunks in progress.
    """
    import multiprocessing

    workers = check_process_count("workers", workers)
    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    pool = _pool_class()(max_workers=workers, initializer=worker_setup,
                         initargs=(os.getpid(),), mp_context=context)
    try:
        yield pool
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown(wait=True)


#: Seconds a stopped worker gets to end after SIGTERM before it is killed.
STOP_GRACE = 1.0


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """End ``pool`` now: cancel the tasks not started, terminate the workers running the
    others (their results are not wanted), and wait only for the workers to exit (SIGKILL
    after :data:`STOP_GRACE` s)."""
    # the pool's workers and queue (no public names before Python 3.14's terminate_workers)
    processes = list((getattr(pool, "_processes", None) or {}).values())
    for item in dict(getattr(pool, "_pending_work_items", None) or {}).values():
        item.future.cancel()   # the tasks not started: cancelled (False for running ones)
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    deadline = time.monotonic() + STOP_GRACE
    for process in processes:
        process.join(max(0.0, deadline - time.monotonic()))
        if process.is_alive():
            process.kill()
            process.join()
