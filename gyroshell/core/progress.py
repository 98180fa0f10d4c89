"""The one progress display: tqdm on stderr when stderr is a terminal; off a terminal (a
pipe, a log) one line per stage (:class:`StageLines`) for work long enough to need it.

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
import time
from collections.abc import Callable

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


def bars_of_this_process() -> None:
    """Give tqdm a lock of this process's threads instead of the one it shares between
    processes (a named semaphore made on its first bar, even a disabled one). For worker
    processes, which draw no bars: a worker stopped by a signal cannot remove that
    semaphore, and Python's resource tracker then warns of a leaked semaphore."""
    import threading

    from tqdm import tqdm

    tqdm.set_lock(threading.RLock())


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
    from .budget import limit_from_environment

    value = limit_from_environment(TIME_LIMIT_VARIABLE, "seconds")
    return DEFAULT_TIME_LIMIT if value is None else value


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


def check_time(estimate: float, *, size: str, how: str, advice: str) -> None:
    """Refuse work estimated to take ``estimate`` seconds above :func:`time_limit`.

    Raises
    ------
    ParameterError
        One line: what the work is (``size``), the estimate and how it was made (``how``),
        the limit and how to ask for less (``advice``).
    """
    limit = time_limit()
    if estimate > limit:
        raise ParameterError(
            f"{size} would take about {duration(estimate)} ({how}), more than the limit "
            f"{duration(limit)}; {advice} (or set {TIME_LIMIT_VARIABLE}, seconds)")


def seconds_per_item(now: float, start: float, first: float | None, done: int) -> float:
    """Seconds per item of ``done`` items timed from ``start`` to ``now``: with the first
    item's end known (``first``: it was reported alone) and others after it, from those
    others only (the first carries the warm-up); else the mean over all."""
    if first is not None and done > 1:
        return (now - first) / (done - 1)
    return (now - start) / done


class TimeCheck:
    """The time limit over work of ``total`` similar items done one by one: once the second
    is done, the whole is estimated from it (the first, which carries the warm-up, left
    out) and refused above :func:`time_limit` (:func:`check_time`). Call it with the items
    done (a progress callback); ``parallel`` runs of the same length go on beside this one,
    so only this one's items count.

    Examples
    --------
    >>> check = TimeCheck(3, unit="speed", size="a sweep of 3 speeds", advice="use fewer")
    >>> for _ in range(3):
    ...     check(1)
    """

    def __init__(self, total: int, *, unit: str, size: str, advice: str,
                 parallel: int = 1) -> None:
        self.total, self.unit, self.size, self.advice = int(total), unit, size, advice
        self.parallel = int(parallel)
        self.done = 0
        self._start, self._first = time.perf_counter(), None

    def __call__(self, n: int = 1) -> None:
        before, self.done = self.done, self.done + int(n)
        if before >= 2:
            return
        now = time.perf_counter()
        if self.done == 1:
            self._first = now
        if 2 <= self.done < self.total:   # all done: nothing left to refuse
            warm = self._first is not None   # the first item's time is known: left out
            per_item = seconds_per_item(now, self._start, self._first, self.done)
            how = (f"an estimate from {per_item:.3g} s per {self.unit} measured on the first "
                   f"{self.done} {self.unit}s{', the first left out' if warm else ''}"
                   + ("" if self.parallel == 1 else f", {self.parallel} runs side by side"))
            check_time(now - self._start + per_item * (self.total - self.done),
                       size=self.size, how=how, advice=self.advice)


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
        self._stages: StageLines | None = None
        self._start, self._first = time.perf_counter(), None

    def __enter__(self) -> LongWork:
        self._bar = progress_bar(self.total, self.description, progress=self._progress,
                                 unit=self.unit)
        self._start, self._first = time.perf_counter(), None
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
        try:
            check_time(self.estimate, size=self.size, how=how, advice=self.advice)
        except ParameterError:
            self.close(finished=False)
            raise
        self._lines = self._lines and self.estimate > LONG_WORK_SECONDS
        if self._lines:
            self._stages = StageLines(self.total, self.description, self.unit,
                                      started=self._start)
            self._stages.say(f"{self.size}: about {duration(self.estimate)} ({how})")
            self._stages.update(self.done)
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
            per_item = seconds_per_item(now, self._start, self._first, self.done)
            self.assess(per_item, f"the first {self.done} {self.unit}s")
            return
        if self._stages is not None:
            self._stages.update(self.done - self._stages.n)
        self._schedule()

    def set_postfix_str(self, text: str) -> None:
        if self._bar is not None:
            self._bar.set_postfix_str(text)

    def close(self, *, finished: bool = True) -> None:
        """Close the bar; a long run reported in lines says it is done."""
        if self._bar is not None:
            self._bar.close()
        if self._stages is not None and finished:
            self._stages.update(self.done - self._stages.n)
            self._stages.close()
        self._stages, self._lines = None, False


# ----- one line per stage off a terminal (studies, sweeps, Campbell diagrams, long work) --------


