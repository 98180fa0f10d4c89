"""What a parameter study computes at one point: the columns of each quantity and
:func:`evaluate`, which fills them and reports each quantity's failure in the row.

The engines are imported inside the functions: the CLI imports this module to parse its
options, before any numerical work.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from ..core.errors import ParameterError
from ..tape.parameters import TapeParameters
from .points import parameters_of

__all__ = ["COMPUTE_CHOICES", "MAX_COUNT", "STABILITY_VALUES", "check_compute", "check_row",
           "evaluate", "result_columns"]

#: What a study can compute at each point.
COMPUTE_CHOICES: tuple[str, ...] = ("critical", "modes", "static", "period", "bearing")
#: Most frequencies per point (the eigen-solver's limit,
#: :data:`gyroshell.linalg.qep.problem.MAX_COUNT`; not imported: it loads scipy).
MAX_COUNT = 50
#: Values of the ``stability`` column ("": the eigen-solve of the point failed).
STABILITY_VALUES: tuple[str, ...] = ("stable", "divergence", "flutter", "undetermined", "")


def check_compute(compute: str | Sequence[str]) -> tuple[str, ...]:
    """The quantities asked for, each once, in the order given.

    Raises
    ------
    ParameterError
        For none, or one not in :data:`COMPUTE_CHOICES`.

    Examples
    --------
    >>> check_compute(["modes", "critical", "modes"])
    ('modes', 'critical')
    """
    items = (compute,) if isinstance(compute, str) else tuple(compute)
    bad = [c for c in items if c not in COMPUTE_CHOICES]
    if bad or not items:
        raise ParameterError(f"compute must be one or more of {', '.join(COMPUTE_CHOICES)}, "
                             f"got {', '.join(map(repr, bad)) or 'nothing'}")
    return tuple(dict.fromkeys(items))


def result_columns(compute: Sequence[str], count: int, bearing=None) -> list[str]:
    """Names of the computed columns, in order, for ``compute`` and ``count`` (and, for
    ``bearing``, the setup's :attr:`~gyroshell.studies.head_study.BearingStudy.columns`).

    Examples
    --------
    >>> result_columns(("critical", "modes"), 2)
    ['critical_speed', 'divergence_speed', 'omega_1', 'omega_2', 'growth_rate',
     'stability', 'error']
    """
    cols: list[str] = []
    if "critical" in compute:
        cols += ["critical_speed", "divergence_speed"]
    if "modes" in compute:
        cols += [f"omega_{j + 1}" for j in range(count)] + ["growth_rate"]
    if "static" in compute:
        cols += ["load_point_deflection", "max_deflection"]
    if "period" in compute:
        cols += ["period"]
    if "modes" in compute or "period" in compute:
        cols += ["stability"]
    if "bearing" in compute:
        cols += list(bearing.columns)
    return cols + ["error"]


def evaluate(base: dict, velocity: float, point: dict, compute: tuple[str, ...],
             count: int, bearing=None) -> dict:
    """Compute one point; returns the computed columns (see :func:`result_columns`).

    Parameters
    ----------
    base : dict
        The base :class:`~gyroshell.TapeParameters` fields (plain values, so that a task
        pickles small).
    velocity : float
        Tape speed V, m/s, where the point does not set it.
    point : dict
        The point's validated values (:func:`gyroshell.studies.points.check_points`).
    compute : tuple of str
        What to compute (:data:`COMPUTE_CHOICES`).
    count : int
        Frequencies for ``modes``.
    bearing : BearingStudy, optional
        The head, air and grid of ``bearing`` (:mod:`gyroshell.studies.head_study`).

    Returns
    -------
    dict
        Column name to value. Each quantity is computed on its own: a failure (e.g.
        ``static`` above the critical speed) leaves NaN in that quantity's columns and is
        reported in ``error`` (``"static: SupercriticalError: message"``; several joined by
        " | "), while the other quantities of the point are kept.
    """
    row: dict = {c: math.nan for c in result_columns(compute, count, bearing)}
    if "stability" in row:
        row["stability"] = ""
    errors: list[str] = []

    def attempt(name: str, fn: Callable, *args) -> None:
        try:
            fn(*args)
        except Exception as exc:  # reported in the row; the study goes on
            errors.append(f"{name}: {type(exc).__name__}: {exc}".replace("\n", " "))

    if "bearing" in compute:
        from .head_study import bearing_row

        attempt("bearing", lambda: row.update(bearing_row(base, velocity, point, bearing)))
        if set(compute) == {"bearing"}:
            row["error"] = " | ".join(errors)
            return row
    built: list = []
    attempt("model", lambda: built.append(_model_of(base, velocity, point)))
    if built:
        model, v = built[0]
        eigen_name = "modes" if "modes" in compute else "period"
        for name, wanted, columns in (
                ("critical", "critical" in compute, _critical_columns),
                (eigen_name, "modes" in compute or "period" in compute, _eigen_columns),
                ("static", "static" in compute, _static_columns)):
            if wanted:
                attempt(name, columns, model, v, row, compute, count)
    row["error"] = " | ".join(errors)
    return row


def _model_of(base: dict, velocity: float, point: dict):
    """The point's TapeModel and speed V (m/s)."""
    from ..tape.model import TapeModel

    params, v = parameters_of(TapeParameters(**base), velocity, point)
    return TapeModel(params), v


def _critical_columns(model, v: float, row: dict, compute, count: int) -> None:
    """``critical_speed`` and ``divergence_speed`` (m/s) into ``row``."""
    from ..engines.critical import critical_speeds

    c = critical_speeds(model)
    row.update(critical_speed=c.critical_speed, divergence_speed=c.divergence_speed)


def _eigen_columns(model, v: float, row: dict, compute, count: int) -> None:
    """``omega_k`` and ``growth_rate`` (modes), ``period`` and ``stability`` into ``row``,
    each as soon as it is known (a later failure keeps them)."""
    from ..engines.eigen import modes
    from .stability import tape_stability

    res = modes(model, v, count if "modes" in compute else 1)
    if "modes" in compute:
        for j, w in enumerate(res.omega):
            row[f"omega_{j + 1}"] = float(w)
        row["growth_rate"] = float(np.max(res.eigenvalues.real.clip(min=0.0)))
    if "period" in compute:
        row["period"] = float(res.period[0])
    row["stability"] = tape_stability(model, v, res.eigenvalues)


def _static_columns(model, v: float, row: dict, compute, count: int) -> None:
    """``load_point_deflection`` and ``max_deflection`` (m) into ``row``."""
    from ..engines.static import solve_static

    s = solve_static(model, v)
    row.update(load_point_deflection=s.load_point_deflection,
               max_deflection=s.max_deflection)


#: The values each computed number may take: (lowest, whether +inf is allowed, unit); NaN
#: is always allowed (the quantity failed at that point and says so in ``error``).
_NUMBER_RANGES = {"critical_speed": (0.0, False, "m/s"), "divergence_speed": (0.0, False, "m/s"),
                  "omega": (0.0, False, "rad/s"), "growth_rate": (0.0, False, "1/s"),
                  "load_point_deflection": (-math.inf, False, "m"),
                  "max_deflection": (-math.inf, False, "m"), "period": (0.0, True, "s")}


def check_row(row: object, compute: Sequence[str], count: int, bearing=None) -> dict:
    """A row read back (from a cache), checked as strictly as a computed one: exactly the
    columns of :func:`result_columns`, each number real (NaN, or finite and in its range),
    ``stability`` one of :data:`STABILITY_VALUES`, ``error`` text. Returns the row with
    its numbers as floats.

    Raises
    ------
    ParameterError
        Naming the column and what it must be.

    Examples
    --------
    >>> check_row({"critical_speed": "fast", "divergence_speed": 101.0, "error": ""},
    ...           ("critical",), 1)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: critical_speed must be a number >= 0 m/s or NaN, got 'fast'
    """
    columns = result_columns(compute, count, bearing)
    if not isinstance(row, dict) or set(row) != set(columns):
        got = sorted(row) if isinstance(row, dict) else type(row).__name__
        raise ParameterError(f"row must have the columns {', '.join(columns)}, got {got}")
    out = {}
    bearing_columns = set(bearing.columns) if bearing is not None else set()
    for column in columns:
        out[column] = _checked_cell(column, row[column], column in bearing_columns)
    return out


def _checked_cell(column: str, value: object, of_bearing: bool = False):
    """One value of a row, checked (see :func:`check_row`)."""
    if column == "error":
        if not isinstance(value, str):
            raise ParameterError(f"error must be text, got {value!r}")
        return value
    if column == "stability":
        if value not in STABILITY_VALUES or not isinstance(value, str):
            raise ParameterError(f"stability must be one of "
                                 f"{', '.join(repr(v) for v in STABILITY_VALUES)}, got {value!r}")
        return value
    if of_bearing:
        from .head_study import number_range

        (low, unit), infinite = number_range(column), False
    else:
        low, infinite, unit = _NUMBER_RANGES["omega" if column.startswith("omega_")
                                              else column]
    allowed = (f"a number >= {low:g} {unit}" if low > -math.inf else f"a finite number {unit}")
    allowed += " (or inf)" if infinite else ""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"{column} must be {allowed} or NaN, got {value!r}")
    value = float(value)
    if math.isnan(value) or (math.isfinite(value) and value >= low) \
            or (infinite and value == math.inf):
        return value
    raise ParameterError(f"{column} must be {allowed} or NaN, got {value!r}")
