"""Tape definitions in TOML files, with units.

A file describes one tape (and optionally its speed); a value is a number in SI units or a
string ``"<number> <unit>"``::

    # tape.toml: the paper's Table 1 tape at 50 m/s
    [tape]
    name = "Table 1"              # optional, free text
    youngs_modulus = "4 GPa"
    poisson = 0.3
    thickness = "20 um"
    radius = "20 mm"
    density = "0.014 kg/m^2"
    tension = "90 N/m"
    width = "6.35 mm"
    length_ratio = 4
    spacing = "0.1549 mm"
    edges = "free"
    load = "200 Pa"
    velocity = "50 m/s"           # optional: the default tape speed

Keys are the :class:`~gyroshell.TapeParameters` fields plus ``velocity`` and
``name``; they may also sit at the top level instead of under ``[tape]``. Missing keys take
the Table 1 defaults. An unknown key, an unknown or mismatched unit, or a value out of range
raises :class:`~gyroshell.ParameterError` naming the file and the key.
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

from ..core.errors import InputFileError, ParameterError
from ..core.files import read_input
from ..core.units import ACCEPTED, SI_UNITS
from .parameters import TapeParameters, check_velocity

#: The numeric keys of a tape file; each has its SI unit in :data:`gyroshell.core.units.SI_UNITS`.
QUANTITIES: dict[str, str] = {key: SI_UNITS[key] for key in (
    "youngs_modulus", "poisson", "thickness", "radius", "density", "tension", "width",
    "length_ratio", "spacing", "load", "load_x", "load_y", "bending_rigidity",
    "foundation_stiffness", "velocity")}
TEXT_KEYS = ("edges", "name")
BOOL_KEYS = ("wrap_pressure",)
KEYS = tuple(QUANTITIES) + TEXT_KEYS + BOOL_KEYS

_VALUE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


@dataclass(frozen=True)
class TapeConfig:
    """A tape read from a file: its parameters, its speed (m/s, None if not given), its name."""

    params: TapeParameters
    velocity: float | None = None
    name: str | None = None
    #: Other tables the caller asked for (``tables=`` of :func:`load_config`), as parsed.
    tables: dict = dataclasses.field(default_factory=dict)


def _tomllib():
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib
    return tomllib


def parse_quantity(key: str, value, where: str = "", *, unit: str | None = None) -> float:
    """A number (SI) or ``"<number> <unit>"`` for ``key``, converted to SI; ``unit`` (an
    SI unit of :data:`~gyroshell.core.units.ACCEPTED`) for a key that is not a tape
    field's (a head's, :mod:`gyroshell.bearing.head_config`).

    Examples
    --------
    >>> parse_quantity("thickness", "20 um"), parse_quantity("tension", "0.09 N/mm")
    (2e-05, 90.0)
    """
    kind = QUANTITIES[key] if unit is None else unit
    prefix = f"{where}{key}"
    if isinstance(value, bool):
        raise ParameterError(f"{prefix} must be a number or '<number> <unit>', got {value!r}")
    if isinstance(value, int | float):
        number, factor = float(value), 1.0
    elif isinstance(value, str):
        match = _VALUE.match(value)
        if match is None:
            raise ParameterError(f"{prefix} must look like '<number> <unit>', got {value!r}")
        number, unit = float(match.group(1)), match.group(2)
        if unit not in ACCEPTED[kind]:
            allowed = ", ".join(u for u in ACCEPTED[kind] if u) or "no unit"
            raise ParameterError(f"{prefix}: unit {unit!r} is not a unit of {kind} "
                                 f"(use one of: {allowed})")
        factor = ACCEPTED[kind][unit]
        exponent = round(math.log10(factor))
        if math.isfinite(number) and factor == 10.0**exponent:
            # decimal prefixes are applied in decimal, rounded once: "20 um" is 2e-05 exactly
            from decimal import Decimal

            return float(Decimal(match.group(1)).scaleb(exponent))
    else:
        raise ParameterError(f"{prefix} must be a number or '<number> <unit>', got {value!r}")
    if not math.isfinite(number):
        raise ParameterError(f"{prefix} must be finite, got {value!r}")
    return number * factor


def config_from_dict(data: dict, where: str = "", adjust=None,
                     tables: tuple[str, ...] = ()) -> TapeConfig:
    """Validate a parsed TOML table (see the module docstring) into a :class:`TapeConfig`.

    ``adjust``, if given, maps the file's TapeParameters fields (a dict, SI) to those to
    validate (see :func:`load_config`); ``tables`` names other tables the file may hold
    beside the tape's (kept unparsed in :attr:`TapeConfig.tables`).
    """
    others = {t: data[t] for t in tables if t in data}
    data = {k: v for k, v in data.items() if k not in others}
    if "tape" in data:
        extra = sorted(set(data) - {"tape"})
        if extra:
            raise ParameterError(f"{where}unknown key(s) {', '.join(extra)} beside [tape]")
        data = data["tape"]
    if not isinstance(data, dict):
        raise ParameterError(f"{where}[tape] must be a table")
    unknown = sorted(set(data) - set(KEYS))
    if unknown:
        raise ParameterError(f"{where}unknown key(s) {', '.join(unknown)}; allowed: "
                             f"{', '.join(KEYS)}")
    fields: dict = {}
    velocity = name = None
    for key, value in data.items():
        if key in QUANTITIES:
            number = parse_quantity(key, value, where)
            if key == "velocity":
                try:
                    velocity = check_velocity(number)
                except ParameterError as exc:
                    raise ParameterError(f"{where}{exc}") from None
            else:
                fields[key] = number
        elif key in BOOL_KEYS:
            if not isinstance(value, bool):
                raise ParameterError(f"{where}{key} must be true or false, got {value!r}")
            fields[key] = value
        else:
            if not isinstance(value, str):
                raise ParameterError(f"{where}{key} must be text, got {value!r}")
            if key == "name":
                name = value
            else:
                fields[key] = value
    try:
        params = TapeParameters(**(fields if adjust is None else adjust(dict(fields))))
    except ParameterError as exc:
        raise ParameterError(f"{where}{exc}") from None
    return TapeConfig(params, velocity, name, others)


#: The UTF-8 byte order mark some editors put first; accepted and skipped (a BOM-prefixed
#: file is UTF-8 text, though tomllib alone would call its first line invalid).
UTF8_BOM = b"\xef\xbb\xbf"
#: Byte order marks of UTF-16 and UTF-32, for a message that says what the file is.
_OTHER_BOMS = ((b"\xff\xfe\x00\x00", "UTF-32"), (b"\x00\x00\xfe\xff", "UTF-32"),
               (b"\xff\xfe", "UTF-16"), (b"\xfe\xff", "UTF-16"))


def config_text_of(raw: bytes, where: str) -> str:
    """The text of a tape file's bytes: UTF-8 (a leading BOM skipped), else refused.

    Raises
    ------
    InputFileError
        ``<file>: not UTF-8 text (UTF-16 ...): TOML files are UTF-8`` for UTF-16/32 text, a
        binary file or NUL bytes, naming the offset of the first bad byte.
    """
    for bom, encoding in _OTHER_BOMS:
        if raw.startswith(bom):
            raise InputFileError(f"{where}not UTF-8 text ({encoding}, by its byte order "
                                 "mark): TOML files are UTF-8; save it as UTF-8")
    if raw.startswith(UTF8_BOM):
        raw = raw[len(UTF8_BOM):]
    nul = raw.find(b"\x00")
    if nul >= 0:
        raise InputFileError(f"{where}not UTF-8 text (a NUL byte at offset {nul}: binary, "
                             "or UTF-16 without a byte order mark): TOML files are UTF-8")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputFileError(f"{where}not UTF-8 text (byte 0x{raw[exc.start]:02x} at offset "
                             f"{exc.start}): TOML files are UTF-8") from None


def load_config(path: str | os.PathLike[str], *, adjust=None,
                tables: tuple[str, ...] = ()) -> TapeConfig:
    """Read a tape definition (TOML, see the module docstring).

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file.
    adjust : callable, optional
        Maps the file's TapeParameters fields (a dict of SI values) to the fields to
        validate: a caller that does not use some of them (the air bearing has no plate
        grid: ``spacing``, ``length_ratio``, the load) replaces them before
        :class:`TapeParameters` checks them.
    tables : tuple of str
        Other tables the file may hold beside the tape's (the bearing's ``[head]``):
        returned unparsed in :attr:`TapeConfig.tables`; any other table is refused.

    Raises
    ------
    MissingFileError
        If there is no such file (a ``FileNotFoundError`` too).
    InputFileError
        If ``path`` is a folder, unreadable, or not UTF-8 text (UTF-16, binary); a UTF-8
        byte order mark is accepted.
    ParameterError
        Invalid TOML, an unknown key, a unit or a value out of range, naming the file.
    """
    raw = read_input(path, what="config file")
    where = f"{os.fspath(path)}: "
    text = config_text_of(raw, where)
    try:
        data = _tomllib().loads(text)
    except _tomllib().TOMLDecodeError as exc:
        raise ParameterError(f"{where}not valid TOML: {exc}") from None
    return config_from_dict(data, where=where, adjust=adjust, tables=tables)


def _format(key: str, value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    unit = QUANTITIES[key]
    return repr(float(value)) if unit == "1" else f'"{float(value)!r} {unit}"'


def config_text(params: TapeParameters, velocity: float | None = None,
                name: str | None = None) -> str:
    """TOML text of a tape (SI values with their units; ``None`` fields left out).

    :func:`load_config` reads it back to equal parameters (floats written exactly).
    """
    lines = ["[tape]"]
    if name is not None:
        lines.append(f"name = {_format('name', name)}")
    for f in dataclasses.fields(params):
        value = getattr(params, f.name)
        if value is not None:
            lines.append(f"{f.name} = {_format(f.name, value)}")
    if velocity is not None:
        lines.append(f"velocity = {_format('velocity', check_velocity(velocity))}")
    return "\n".join(lines) + "\n"


def write_config(params: TapeParameters, path: str | os.PathLike[str], *,
                 velocity: float | None = None, name: str | None = None) -> Path:
    """Write a tape definition file (whole or not at all)."""
    from ..core.files import write_atomic

    text = config_text(params, velocity, name)
    return write_atomic(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
