"""BLAS thread control for the engines' inner loops, and the one pool of worker processes.

Newmark's substitutions and ARPACK's iterations call BLAS on many small blocks, where
OpenBLAS's spinning worker threads compete with other work on a shared machine (measured in
benchmarks/). threadpoolctl (a dependency) holds BLAS to the given number of threads;
without it this does nothing and the engines only run slower.

Studies and sweeps that run on several local processes get them from :func:`process_pool`.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import AbstractContextManager, contextmanager, nullcontext
from typing import TYPE_CHECKING

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


@contextmanager
def process_pool(workers: int) -> Iterator[ProcessPoolExecutor]:
    """A :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` local processes.

    The workers start from a fork server (spawn where there is none), not by fork: the
    parent may hold BLAS or Dask threads, and a forked child can deadlock on their locks
    (Python 3.12+ warns). Each worker keeps to one BLAS thread (:func:`one_blas_thread`).
    If the block raises (an error, Ctrl-C), the tasks not yet started are cancelled before
    the pool shuts down, so the error surfaces without waiting for the whole queue.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    pool = ProcessPoolExecutor(max_workers=workers, initializer=one_blas_thread,
                               mp_context=context)
    try:
        yield pool
    except BaseException:
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    pool.shutdown(wait=True)
