"""Argument checks shared by every public function: numbers, integers, flags, types, vectors.

Each check returns the value converted to its plain Python (or NumPy) type, or raises
:class:`~gyroshell.ParameterError` with a message that names the parameter, the
allowed range and the value received, e.g. ``thickness must be > 0 m, got -1e-06``.

Examples
--------
>>> real("velocity", 50, low=0.0, unit="m/s")
50.0
>>> real("velocity", -1, low=0.0, unit="m/s")
Traceback (most recent call last):
...
gyroshell.ParameterError: velocity must be >= 0 m/s, got -1
>>> integer("count", 6.0, low=1)
6
"""

from __future__ import annotations

import math
import numbers
import sys

import numpy as np

from .errors import ParameterError

#: Smallest positive normal double: scales below it have lost precision (subnormal) or are 0.
TINY = sys.float_info.min
#: Range of the operators' scales (entries of K, G, M and ratios such as k/ρ): the solvers
#: multiply two of them (ω² M, residual norms), so each must stay within the square root of
#: the double range. Physical tapes lie near 1e-10..1e10.
MIN_SCALE, MAX_SCALE = 1e-150, 1e150


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def real(name: str, value: object, *, low: float | None = None, high: float | None = None,
         low_open: bool = False, high_open: bool = False, unit: str = "") -> float:
    """A finite real number, optionally within [low, high] (or open ends), as float.

    Booleans, strings and complex numbers are refused: ``True`` is not a length.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.ndarray)):
        raise ParameterError(f"{name} must be a real number{_unit(unit)}, got {value!r}")
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a real number{_unit(unit)}, got {value!r}"
                             ) from None
    if not math.isfinite(value):
        raise ParameterError(f"{name} must be finite{_unit(unit)}, got {value}")
    if low is not None and (value < low or (low_open and value == low)):
        raise ParameterError(_range_message(name, value, low, high, low_open, high_open, unit))
    if high is not None and (value > high or (high_open and value == high)):
        raise ParameterError(_range_message(name, value, low, high, low_open, high_open, unit))
    return value


def _range_message(name, value, low, high, low_open, high_open, unit) -> str:
    if low is not None and high is not None:
        left, right = "(" if low_open else "[", ")" if high_open else "]"
        allowed = f"in {left}{low:g}, {high:g}{right}{_unit(unit)}"
    elif low is not None:
        allowed = f"{'>' if low_open else '>='} {low:g}{_unit(unit)}"
    else:
        allowed = f"{'<' if high_open else '<='} {high:g}{_unit(unit)}"
    return f"{name} must be {allowed}, got {value:g}"


def positive(name: str, value: object, unit: str = "") -> float:
    """A finite real number > 0."""
    return real(name, value, low=0.0, low_open=True, unit=unit)


def nonnegative(name: str, value: object, unit: str = "") -> float:
    """A finite real number >= 0."""
    return real(name, value, low=0.0, unit=unit)


def integer(name: str, value: object, *, low: int | None = None, high: int | None = None,
            optional: bool = False) -> int | None:
    """A whole number (an integral float such as 6.0 or 1e6 is accepted), within [low, high];
    with ``optional=True`` None is accepted too (and returned).

    Examples
    --------
    >>> integer("maxiter", None, low=1, optional=True) is None
    True
    >>> integer("maxiter", 2.5, low=1, optional=True)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: maxiter must be None or an integer, got 2.5
    """
    if optional and value is None:
        return None
    if low is not None and high is not None:
        allowed = f" in [{low}, {high}]"
    elif low is not None:
        allowed = f" >= {low}"
    else:
        allowed = "" if high is None else f" <= {high}"
    kind = f"{name} must be {'None or ' if optional else ''}an integer"
    if isinstance(value, (bool, np.bool_)):
        raise ParameterError(f"{kind}, got {value!r}")
    if isinstance(value, numbers.Integral):
        out = int(value)
    elif isinstance(value, numbers.Real) and math.isfinite(float(value)) \
            and float(value).is_integer():
        out = int(float(value))
    else:
        raise ParameterError(f"{kind}, got {value!r}")
    if (low is not None and out < low) or (high is not None and out > high):
        raise ParameterError(f"{kind}{allowed}, got {out}")
    return out


def boolean(name: str, value: object) -> bool:
    """True or False (NumPy booleans too); 0, 1, 'yes' and None are refused."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ParameterError(f"{name} must be True or False, got {value!r}")


def progress(value: object, name: str = "progress") -> bool | None:
    """An engine's ``progress=``: True (a bar on stderr), False (nothing) or None (the bar
    on a terminal, else what the engine reports in lines); returned as bool or None.

    Examples
    --------
    >>> progress(False)
    False
    >>> progress("yes")
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: progress must be True, False or None, got 'yes'
    """
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ParameterError(f"{name} must be True, False or None, got {value!r}")


