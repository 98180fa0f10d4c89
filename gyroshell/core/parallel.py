"""BLAS thread control for the engines' inner loops.

Newmark's substitutions and ARPACK's iterations call BLAS on many small blocks, where
OpenBLAS's spinning worker threads compete with other work on a shared machine (measured in
benchmarks/). threadpoolctl (a dependency) holds BLAS to the given number of threads;
without it this does nothing and the engines only run slower.
"""

from __future__ import annotations

from contextlib import AbstractContextManager, nullcontext


def blas_threads(limit: int | None = 1) -> AbstractContextManager:
    """Context manager holding BLAS to ``limit`` threads (None: leave them alone)."""
    if limit is None:
        return nullcontext()
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # pragma: no cover - threadpoolctl missing
        return nullcontext()
    return threadpool_limits(limits=int(limit), user_api="blas")
