"""The points of a parameter study: which parameters may vary, grids of them, and the
checks that turn a user's points into validated ones.

A point is a mapping from parameter names (the :class:`~gyroshell.TapeParameters` fields in
SI units, and ``velocity`` in m/s) to values; names may use ``-`` for ``_``. A layered tape's
layers vary one quantity at a time as ``layer<N>.<key>``: ``layer2.thickness`` is the
thickness (m) of the second layer from the bottom (counted from 1, in the order of the
``[[layer]]`` tables of a tape file), ``<key>`` one of the
:class:`~gyroshell.tape.material.Layer` fields; the tape's thickness, areal density, E_x and
ν_xy then follow from the changed stack (:meth:`~gyroshell.TapeParameters.with_layers`).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..core import budget, validation
from ..core.errors import ParameterError
from ..core.units import LAYER_NAME, LAYER_UNITS
from ..tape.parameters import TapeParameters, check_velocity

__all__ = ["BEARING_VARIABLES", "BOOLEAN_VARIABLES", "BOTH_WRAPS", "CHOICE_VARIABLES",
           "HEAD_VARIABLES", "INTERFACE_VARIABLES", "LAYER_VARIABLES", "VARIABLE_NAMES",
           "canonical_name", "check_points", "design_fields", "grid_points",
           "parameters_of"]

#: The head variable that sets both wraps of a flat or measured head, ``wrap_in`` and
#: ``wrap_out``, to one value (rad): ``vary={"wrap": [...]}``.
BOTH_WRAPS = "wrap"
#: Parameters of the head a bearing study (``compute="bearing"``) can vary, SI (angles in
#: rad): :class:`gyroshell.bearing.head_config.HeadDesign` fields, and :data:`BOTH_WRAPS`.
HEAD_VARIABLES: tuple[str, ...] = ("wrap_angle", "wrap_in", "wrap_out", "land_length",
                                   "corner_radius", "module_gap", BOTH_WRAPS)
#: Parameters of the head–tape interface a bearing study can vary: the film's models
#: (:class:`gyroshell.bearing.air.AirParameters` ``rarefaction``, ``flow_factors``) and
#: the contact's (:class:`gyroshell.bearing.contact.ContactParameters`: ``contact`` is its
#: law; the others its fields, SI).
INTERFACE_VARIABLES: tuple[str, ...] = ("rarefaction", "flow_factors", "contact",
                                        "roughness", "asperity_density", "asperity_radius",
                                        "contact_modulus")
#: The interface variables whose values are words, and the words each takes.
CHOICE_VARIABLES: dict[str, tuple[str, ...]] = {
    "rarefaction": ("fukui-kaneko", "first-order", "second-order", "none"),
    "flow_factors": ("patir-cheng", "none"),
    "contact": ("asperity", "hard"),
}
#: The variables that set the bearing, not the tape.
BEARING_VARIABLES: tuple[str, ...] = HEAD_VARIABLES + INTERFACE_VARIABLES
#: TapeParameters fields that are not one number: a study varies a layer's quantities one by
#: one (:data:`LAYER_VARIABLES`), and not the four bending stiffnesses.
NOT_SCALAR = ("bending_stiffness", "layers")
#: Parameters a study can vary: every scalar TapeParameters field, plus the tape speed and
#: the head's parameters.
VARIABLE_NAMES: tuple[str, ...] = ("velocity",) + tuple(
    f.name for f in dataclasses.fields(TapeParameters) if f.name not in NOT_SCALAR
) + BEARING_VARIABLES
#: The variables that are yes or no (True or False), not numbers.
BOOLEAN_VARIABLES: tuple[str, ...] = tuple(
    f.name for f in dataclasses.fields(TapeParameters) if f.type in (bool, "bool"))
#: How the quantities of a layered tape's layers are named (see the module docstring).
LAYER_VARIABLES = f"layer<N>.<key> (key: {', '.join(LAYER_UNITS)})"


def design_fields(names) -> tuple[str, ...]:
    """The :class:`~gyroshell.bearing.head_config.HeadDesign` fields the head variables
    among ``names`` set (:data:`BOTH_WRAPS` sets ``wrap_in`` and ``wrap_out``).

    Examples
    --------
    >>> design_fields(["tension", "wrap", "land_length"])
    ('wrap_in', 'wrap_out', 'land_length')
    """
    out: list[str] = []
    for name in names:
        if name == BOTH_WRAPS:
            out += ["wrap_in", "wrap_out"]
        elif name in HEAD_VARIABLES:
            out.append(name)
    return tuple(dict.fromkeys(out))


def canonical_name(name: str) -> str:
    """The variable's name as in :data:`VARIABLE_NAMES` (``-`` read as ``_``).

    Raises
    ------
    ParameterError
        If the name is not one a study can vary.

    Examples
    --------
    >>> canonical_name("youngs-modulus"), canonical_name("layer2.youngs-modulus-y")
    ('youngs_modulus', 'layer2.youngs_modulus_y')
    """
    key = str(name).strip().replace("-", "_")
    layer = LAYER_NAME.match(key)
    if layer is not None:
        number, quantity = int(layer.group(1)), layer.group(2)
        if quantity not in LAYER_UNITS:
            raise ParameterError(f"cannot vary {name!r}: a layer has "
                                 f"{', '.join(LAYER_UNITS)}")
        if number < 1:
            raise ParameterError(f"cannot vary {name!r}: layers are counted from 1 at the "
                                 "bottom (layer1, layer2, ...)")
        return f"layer{number}.{quantity}"
    if key not in VARIABLE_NAMES:
        raise ParameterError(f"cannot vary {name!r}: choose from {', '.join(VARIABLE_NAMES)}, "
                             f"or a layer's {LAYER_VARIABLES}")
    return key


def layer_of(name: str) -> tuple[int, str] | None:
    """(index from 0, Layer field) of a canonical ``layer<N>.<key>`` name, else None."""
    layer = LAYER_NAME.match(name)
    return None if layer is None else (int(layer.group(1)) - 1, layer.group(2))


def check_layer_names(base: TapeParameters, names) -> None:
    """Refuse a ``layer<N>.<key>`` of a layer ``base`` does not have.

    Examples
    --------
    >>> check_layer_names(TapeParameters(), ["tension", "layer1.thickness"])
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: cannot vary layer1.thickness: the tape has no layers ...
    """
    count = 0 if base.layers is None else len(base.layers)
    for name in names:
        layer = layer_of(name)
        if layer is None or layer[0] < count:
            continue
        if count == 0:
            raise ParameterError(f"cannot vary {name}: the tape has no layers (give them with "
                                 "TapeParameters.from_layers or [[layer]] tables in a tape "
                                 "file)")
        raise ParameterError(f"cannot vary {name}: the tape has {count} layer"
                             f"{'s' if count > 1 else ''} (layer1 to layer{count}, bottom up)")


def value_of(params: TapeParameters, velocity: float, name: str):
    """The value of the canonical variable ``name`` on the tape ``params`` at speed V."""
    if name == "velocity":
        return velocity
    layer = layer_of(name)
    if layer is None:
        return getattr(params, name)
    return getattr(params.layers[layer[0]], layer[1])


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


def check_speed(velocity: object, *, signed: bool = False) -> float:
    """A tape speed V, m/s: finite and >= 0 (:func:`~gyroshell.tape.parameters.
    check_velocity`), or, ``signed``, any finite real number (the air bearing alone: the
    tape runs along +x or -x)."""
    if signed:
        return validation.real("velocity", velocity, unit="m/s")
    return check_velocity(velocity)


def check_points(base: TapeParameters, velocity: float, points: Sequence[Mapping], *,
                 signed: bool = False) -> tuple[list[dict], tuple[str, ...]]:
    """The points with canonical names and validated values, and the names varied.

    Parameters
    ----------
    base : TapeParameters
        The tape the points change.
    velocity : float
        Tape speed V, m/s, where a point does not set it.
    points : sequence of mappings
        The user's points.
    signed : bool
        Speeds of either sign (a study of the air bearing alone, :func:`check_speed`).

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
    check_layer_names(base, {canonical_name(name) for point in points for name in point})
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
            params, v = parameters_of(base, velocity, clean, signed=signed)
        except ParameterError as exc:
            raise ParameterError(f"point {i} {clean}: {exc}") from None
        clean = {k: clean[k] if k in BEARING_VARIABLES else value_of(params, v, k)
                 for k in clean}
        out.append(clean)
    if not out:
        raise ParameterError("a study needs at least one point")
    return out, tuple(names)


def parameters_of(base: TapeParameters, velocity: float, point: Mapping, *,
                  signed: bool = False) -> tuple[TapeParameters, float]:
    """The point's tape and speed V (m/s): ``base`` changed by the point's fields (its
    layers by the ``layer<N>.<key>`` ones), and the point's ``velocity`` or else
    ``velocity`` (of either sign if ``signed``, :func:`check_speed`); the head's variables
    are not the tape's (:func:`gyroshell.studies.head_study.head_of_point`)."""
    changes = {k: v for k, v in point.items()
               if k != "velocity" and layer_of(k) is None and k not in BEARING_VARIABLES}
    v = check_speed(point.get("velocity", velocity), signed=signed)
    params = base
    layer_changes = {k: v for k, v in point.items() if layer_of(k) is not None}
    if layer_changes:
        check_layer_names(base, layer_changes)
        layers = list(base.layers)
        for name, value in layer_changes.items():
            index, key = layer_of(name)
            try:
                layers[index] = dataclasses.replace(layers[index], **{key: value})
            except ParameterError as exc:
                raise ParameterError(f"layer{index + 1}.{exc}") from None
        params = params.with_layers(layers)
    return (params.replace(**changes) if changes else params), v
