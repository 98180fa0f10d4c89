"""The points of a parameter study: which parameters may vary, grids of them, and the
checks that turn a user's points into validated ones.

A point is a mapping from parameter names (the :class:`~gyroshell.TapeParameters` fields in
SI units, and ``velocity`` in m/s) to values; names may use ``-`` for ``_``.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..core import budget
from ..core.errors import ParameterError
from ..tape.parameters import TapeParameters, check_velocity

__all__ = ["HEAD_VARIABLES", "VARIABLE_NAMES", "canonical_name", "check_points",
           "grid_points", "parameters_of"]

#: Parameters of the head a bearing study (``compute="bearing"``) can vary, SI (angles in
#: rad): :class:`gyroshell.bearing.head_config.HeadDesign` fields.
HEAD_VARIABLES: tuple[str, ...] = ("wrap_angle", "wrap_in", "wrap_out", "land_length",
                                   "corner_radius", "module_gap")
#: Parameters a study can vary: every TapeParameters field, plus the tape speed and the
#: head's parameters.
VARIABLE_NAMES: tuple[str, ...] = ("velocity",) + tuple(
    f.name for f in dataclasses.fields(TapeParameters)) + HEAD_VARIABLES


def canonical_name(name: str) -> str:
    """The variable's name as in :data:`VARIABLE_NAMES` (``-`` read as ``_``).

    Raises
    ------
    ParameterError
        If the name is not one a study can vary.

    Examples
    --------
    >>> canonical_name("youngs-modulus")
    'youngs_modulus'
    """
    key = str(name).strip().replace("-", "_")
    if key not in VARIABLE_NAMES:
        raise ParameterError(f"cannot vary {name!r}: choose from {', '.join(VARIABLE_NAMES)}")
    return key


def grid_points(vary: Mapping[str, Sequence]) -> list[dict]:
    """All combinations of the values in ``vary`` (the first name varies slowest).

    Raises
    ------
    ParameterError
        For an unknown name, a name without values, or more points than a study allows
        (:func:`gyroshell.core.budget.check_study_points`).

    Examples
    --------
    >>> grid_points({"velocity": [0.0, 50.0], "youngs-modulus": [4e9]})
    [{'velocity': 0.0, 'youngs_modulus': 4000000000.0},
     {'velocity': 50.0, 'youngs_modulus': 4000000000.0}]
    """
    names = [canonical_name(n) for n in vary]
    values = []
    for name, vals in zip(names, vary.values(), strict=True):
        vals = list(vals) if not isinstance(vals, str) else [vals]
        if not vals:
            raise ParameterError(f"{name} needs at least one value")
        values.append(vals)
    budget.check_study_points(math.prod(len(v) for v in values))
    return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*values)]


def check_points(base: TapeParameters, velocity: float, points: Sequence[Mapping]
                 ) -> tuple[list[dict], tuple[str, ...]]:
    """The points with canonical names and validated values, and the names varied.

    Parameters
    ----------
    base : TapeParameters
        The tape the points change.
    velocity : float
        Tape speed V, m/s, where a point does not set it.
    points : sequence of mappings
        The user's points.

    Returns
    -------
    points : list of dict
        Each value as the tape holds it (e.g. a word parameter normalized).
    varied : tuple of str
        Every name some point sets, in order of first appearance.

    Raises
    ------
    ParameterError
        For no point, or a bad one (the message names the point's index and values).
    """
    out, names = [], []
    for i, point in enumerate(points):
        clean = {}
        for name, value in point.items():
            key = canonical_name(name)
            if isinstance(value, np.generic):
                value = value.item()
            clean[key] = value
            if key not in names:
                names.append(key)
        try:
            params, v = parameters_of(base, velocity, clean)
        except ParameterError as exc:
            raise ParameterError(f"point {i} {clean}: {exc}") from None
        clean = {k: (v if k == "velocity" else clean[k] if k in HEAD_VARIABLES
                     else getattr(params, k)) for k in clean}
        out.append(clean)
    if not out:
        raise ParameterError("a study needs at least one point")
    return out, tuple(names)


def parameters_of(base: TapeParameters, velocity: float, point: Mapping
                  ) -> tuple[TapeParameters, float]:
    """The point's tape and speed V (m/s): ``base`` changed by the point's fields, and the
    point's ``velocity`` or else ``velocity``; the head's variables are not the tape's
    (:func:`gyroshell.studies.head_study.head_of_point`)."""
    changes = {k: v for k, v in point.items() if k != "velocity" and k not in HEAD_VARIABLES}
    v = check_velocity(point.get("velocity", velocity))
    return (base.replace(**changes) if changes else base), v
