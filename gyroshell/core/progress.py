"""The one progress bar: tqdm on stderr when stderr is a terminal, never in pipes or logs.

Every long computation (time marches, frequency sweeps, speed sweeps, Campbell diagrams,
parameter studies, bearing transients) takes ``progress: bool | None``: True draws a bar,
False none (the CLI's ``--quiet``), None a bar only if stderr is a terminal. They all go
through :func:`progress_bar`, so the bars look and behave alike.

Examples
--------
>>> with progress_bar(3, "demo", progress=False) as bar:
...     for _ in range(3):
...         _ = bar.update()
"""

from __future__ import annotations

import sys

#: Seconds between redraws: frequent enough to look alive, rare enough to cost nothing.
REFRESH_INTERVAL = 0.25


def progress_wanted(progress: bool | None) -> bool:
    """Whether to draw a progress bar: ``progress`` if given, else whether stderr is a
    terminal (bars in log files and pipes are noise)."""
    if progress is None:
        isatty = getattr(sys.stderr, "isatty", None)
        return bool(isatty()) if isatty is not None else False
    return bool(progress)


def progress_bar(total: int, description: str, *, progress: bool | None = None,
                 unit: str = "it", initial: int = 0, leave: bool = False):
    """A tqdm bar on stderr over ``total`` items, disabled unless :func:`progress_wanted`.

    A disabled bar takes the same calls (``update``, ``set_postfix_str``, ``close``, use as a
    context manager), so callers never branch on whether a bar is shown.
    """
    from tqdm import tqdm

    return tqdm(total=total, initial=initial, desc=description, unit=unit,
                disable=not progress_wanted(progress), mininterval=REFRESH_INTERVAL,
                leave=leave, file=sys.stderr)
