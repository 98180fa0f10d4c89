"""The frequency response's request, checked without loading scipy: the angular
frequencies (a list or ``START:STOP:NUM``, rad/s, within the solvers' range), the method and
the reduced model's ``tol`` and ``max_points``.

:mod:`gyroshell.engines.frequency_response` uses these checks (and re-exports them); the
command line calls them before anything is assembled.
"""

from __future__ import annotations

import math

import numpy as np

from ..core import validation
from ..core.errors import ParameterError

METHODS = ("auto", "direct", "reduced")
#: Default relative accuracy of the reduced model against direct solves.
DEFAULT_TOL = 1e-6
#: Largest number of interpolation frequencies (factorizations) of the reduced model, by
#: default.
MAX_POINTS = 40
#: Relative round-off level of the reduced evaluation, added to its error estimate (basis
#: orthogonalization and the small eigen-decomposition lose about 1e-9 against direct
#: solves).
ESTIMATE_ROUNDOFF = 1e-8
#: Allowed range of ``tol``: below the estimate's own round-off level the reduced model can
#: never meet it (every frequency would fall back to a direct solve); above 10 % the
#: amplitude is not a measurement.
MIN_TOL, MAX_TOL = ESTIMATE_ROUNDOFF, 0.1
#: Most interpolation frequencies a reduced model may take: each adds 2 x moments basis
#: vectors, and every round decomposes the dense first-order model of twice that size.
MAX_POINTS_LIMIT = 100


# ----- validation ----------------------------------------------------------------------
def max_frequency(density: float) -> float:
    """Largest angular frequency, rad/s, whose ρω² stays within the solvers' range (as
    :meth:`gyroshell.TapeParameters.max_velocity` for ρV²): 8.45e75 rad/s for the Table 1
    tape, far above any physical one."""
    return math.sqrt(validation.MAX_SCALE) / math.sqrt(density)


def check_frequencies(omega, *, density: float | None = None) -> np.ndarray:
    """Validate angular frequencies (rad/s): a non-empty 1-D list of finite values >= 0, and
    with ``density`` (kg/m²) at most :func:`max_frequency`.

    Examples
    --------
    >>> check_frequencies([0.0, 1e5], density=0.014)
    array([     0., 100000.])
    >>> check_frequencies([-1.0])
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: frequencies must be >= 0 rad/s, got -1
    """
    try:
        out = np.atleast_1d(np.asarray(omega, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError("frequencies must be a list of numbers >= 0, rad/s") from None
    if out.ndim != 1 or out.size == 0:
        raise ParameterError("frequencies must be a non-empty list of numbers >= 0, rad/s")
    if not np.all(np.isfinite(out)):
        bad = out[~np.isfinite(out)][0]
        raise ParameterError(f"frequencies must be finite, rad/s, got {bad}")
    if np.any(out < 0):
        raise ParameterError(f"frequencies must be >= 0 rad/s, got {out[out < 0][0]:g}")
    high = math.inf if density is None else max_frequency(density)
    if np.any(out > high):
        raise ParameterError(f"frequencies must be in [0, {high:g}] rad/s (rho omega^2 "
                             f"overflows the solvers' range above), got {out[out > high][0]:g}")
    return out


def _check_count(count: int) -> None:
    """Refuse a range of more than a million frequencies before making it."""
    if count > 10**6:
        raise ParameterError(f"frequencies: NUM must be <= 1000000, got {count}")


def parse_frequencies(text: str) -> np.ndarray:
    """'START:STOP:NUM' (NUM points, both ends included) or 'w1,w2,...', rad/s.

    Examples
    --------
    >>> parse_frequencies("0:1e5:3")
    array([     0.,  50000., 100000.])
    >>> parse_frequencies("1e5:0:3")
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: frequencies: need finite START <= STOP, got '1e5:0:3'
    """
    try:
        if ":" in text:
            from ..core.ranges import parse_range

            if len(text.split(":")) == 3:
                try:
                    a, b = (float(t) for t in text.split(":")[:2])
                except ValueError:
                    a = b = math.nan
                if math.isfinite(a) and math.isfinite(b) and b < a:
                    raise ParameterError(f"frequencies: need finite START <= STOP, got "
                                         f"{text!r}")
            return check_frequencies(parse_range(text, "frequencies", unit="rad/s",
                                                 limit=_check_count))
        return check_frequencies([float(s) for s in text.split(",") if s.strip()])
    except ValueError as exc:
        if isinstance(exc, ParameterError):
            raise
        raise ParameterError(f"frequencies must be 'START:STOP:NUM' or 'w1,w2,...' in rad/s, "
                             f"got {text!r}") from None


def check_options(method: str, tol, max_points) -> tuple[float, int]:
    """Validate ``method``, ``tol`` (in (:data:`MIN_TOL`, :data:`MAX_TOL`]) and
    ``max_points`` (in [1, :data:`MAX_POINTS_LIMIT`]); returns (tol, max_points)."""
    validation.choice("method", method, METHODS)
    tol = validation.real("tol", tol, low=MIN_TOL, high=MAX_TOL, low_open=True)
    return tol, validation.integer("max_points", max_points, low=1, high=MAX_POINTS_LIMIT)
