"""What a saved file must hold, checked before a kind reads it: read back as strictly as typed.

A file read by :func:`gyroshell.load` may be truncated, edited by hand, written by another
tool or by a newer gyroshell. Before a kind's ``from_xarray`` sees it, :func:`check_dataset`
checks the metadata every file carries and the kind's :class:`Layout`:

* ``gyroshell_version``: present, a version, not newer than this gyroshell's major.minor;
* ``parameters``: JSON ``null`` or an object with exactly the
  :class:`~gyroshell.TapeParameters` fields (the orthotropic ones may be absent, as in the
  files of release 0.1.0; ``layers`` a list of objects of the Layer fields), validated by
  TapeParameters itself (so a negative tension or a stack whose thickness disagrees with
  its layers is refused as when typed); ``grid``: likewise with the
  :class:`~gyroshell.Grid` fields; ``info``: a JSON object;
* every variable of the layout: present (a complex one as its ``_real``/``_imag`` pair),
  on its dimensions, numbers where numbers belong (not text), finite where NaN has no
  meaning, and its own check (a speed through :func:`~gyroshell.tape.parameters.
  check_velocity`, a time step > 0, ...);
* the dimensions ``x``, ``y`` (and ``unknown``) against the stored grid, and the JSON
  attributes of the layout (counts as counts, flags as 0/1).

Every refusal is an :class:`~gyroshell.core.errors.InputFileError` (a ParameterError) whose
one line names the file and the field: ``"static.nc: parameters: tension must be >= 0 N/m,
got -5"``.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.errors import InputFileError, ParameterError
from ..core.version import __version__

#: Accepted dtype kinds (numpy ``dtype.kind``) of each declared variable kind.
_DTYPE_KINDS = {"float": "fiu", "int": "iu", "bool": "biu", "text": "USO"}
_NAMES = {"float": "numbers", "int": "integers", "bool": "flags (0/1)", "text": "text"}
_VERSION = re.compile(r"^(\d+)\.(\d+)(?:[.+\-].*)?$")


@dataclass(frozen=True)
class Variable:
    """One variable a kind's file holds.

    Attributes
    ----------
    dims : tuple of str
        Its dimensions, in order (``()`` for a scalar).
    kind : {"float", "int", "bool", "text", "complex"}
        What its values are; ``"complex"`` is stored as ``<name>_real``, ``<name>_imag``.
    finite : bool
        Refuse NaN and infinite values.
    optional : bool
        The variable may be absent (files of the previous release, optional records).
    check : callable, optional
        ``check(values)`` raising ParameterError for values out of range (e.g. a speed).
    """

    dims: tuple[str, ...]
    kind: str = "float"
    finite: bool = True
    optional: bool = False
    check: Callable[[np.ndarray], object] | None = None


@dataclass(frozen=True)
class Attr:
    """One JSON attribute a kind's file holds; ``check(value)`` raises ParameterError."""

    check: Callable[[object], object]
    optional: bool = False


@dataclass(frozen=True)
class Layout:
    """What a kind's file holds: its variables and JSON attributes, by name."""

    variables: Mapping[str, Variable] = field(default_factory=dict)
    attrs: Mapping[str, Attr] = field(default_factory=dict)
    #: Metadata attributes that must not be ``null`` (e.g. ``("grid",)``).
    needs: tuple[str, ...] = ()
    #: ``check(ds)`` raising ParameterError: what the fields above cannot say (a table's
    #: columns, sizes that must agree).
    check: Callable[[object], object] | None = None


def _decode(obj: dict) -> Any:
    if set(obj) == {"__complex__"}:
        re, im = obj["__complex__"]
        return complex(re, im)
    return obj


def from_json(text: str) -> Any:
    """The metadata written by :func:`gyroshell.results.base.to_json` (complex numbers
    back as complex)."""
    return json.loads(text, object_hook=_decode)


# ----- reusable checks -------------------------------------------------------------------
def scalar_check(check: Callable[[float], object]) -> Callable[[np.ndarray], object]:
    """A variable check applying ``check`` to a scalar variable's value."""
    return lambda values: check(values.item())


