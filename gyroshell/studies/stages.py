"""The progress of a study, sweep or Campbell diagram on stderr: the bar on a terminal, one
line per stage elsewhere.

On a terminal the bar is :func:`gyroshell.core.progress.progress_bar`. When stderr is a pipe
or a log file (``progress=None`` and no terminal), a bar would be noise, yet minutes of
silence look like a hang: :class:`StageLines` writes one line when the work starts (its
size and where it runs), one at each quarter done (with the elapsed time and an estimate
of the time left, from the rate so far) and one at the end. ``progress=False`` (the CLI's
``--quiet``) shows nothing, ``progress=True`` the bar.

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

from __future__ import annotations

import sys
import time
from collections.abc import Callable

from ..core.progress import progress_bar, progress_wanted

__all__ = ["QUARTERS", "StageLines", "stage_line", "stage_progress"]

#: The fractions done at which a line is written.
QUARTERS = (0.25, 0.5, 0.75)


class StageLines:
    """One stderr line per stage of ``total`` items (``unit`` each) of ``description``;
    the same calls as a tqdm bar (``update``, ``close``, a context manager).

    ``initial`` items are done before the start (a study's cached points); ``stream`` and
    ``clock`` (seconds) default to stderr and :func:`time.perf_counter`.
    """

    def __init__(self, total: int, description: str, unit: str, *, initial: int = 0,
                 stream=None, clock: Callable[[], float] = time.perf_counter) -> None:
        self.total, self.description, self.unit = int(total), description, unit
        self.n = self._first = int(initial)
        self._stream, self._clock = stream, clock
        self._t0 = clock()
        self._marks = [q for q in QUARTERS if q * self.total > self.n]
        self._closed = False

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
                        f"({100 * self.n / self.total:.0f} %) in {elapsed:.3g} s, about "
                        f"{left:.2g} s left")
        return True

    def set_postfix_str(self, text: str) -> None:  # the bar's call: nothing to draw
        """Accepted and ignored (a bar's status text)."""

    def close(self) -> None:
        """The last line, once, if every item is done (an interrupted run says nothing)."""
        if not self._closed and self.n >= self.total:
            self._write(f"{self.n}/{self._units(self.total)} done in "
                        f"{self._clock() - self._t0:.3g} s")
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
