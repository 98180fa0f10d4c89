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

import math
import os
import sys
import time

from .errors import ParameterError

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


# ----- long work: a measured time estimate, a time limit and progress lines -------------------
#: Environment variable overriding the time limit, seconds (e.g. ``86400`` for a day).
TIME_LIMIT_VARIABLE = "GYROSHELL_TIME_LIMIT"
#: Longest estimated run time a computation may plan, s, unless ``GYROSHELL_TIME_LIMIT`` says
#: otherwise: one hour, far beyond every documented use (the paper's runs take seconds).
DEFAULT_TIME_LIMIT = 3600.0
#: Work estimated to take longer than this, s, reports its stages in lines when stderr is not
#: a terminal (a log or a pipe), where no bar is drawn.
LONG_WORK_SECONDS = 10.0
#: The time is estimated once this many items are done, or this many seconds have passed,
#: whichever comes first (the first items include the warm-up: the estimate errs high).
PROBE_ITEMS = 16
PROBE_SECONDS = 0.5
#: Fractions of the work at which a line reports the progress (besides start and end).
REPORT_FRACTIONS = (0.25, 0.5, 0.75)


def time_limit() -> float:
    """Seconds a run may plan to take: ``GYROSHELL_TIME_LIMIT`` or :data:`DEFAULT_TIME_LIMIT`.

    Raises
    ------
    ParameterError
        If the variable is set to anything but a number of seconds > 0.
    """
    text = os.environ.get(TIME_LIMIT_VARIABLE)
    if not text:
        return DEFAULT_TIME_LIMIT
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise ParameterError(f"{TIME_LIMIT_VARIABLE} must be a number of seconds > 0, "
                             f"got {text!r}")
    return value


def duration(seconds: float) -> str:
    """``seconds`` as a short human text in the largest unit of which it holds two or more:
    '0.351 s', '12 min', '3.2 h', '41.7 days'.

    Examples
    --------
    >>> duration(0.351), duration(720), duration(11520), duration(3.6e6)
    ('0.351 s', '12 min', '3.2 h', '41.7 days')
    """
    for unit, scale in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= 2.0 * scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds:.3g} s"


class LongWork:
    """Progress of ``total`` items whose time is measured on the first ones.

    Once :data:`PROBE_ITEMS` items (or :data:`PROBE_SECONDS`) are done, the remaining time
    is estimated from their measured cost (the first item, which carries the warm-up, left
    out when there are others); above :func:`time_limit` the work is refused with that
    estimate (``ParameterError``, which says it is an estimate). A caller that can measure
    the cost before the work starts (a few trial steps) calls :meth:`assess` first, so that
    the refusal comes before any large allocation. On a terminal (or with
    ``progress=True``) a tqdm bar is drawn, as by :func:`progress_bar`; with
    ``progress=None`` and stderr not a terminal, work estimated above
    :data:`LONG_WORK_SECONDS` writes one line when its estimate is known (its size and
    estimated time), one at each of :data:`REPORT_FRACTIONS` and one at the end;
    ``progress=False`` writes nothing (the time limit still holds).

    Parameters
    ----------
    total : int
        Items of the work (steps, solves).
    description : str
        Short label of the bar and the lines ("newmark", "frf direct").
    progress : bool or None
        As for :func:`progress_bar`.
    unit : str
        Name of one item ("step", "solve"); an ``s`` makes the plural.
    size : str
        What the work is, for the lines and the refusal ("a transient of 30000000 steps of
        6765 unknowns").
    advice : str
        How to ask for less ("use fewer steps").

    Examples
    --------
    >>> with LongWork(3, "demo", progress=False, unit="item", size="3 items",
    ...               advice="ask for fewer") as work:
    ...     for _ in range(3):
    ...         work.update()
    """

    def __init__(self, total: int, description: str, *, progress: bool | None, unit: str,
                 size: str, advice: str) -> None:
        self.total, self.description, self.unit = int(total), description, unit
        self.size, self.advice = size, advice
        self._lines = progress is None and not progress_wanted(None)
        self._progress = progress
        self._bar = None
        self.done = 0
        #: Estimated seconds of the whole work, once measured (None before).
        self.estimate: float | None = None
        self._next = 1
        self._reports = [int(f * total) for f in REPORT_FRACTIONS if int(f * total) > 0]
        self._start = self._first = time.perf_counter()

    def __enter__(self) -> LongWork:
        self._bar = progress_bar(self.total, self.description, progress=self._progress,
                                 unit=self.unit)
        self._start = self._first = time.perf_counter()
        return self

    def __exit__(self, kind, value, traceback) -> None:
        self.close(finished=kind is None)

    def update(self, n: int = 1) -> None:
        """``n`` more items are done (cheap: a comparison, except at the checkpoints)."""
        self.done += n
        if self.done >= self._next:
            self._checkpoint()
        self._bar.update(n)

    def assess(self, per_item: float, how: str) -> None:
        """Take ``per_item`` seconds per item (measured as ``how`` says) as the estimate:
        refuse above the limit; start the lines if the work is long.

        Raises
        ------
        ParameterError
            If ``per_item`` times the items left is above :func:`time_limit`: naming the
            work, the estimate, how it was measured and the limit.
        """
        elapsed = time.perf_counter() - self._start if self.done else 0.0
        self.estimate = elapsed + per_item * (self.total - self.done)
        how = f"an estimate from {per_item:.3g} s per {self.unit} measured on {how}"
        limit = time_limit()
        if self.estimate > limit:
            self.close(finished=False)
            raise ParameterError(
                f"{self.size} would take about {duration(self.estimate)} ({how}), more than "
                f"the limit {duration(limit)}; {self.advice} (or set {TIME_LIMIT_VARIABLE}, "
                "seconds)")
        self._lines = self._lines and self.estimate > LONG_WORK_SECONDS
        if self._lines:
            self._say(f"{self.size}: about {duration(self.estimate)} ({how})")
        self._schedule()

    def _schedule(self) -> None:
        """The next item count at which :meth:`update` looks at the clock."""
        while self._reports and self._reports[0] <= self.done:
            self._reports.pop(0)
        self._next = self._reports[0] if self._lines and self._reports else self.total + 1

    def _checkpoint(self) -> None:
        now = time.perf_counter()
        if self.done == 1:
            self._first = now
        elapsed = now - self._start
        if self.estimate is None:
            if self.done < min(PROBE_ITEMS, self.total) and elapsed < PROBE_SECONDS:
                self._next = self.done + 1
                return
            per_item = ((now - self._first) / (self.done - 1) if self.done > 1
                        else elapsed / self.done)
            self.assess(per_item, f"the first {self.done} {self.unit}s")
            return
        if self._lines and self.done < self.total:
            left = elapsed / self.done * (self.total - self.done)
            self._say(f"{100 * self.done / self.total:.0f} % ({self.done} of {self.total} "
                      f"{self.unit}s), {duration(elapsed)} elapsed, about {duration(left)} "
                      "left")
        self._schedule()

    def _say(self, text: str) -> None:
        print(f"gyroshell: {self.description}: {text}", file=sys.stderr, flush=True)

    def set_postfix_str(self, text: str) -> None:
        if self._bar is not None:
            self._bar.set_postfix_str(text)

    def close(self, *, finished: bool = True) -> None:
        """Close the bar; a long run reported in lines says it is done."""
        if self._bar is not None:
            self._bar.close()
        if self._lines and finished and self.estimate is not None and self.done:
            self._say(f"done: {self.done} {self.unit}s in "
                      f"{duration(time.perf_counter() - self._start)}")
        self._lines = False