def each(check: Callable[[float], object]) -> Callable[[np.ndarray], object]:
    """A variable check applying ``check`` to every value."""
    def apply(values: np.ndarray) -> None:
        for value in np.ravel(values).tolist():
            check(value)
    return apply


def count(name: str, low: int = 0) -> Callable[[object], object]:
    """An attribute check: an integer >= ``low`` (not a bool, not 2.5)."""
    def apply(value: object) -> None:
        if isinstance(value, bool) or not isinstance(value, int) or value < low:
            raise ParameterError(f"{name} must be an integer >= {low}, got {value!r}")
    return apply


def flag(name: str) -> Callable[[object], object]:
    """An attribute check: 0 or 1 (how flags are stored), or true/false."""
    def apply(value: object) -> None:
        if value not in (0, 1) or isinstance(value, float):
            raise ParameterError(f"{name} must be 0 or 1, got {value!r}")
    return apply


def of_type(name: str, kind: type | tuple[type, ...], what: str) -> Callable[[object], object]:
    """An attribute check: a JSON value of Python type ``kind`` (described as ``what``);
    true/false is not a number here."""
    kinds = kind if isinstance(kind, tuple) else (kind,)

    def apply(value: object) -> None:
        if not isinstance(value, kinds) or (isinstance(value, bool) and bool not in kinds):
            raise ParameterError(f"{name} must be {what}, got {value!r}")
    return apply


def monotonic(name: str) -> Callable[[np.ndarray], object]:
    """A variable check: strictly increasing values (times, coordinates)."""
    def apply(values: np.ndarray) -> None:
        if values.size > 1 and not np.all(np.diff(values) > 0):
            raise ParameterError(f"{name} must be strictly increasing")
    return apply


# ----- the checks of a file ---------------------------------------------------------------
def check_dataset(ds, layout: Layout | None, source: str) -> None:
    """Refuse a dataset whose metadata or variables a kind could not read as saved.

    Raises
    ------
    InputFileError
        Naming ``source`` (the file) and the field, and what is wrong with it.
    """
    check_version(ds.attrs, source)
    grid = check_metadata(ds.attrs, source)
    if layout is None:
        return
    for name, variable in layout.variables.items():
        _check_variable(ds, name, variable, source)
    for name, attr in layout.attrs.items():
        _check_attr(ds.attrs, name, attr, source)
    for name in layout.needs:
        if json_attr(ds.attrs, name, source) is None:
            raise InputFileError(f"{source}: {name} is missing or null; a "
                                 f"{ds.attrs.get('gyroshell_type')} file stores it")
    if grid is not None:
        _check_against_grid(ds, grid, source)
    if layout.check is not None:
        try:
            layout.check(ds)
        except ParameterError as exc:
            raise InputFileError(f"{source}: {exc}") from None


def check_version(attrs: Mapping, source: str) -> None:
    """``gyroshell_version``: a version string no newer (major.minor) than this package's."""
    version = attrs.get("gyroshell_version")
    if version is None:
        raise InputFileError(f"{source}: no gyroshell_version attribute: not a file written "
                             "by gyroshell")
    match = _VERSION.match(str(version))
    if not isinstance(version, str) or match is None:
        raise InputFileError(f"{source}: gyroshell_version {version!r} is not a version "
                             "(like 0.1.0)")
    ours = _VERSION.match(__version__)
    if ours is not None and tuple(map(int, match.groups())) > tuple(map(int, ours.groups())):
        raise InputFileError(f"{source}: written by gyroshell {version}, newer than this "
                             f"gyroshell {__version__}; upgrade gyroshell to read it")


def json_attr(attrs: Mapping, name: str, source: str, default: str = "null"):
    """The JSON value of attribute ``name`` (``default`` text if absent), or refused."""
    text = attrs.get(name, default)
    if not isinstance(text, str):
        raise InputFileError(f"{source}: attribute {name} must be JSON text, got "
                             f"{type(text).__name__}")
    try:
        return from_json(text)
    except (json.JSONDecodeError, ValueError, TypeError):  # bad JSON or a bad __complex__
        raise InputFileError(f"{source}: attribute {name} is not valid JSON: "
                             f"{text[:60]!r}") from None