class StageLines:
    """One stderr line per stage of ``total`` items (``unit`` each) of ``description``;
    the same calls as a tqdm bar (``update``, ``close``, a context manager).

    Where stderr is a pipe or a log, a bar would be noise, yet minutes of silence look like
    a hang: one line when the work starts (:meth:`start`: its size and where it runs), one
    at each of :data:`REPORT_FRACTIONS` done (the time so far and an estimate of the time
    left, from the rate so far) and one at the end. ``initial`` items are done before the
    start (a study's cached points); ``stream`` and ``clock`` (seconds) default to stderr
    and :func:`time.perf_counter`; ``started`` is the clock's time the work began (default:
    now).

    Examples
    --------
    >>> import io
    >>> out = io.StringIO()
    >>> with StageLines(4, "study", "point", stream=out, clock=iter(range(10)).__next__) as s:
    ...     s.start("on 1 process")
    ...     _ = s.update(2)
    ...     _ = s.update(2)
    >>> print(out.getvalue(), end="")
    gyroshell: study: 4 points on 1 process
    gyroshell: study: 2/4 points done (50 %) in 1 s, about 1 s left
    gyroshell: study: 4/4 points done in 2 s
    """

    def __init__(self, total: int, description: str, unit: str, *, initial: int = 0,
                 stream=None, clock: Callable[[], float] = time.perf_counter,
                 started: float | None = None) -> None:
        self.total, self.description, self.unit = int(total), description, unit
        self.n = self._first = int(initial)
        self._stream, self._clock = stream, clock
        self._t0 = clock() if started is None else started
        self._marks = [q for q in REPORT_FRACTIONS if q * self.total > self.n]
        self._closed = False

    def say(self, text: str) -> None:
        """One line ``gyroshell: DESCRIPTION: TEXT`` (a stage of the caller's own)."""
        self._write(text)

    def _write(self, text: str) -> None:
        stream = self._stream if self._stream is not None else sys.stderr
        print(f"gyroshell: {self.description}: {text}", file=stream, flush=True)

    def _units(self, n: int) -> str:
        return f"{n} {self.unit}{'' if n == 1 else 's'}"

    def start(self, where: str = "") -> None:
        """The first line: how many items, how many are already done, where they run."""
        cached = f" ({self.n} from the cache)" if self.n else ""
        self._write(f"{self._units(self.total)}{cached}{' ' + where if where else ''}")
        self._t0 = self._clock()

    def update(self, n: int = 1) -> bool:
        """``n`` more items done; a line when a quarter is passed."""
        self.n += int(n)
        passed = [q for q in self._marks if self.n >= q * self.total]
        if passed and self.n < self.total:
            self._marks = [q for q in self._marks if q not in passed]
            elapsed = self._clock() - self._t0
            done_now = self.n - self._first
            left = elapsed * (self.total - self.n) / done_now if done_now else float("nan")
            self._write(f"{self.n}/{self._units(self.total)} done "
                        f"({100 * self.n / self.total:.0f} %) in {duration(elapsed)}, about "
                        f"{duration(left)} left")
        return True

    def set_postfix_str(self, text: str) -> None:  # the bar's call: nothing to draw
        """Accepted and ignored (a bar's status text)."""

    def close(self) -> None:
        """The last line, once, if every item is done (an interrupted run says nothing)."""
        if not self._closed and self.n >= self.total:
            self._write(f"{self.n}/{self._units(self.total)} done in "
                        f"{duration(self._clock() - self._t0)}")
        self._closed = True

    def __enter__(self) -> StageLines:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class _Bar:
    """A tqdm bar with the ``start`` call of :class:`StageLines` (which does nothing)."""

    def __init__(self, bar) -> None:
        self._bar = bar

    def start(self, where: str = "") -> None:
        """Nothing: the bar shows its own start."""

    def update(self, n: int = 1):
        return self._bar.update(n)

    def close(self) -> None:
        self._bar.close()

    def __enter__(self) -> _Bar:
        self._bar.__enter__()
        return self

    def __exit__(self, *exc) -> None:
        self._bar.__exit__(*exc)


def stage_progress(total: int, description: str, *, progress: bool | None, unit: str,
                   initial: int = 0):
    """The progress display of ``total`` items: the bar if ``progress`` is True (or None on
    a terminal), :class:`StageLines` if None without a terminal, nothing if False."""
    if progress is None and not progress_wanted(None):
        return StageLines(total, description, unit, initial=initial)
    return _Bar(progress_bar(total, description, progress=bool(progress_wanted(progress)),
                             unit=unit, initial=initial))


def stage_line(description: str, text: str, *, progress: bool | None) -> None:
    """One stage line (``gyroshell: DESCRIPTION: TEXT``) on stderr when ``progress`` is
    None and stderr is not a terminal (where :func:`stage_progress` writes lines)."""
    if progress is None and not progress_wanted(None):
        print(f"gyroshell: {description}: {text}", file=sys.stderr, flush=True)