def choice(name: str, value: object, choices: tuple[str, ...]) -> str:
    """One of ``choices``."""
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(f"{name} must be one of {', '.join(choices)}, got {value!r}")
    return value


def instance(name: str, value: object, cls: type | tuple[type, ...], *,
             optional: bool = False) -> object:
    """An instance of ``cls`` (or None with ``optional=True``), returned unchanged.

    Examples
    --------
    >>> instance("label", "tape", str)
    'tape'
    >>> instance("label", 3.0, str, optional=True)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: label must be a str or None, got float
    """
    if (optional and value is None) or isinstance(value, cls):
        return value
    names = [c.__name__ for c in (cls if isinstance(cls, tuple) else (cls,))]
    allowed = " or ".join(names + (["None"] if optional else []))
    raise ParameterError(f"{name} must be a {allowed}, got {type(value).__name__}")


def vector(name: str, value: object, length: int, unit: str = "") -> np.ndarray:
    """A finite real float vector of shape (length,) (a new array)."""
    try:
        out = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a real vector of length {length}{_unit(unit)}"
                             ) from None
    if out.shape != (length,):
        raise ParameterError(f"{name} must be a vector of length {length}{_unit(unit)}, "
                             f"got shape {out.shape}")
    if not np.all(np.isfinite(out)):
        raise ParameterError(f"{name} must be finite{_unit(unit)}: it has "
                             f"{int(np.count_nonzero(~np.isfinite(out)))} NaN or infinite "
                             "entries")
    return out


def finite_scale(name: str, value: float, unit: str = "", *, what: str = "") -> float:
    """A derived quantity that must be a finite, normal (not underflowed) positive number.

    ``what`` says which inputs it comes from, so the message points at them.
    """
    source = f" (from {what})" if what else ""
    if not math.isfinite(value):
        raise ParameterError(f"{name}{source} overflows: {value}{_unit(unit)}; "
                             "use values nearer the physical range")
    if not value >= TINY:
        raise ParameterError(f"{name}{source} underflows: {value:g}{_unit(unit)} is below "
                             f"{TINY:g}; use values nearer the physical range")
    return value


def scale(name: str, value: float, unit: str = "", *, what: str = "",
          lower: bool = True) -> float:
    """A derived scale of the operators: finite and within [MIN_SCALE, MAX_SCALE] (only
    <= MAX_SCALE with ``lower=False``, for quantities that may vanish, such as T and k).

    ``what`` says which inputs it comes from, so the message points at them.

    Examples
    --------
    >>> scale("k / density", 1.57e10, "1/s^2")
    15700000000.0
    >>> scale("k / density", 1e200, "1/s^2", what="the shell stiffness and density")
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: k / density (from the shell stiffness and density) ...
    """
    source = f" (from {what})" if what else ""
    if not value <= MAX_SCALE:
        raise ParameterError(f"{name}{source} overflows the solvers' range: {value:g}"
                             f"{_unit(unit)} > {MAX_SCALE:g}; use values nearer the physical "
                             "range")
    if lower and not value >= MIN_SCALE:
        raise ParameterError(f"{name}{source} underflows the solvers' range: {value:g}"
                             f"{_unit(unit)} < {MIN_SCALE:g}; use values nearer the physical "
                             "range")
    return value


def time_step(dt: object, beta: object, *, stiffness_scale: float | None = None) -> float:
    """A Newmark time step Δt, s: > 0 and finite, with βΔt² >= MIN_SCALE (no underflow
    towards zero, which divides the corrector) and βΔt² · max|K_ii| <= MAX_SCALE (no
    overflow in the Newmark matrix M + γΔt G + βΔt² K). Returns Δt.

    Examples
    --------
    >>> time_step(2e-6, 0.25)
    2e-06
    >>> time_step(1e-170, 0.25)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: dt 1e-170 s is too small: beta x dt^2 = 0 s^2 ...
    """
    dt = positive("dt", dt, "s")
    beta = positive("beta", beta)
    bdt2 = beta * dt * dt
    if not bdt2 >= MIN_SCALE:
        raise ParameterError(f"dt {dt:g} s is too small: beta x dt^2 = {bdt2:g} s^2 underflows "
                             f"the solvers' range (need beta x dt^2 >= {MIN_SCALE:g} s^2)")
    if not bdt2 <= MAX_SCALE or (stiffness_scale is not None
                                 and not bdt2 * stiffness_scale <= MAX_SCALE):
        raise ParameterError(f"dt {dt:g} s is too large: beta x dt^2 x K overflows the "
                             f"solvers' range ({MAX_SCALE:g})")
    return dt