def _fields_of(attrs: Mapping, name: str, cls: type, source: str,
               optional: tuple[str, ...] = ()):
    """``cls(**attrs[name])`` for a dataclass stored as JSON (None for ``null``), its keys
    exactly the fields (those in ``optional``, added since files were first written, may
    be absent and take their defaults), validated by ``cls`` itself."""
    data = json_attr(attrs, name, source)
    if data is None:
        return None
    if not isinstance(data, dict):
        raise InputFileError(f"{source}: {name} must be a JSON object of "
                             f"{cls.__name__} fields, got {type(data).__name__}")
    expected = {f.name for f in dataclasses.fields(cls)}
    extra = sorted(set(data) - expected)
    missing = sorted(expected - set(data) - set(optional))
    if extra:
        raise InputFileError(f"{source}: {name}: unknown field(s) {', '.join(extra)}; a "
                             f"{cls.__name__} has {', '.join(sorted(expected))}")
    if missing:
        raise InputFileError(f"{source}: {name}: missing field(s) {', '.join(missing)}")
    try:
        return cls(**data)
    except ParameterError as exc:
        raise InputFileError(f"{source}: {name}: {exc}") from None


def check_metadata(attrs: Mapping, source: str):
    """Check ``parameters``, ``grid`` (spanning the tape of ``parameters`` where both are
    stored) and ``info``; returns the stored Grid (or None)."""
    from ..tape.grid import Grid
    from ..tape.parameters import ORTHOTROPIC_FIELDS, TapeParameters

    params = _fields_of(attrs, "parameters", TapeParameters, source,
                        optional=ORTHOTROPIC_FIELDS)
    grid = _fields_of(attrs, "grid", Grid, source)
    if params is not None and grid is not None:
        try:
            grid.check_matches(params)
        except ParameterError as exc:
            raise InputFileError(f"{source}: {exc}") from None
    info = json_attr(attrs, "info", source, default="{}")
    if not isinstance(info, dict):
        raise InputFileError(f"{source}: info must be a JSON object, got "
                             f"{type(info).__name__}")
    return grid


def _stored(ds, name: str, variable: Variable) -> list[str]:
    if variable.kind == "complex":
        return [f"{name}_real", f"{name}_imag"]
    return [name]


def _check_variable(ds, name: str, variable: Variable, source: str) -> None:
    parts = _stored(ds, name, variable)
    present = [part in ds.variables for part in parts]
    if not any(present) and variable.optional:
        return
    for part, here in zip(parts, present, strict=True):
        if not here:
            raise InputFileError(f"{source}: missing variable {part}")
    for part in parts:
        _check_values(ds[part], part, variable, source)
    if variable.check is not None:
        values = np.asarray(ds[parts[0]].values)
        try:
            variable.check(values)
        except ParameterError as exc:
            raise InputFileError(f"{source}: {exc}") from None


def _check_values(array, name: str, variable: Variable, source: str) -> None:
    if tuple(array.dims) != tuple(variable.dims):
        raise InputFileError(f"{source}: variable {name} has dimensions {tuple(array.dims)}, "
                             f"expected {tuple(variable.dims)}")
    kind = "float" if variable.kind == "complex" else variable.kind
    values = array.values
    if values.dtype.kind not in _DTYPE_KINDS[kind]:
        raise InputFileError(f"{source}: variable {name} holds {_describe(values)}, "
                             f"expected {_NAMES[kind]}")
    if kind == "bool" and values.dtype.kind in "iu" and not np.isin(values, (0, 1)).all():
        raise InputFileError(f"{source}: variable {name} must hold 0 or 1")
    if kind == "text" and values.dtype.kind == "O" and not all(
            isinstance(v, str) for v in values.ravel().tolist()):
        raise InputFileError(f"{source}: variable {name} must hold text")
    if variable.finite and kind == "float" and not np.all(np.isfinite(values)):
        raise InputFileError(f"{source}: variable {name} has NaN or infinite values")


