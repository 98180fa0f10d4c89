"""The one meaning of a range in an option: ``START:STOP:NUM``, NUM evenly spaced values
from START to STOP, both included (``numpy.linspace``), in every option that takes one:
``sweep`` and ``campbell --velocities`` (m/s), ``frf --frequencies`` (rad/s), ``study
--vary NAME=...`` (the parameter's unit).

``sweep`` and ``campbell`` read ``START:STOP:STEP`` (a step, STOP included) until
:data:`STEP_FORM_ENDS`; :func:`old_step_range` tells that form apart where it can
(a STEP that is not a whole number, or one that steps exactly onto STOP and so gives
other values than NUM would) and says so in a notice.

Examples
--------
>>> parse_range("0:100:5", "--velocities", unit="m/s")
array([  0.,  25.,  50.,  75., 100.])
>>> parse_range("1:2", "--vary tension", unit="N/m")
Traceback (most recent call last):
...
gyroshell.ParameterError: --vary tension '1:2': use START:STOP:NUM (NUM values from START ...
"""

from __future__ import annotations

import math

import numpy as np

from .errors import ParameterError

__all__ = ["RANGE_FORM", "STEP_FORM_ENDS", "old_step_range", "parse_range", "range_count"]

#: How every range option is written.
RANGE_FORM = "START:STOP:NUM"
#: The release from which ``--velocities START:STOP:STEP`` is no longer read.
STEP_FORM_ENDS = "0.3"


def _numbers(text: str, option: str, unit: str) -> tuple[float, float, str]:
    """(START, STOP, the third field's text) of ``START:STOP:X``."""
    parts = text.split(":")
    form = (f"{option} {text!r}: use {RANGE_FORM} (NUM values from START to STOP, both "
            f"included, {unit})")
    if len(parts) != 3:
        raise ParameterError(form)
    try:
        start, stop = float(parts[0]), float(parts[1])
    except ValueError:
        raise ParameterError(form) from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise ParameterError(f"{option} {text!r}: every number must be finite ({unit})")
    return start, stop, parts[2].strip()


def range_count(text: str, option: str, *, unit: str) -> tuple[float, float, int]:
    """(START, STOP, NUM) of ``START:STOP:NUM``, checked: NUM a whole number >= 1, and
    NUM = 1 only with START = STOP (else STOP would be dropped).

    Raises
    ------
    ParameterError
        Naming the option and what is wrong.
    """
    start, stop, third = _numbers(text, option, unit)
    try:
        count = float(third)
    except ValueError:
        count = math.nan
    if not (math.isfinite(count) and count == int(count) and count >= 1):
        raise ParameterError(f"{option}: NUM must be an integer >= 1, got {third!r}")
    if count == 1 and start != stop:
        raise ParameterError(f"{option}: NUM = 1 gives START alone; use START = STOP or "
                             f"NUM >= 2, got {text!r}")
    return start, stop, int(count)


def parse_range(text: str, option: str, *, unit: str, limit=None) -> np.ndarray:
    """The values of ``START:STOP:NUM``: NUM evenly spaced from START to STOP, both
    included (either order). ``limit(num)`` may refuse NUM before the values are made.

    Raises
    ------
    ParameterError
        As :func:`range_count`, or what ``limit`` raises.
    """
    start, stop, count = range_count(text, option, unit=unit)
    if limit is not None:
        limit(count)
    return np.linspace(start, stop, count)


def old_step_range(text: str, option: str, *, unit: str
                   ) -> tuple[float, float, int, str] | None:
    """(START, STEP, the number of values, a one-line notice) if ``text`` is the old
    ``START:STOP:STEP`` form of ``--velocities``, read until :data:`STEP_FORM_ENDS`; None
    if it is ``START:STOP:NUM`` (or malformed: :func:`range_count` says how).

    The old form is recognised where it gives other values than NUM would: a STEP that is
    not a whole number (0:1:0.25), or a whole one that steps from START exactly onto a
    STOP above it in another number of values (0:100:10: 11 values, not 10). A STEP that
    gives the values NUM gives (0:90:10) is NUM; so is one that misses STOP (0:100:11).

    Examples
    --------
    >>> old_step_range("0:100:11", "--velocities", unit="m/s") is None
    True
    >>> start, step, count, notice = old_step_range("0:100:10", "--velocities", unit="m/s")
    >>> count, notice.split(";")[0]
    (11, '--velocities 0:100:10 is read as START:STOP:STEP (11 values, step 10 m/s)')
    """
    if ":" not in text or len(text.split(":")) != 3:
        return None
    try:
        start, stop, step = (float(part) for part in text.split(":"))
    except ValueError:
        return None
    if not (math.isfinite(start) and math.isfinite(stop) and math.isfinite(step)
            and step > 0 and stop > start):
        return None
    steps = (stop - start) / step
    if not math.isfinite(steps):
        return None
    lands = abs(steps - round(steps)) <= 1e-9 * max(1.0, steps)
    if step == int(step) and not (lands and round(steps) + 1 != step):
        return None
    count = math.floor(steps + 1e-9) + 1
    notice = (f"{option} {text} is read as START:STOP:STEP ({count} values, step {step:g} "
              f"{unit}); from release {STEP_FORM_ENDS} it means {RANGE_FORM} as in every "
              f"range option: write {start:g}:{start + (count - 1) * step:g}:{count}")
    return start, step, count, notice
