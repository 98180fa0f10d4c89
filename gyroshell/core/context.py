"""Blocks that share one object with every block nested inside them.

:func:`outermost` is the one mechanism behind the transaction of output files
(:func:`gyroshell.core.files.transaction`), the shared Newmark factorizations
(:func:`gyroshell.engines.newmark.sharing_factorizations`) and the shared step-load runs of
the reproductions (``gyroshell.reproduce._marches.sharing_marches``): the outermost block
makes the object and owns it; nested blocks get the same object and own nothing.
"""

from __future__ import annotations

import contextvars
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TypeVar

T = TypeVar("T")


@contextmanager
def outermost(variable: contextvars.ContextVar[T | None],
              make: Callable[[], T]) -> Iterator[tuple[T, bool]]:
    """Yield ``(shared, owner)``: the object of the enclosing block, or a new one from
    ``make`` that this block sets in ``variable`` (``owner`` True) until it ends."""
    current = variable.get()
    if current is not None:
        yield current, False
        return
    shared = make()
    token = variable.set(shared)
    try:
        yield shared, True
    finally:
        variable.reset(token)