def _describe(values: np.ndarray) -> str:
    kind = values.dtype.kind
    if kind in "USO":
        return f"text ({values.dtype})"
    return f"{values.dtype} values"


def _check_attr(attrs: Mapping, name: str, attr: Attr, source: str) -> None:
    if name not in attrs:
        if attr.optional:
            return
        raise InputFileError(f"{source}: missing attribute {name}")
    value = attrs[name]
    if isinstance(value, str):
        value = json_attr(attrs, name, source)
    elif isinstance(value, np.generic):
        value = value.item()
    try:
        attr.check(value)
    except ParameterError as exc:
        raise InputFileError(f"{source}: attribute {exc}") from None


def _check_against_grid(ds, grid, source: str) -> None:
    """Sizes (and coordinates) of ``x``, ``y``, ``unknown`` against the stored grid."""
    expected = {"x": grid.nx + 1, "y": grid.ny + 1, "unknown": grid.unknowns}
    for dim, size in expected.items():
        if dim in ds.sizes and ds.sizes[dim] != size:
            raise InputFileError(f"{source}: dimension {dim} has {ds.sizes[dim]} entries but "
                                 f"the stored grid ({grid.nx} x {grid.ny} intervals, "
                                 f"{grid.edges} edges) has {size}")
    for dim, nodes in (("x", grid.x), ("y", grid.y)):
        if dim in ds.variables and ds[dim].dtype.kind in "fiu" and not np.allclose(
                ds[dim].values, nodes, rtol=1e-9, atol=0.0):
            raise InputFileError(f"{source}: coordinate {dim} does not match the stored grid "
                                 f"(length {grid.length:g} m, width {grid.width:g} m)")


def finite_number(name: str, unit: str = "") -> Callable[[float], object]:
    """A scalar check: a finite real number."""
    def apply(value: float) -> None:
        if not math.isfinite(value):
            raise ParameterError(f"{name} must be finite {unit}".rstrip() + f", got {value!r}")
    return apply


def nonnegative(name: str, unit: str = "") -> Callable[[np.ndarray], object]:
    """A variable check: every value finite and >= 0 (a speed, a rate, a residual)."""
    from ..core import validation

    return each(lambda value: validation.nonnegative(name, value, unit))


def positive(name: str, unit: str = "") -> Callable[[np.ndarray], object]:
    """A variable check: every value finite and > 0 (a time step)."""
    from ..core import validation

    return each(lambda value: validation.positive(name, value, unit))


def speed(name: str = "velocity") -> Callable[[np.ndarray], object]:
    """A variable check: tape speeds through :func:`~gyroshell.tape.parameters.check_velocity`
    (the message names ``name``)."""
    from ..tape.parameters import check_velocity

    def apply(values: np.ndarray) -> None:
        for value in np.ravel(values).tolist():
            try:
                check_velocity(value)
            except ParameterError as exc:
                raise ParameterError(str(exc).replace("velocity", name, 1)) from None
    return apply


def table_columns(ds, *, attribute: str = "columns", dim: str = "row") -> None:
    """A layout check: ``attribute`` lists text column names, each a variable on ``dim``."""
    columns = ds.attrs.get(attribute)
    try:
        names = from_json(columns) if isinstance(columns, str) else None
    except (json.JSONDecodeError, ValueError):
        names = None
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise ParameterError(f"attribute {attribute} must be a JSON list of column names")
    for name in names:
        if name not in ds.variables:
            raise ParameterError(f"column {name} (listed in {attribute}) is missing")
        if tuple(ds[name].dims) != (dim,):
            raise ParameterError(f"column {name} has dimensions {tuple(ds[name].dims)}, "
                                 f"expected ({dim!r},)")


def json_object(name: str) -> Attr:
    """A required JSON attribute holding an object (``{...}``)."""
    return Attr(of_type(name, dict, "a JSON object"))


#: The ``info`` attribute as most kinds read it: a JSON object, required.
INFO = json_object("info")
#: Node coordinates of a grid, m.
X = Variable(("x",), check=monotonic("x"))
Y = Variable(("y",), check=monotonic("y"))
