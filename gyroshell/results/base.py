"""The one result protocol: every result saves, converts, summarizes and plots the same way.

A result kind is a subclass of :class:`Result` that names itself, ``class StaticSolution(
Result, kind="static")``; the base keeps a registry of kinds filled by ``__init_subclass__``,
so reading a file looks its stored kind up there and the base never names a subclass. Each
kind implements

``to_xarray()``
    An :class:`xarray.Dataset` with named dimensions (``x``, ``y`` in m, ``t`` in s,
    ``mode``, ``row``...), SI units as ``units`` attributes and the metadata below.
``from_xarray(ds)`` (class method)
    The same object again from such a dataset: every array and parameter bit-exact.
``summary()``
    A dict of plain numbers and text (what the CLI's ``--json`` prints).
``plot(ax=None)``
    Its usual figure, drawn by :mod:`gyroshell.plot`; returns the Axes.
``to_frame()``
    A :class:`pandas.DataFrame`, where a table fits the result.

and inherits :meth:`Result.save` (NetCDF for every kind, CSV or Parquet for tables).
:func:`read` opens a NetCDF file and returns the object of its stored kind.

In a notebook a result shows its summary: ``repr`` is one line of at most
:data:`REPR_LIMIT` characters (the kind, then the summary's numbers with their units,
:attr:`Result.headline` first), ``_repr_html_`` a table of the whole summary. A kind states
the units of its summary entries that :func:`gyroshell.core.units.unit_of` does not know in
:attr:`Result.summary_units`.

Metadata attributes of every file: ``gyroshell_type`` (the kind), ``gyroshell_version``,
and JSON text ``parameters`` (the :class:`~gyroshell.TapeParameters` fields, when known),
``grid`` (the :class:`~gyroshell.Grid` fields) and ``info`` (the run's diagnostics).

Complex numbers: NetCDF has no complex type, so a complex variable ``z`` is stored as two
float64 variables ``z_real`` and ``z_imag`` with attributes ``complex_of = "z"`` and
``complex_part = "real"`` / ``"imag"``; any NetCDF reader (ncdump, netCDF4, MATLAB) sees two
ordinary real arrays. Tables go to CSV with floats in Python's shortest round-trip form and
NaN written as ``NaN`` (read back exactly), or to Parquet.

Files are written whole or not at all (a temporary file moved into place). xarray and a
NetCDF engine (h5netcdf, or netCDF4) are imported only when a NetCDF file is written or read:
``pip install "gyroshell[io]"``.
"""

from __future__ import annotations

import dataclasses
import html
import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from ..core.errors import InputFileError, ParameterError
from ..core.files import atomic_path, check_input
from ..core.units import unit_of
from ..core.version import __version__
from .layout import Layout, check_dataset, check_metadata, check_version, from_json

#: Suffixes of the formats :meth:`Result.save` writes.
NETCDF_SUFFIXES = (".nc", ".nc4", ".netcdf")
TABLE_SUFFIXES = (".csv", ".parquet")
#: The attribute naming a file's kind.
KIND_ATTRIBUTE = "gyroshell_type"
COMPLEX_CONVENTION = "complex z stored as z_real, z_imag (attributes complex_of, complex_part)"
#: Longest ``repr`` of a result, characters.
REPR_LIMIT = 1000
#: Numbers of a list that a repr or an HTML cell shows before it elides the middle.
SHOWN_ITEMS = 4
#: Longest text of one HTML cell, characters (nested entries shortened to it).
CELL_LIMIT = 120
#: Summary entries named ``<quantity><suffix>`` have the quantity's unit.
_UNIT_SUFFIXES = ("_min", "_max")


class Result:
    """Base of every result kind (see the module docstring for the protocol).

    Subclasses register with ``kind="name"`` in their class statement; :func:`read` finds
    them by that name.
    """

    #: The kind's name, stored as ``gyroshell_type`` in its files.
    kind: ClassVar[str] = ""
    #: What the kind's file holds (:class:`~gyroshell.results.layout.Layout`), checked by
    #: :func:`from_dataset` before ``from_xarray`` reads it; None: only the metadata.
    file_layout: ClassVar[Layout | None] = None
    #: SI units (ASCII, as in :data:`gyroshell.core.units.SI_UNITS`) of the summary entries
    #: that :func:`~gyroshell.core.units.unit_of` does not know.
    summary_units: ClassVar[dict[str, str]] = {}
    #: Summary entries a ``repr`` shows first (the rest follow while they fit).
    headline: ClassVar[tuple[str, ...]] = ()
    _kinds: ClassVar[dict[str, type[Result]]] = {}

    def __init_subclass__(cls, *, kind: str | None = None, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "__repr__" not in cls.__dict__:
            # set before @dataclass runs, so that it keeps this one (not every array)
            cls.__repr__ = Result.__repr__
        if kind is None:
            return
        known = Result._kinds.get(kind)
        if known is not None and known.__qualname__ != cls.__qualname__:
            raise TypeError(f"result kind {kind!r} is registered already by {known.__name__}")
        cls.kind = kind
        Result._kinds[kind] = cls

    def to_xarray(self, *, params=None):
        """The result as an :class:`xarray.Dataset` (named dimensions, units, metadata).

        ``params`` (a :class:`~gyroshell.TapeParameters`) is stored as metadata by kinds
        that do not carry their tape themselves."""
        raise NotImplementedError(f"{type(self).__name__}.to_xarray")

    @classmethod
    def from_xarray(cls, ds) -> Result:
        """The result stored in ``ds`` (a Dataset written by :meth:`to_xarray`)."""
        raise NotImplementedError(f"{cls.__name__}.from_xarray")

    def summary(self) -> dict:
        """The headline numbers as a dict of plain floats, ints and text (SI units)."""
        raise NotImplementedError(f"{type(self).__name__}.summary")

    def plot(self, ax=None):
        """Draw the result's usual figure on ``ax`` (a new figure if None); returns the Axes."""
        raise NotImplementedError(f"{type(self).__name__}.plot")

    def summary_unit(self, name: str) -> str | None:
        """The SI unit of the summary entry ``name`` (None: a count, text or no unit
        known): :attr:`summary_units`, else :func:`~gyroshell.core.units.unit_of` of the
        name or of the quantity it is the least or largest of (``velocity_max``)."""
        unit = self.summary_units.get(name) or unit_of(name)
        for suffix in _UNIT_SUFFIXES:
            if unit is None and name.endswith(suffix):
                unit = unit_of(name[: -len(suffix)])
        return unit

    def _summary_or_none(self) -> dict | None:
        try:
            return self.summary()
        except Exception:  # noqa: BLE001 - showing a result must never fail
            return None

    def __repr__(self) -> str:
        """One line of at most :data:`REPR_LIMIT` characters: the class and kind, then the
        summary's numbers with their units (:attr:`headline` first; lists of numbers
        shortened, nested entries left to :meth:`_repr_html_`)."""
        head = f"{type(self).__name__}(kind={self.kind!r}"
        summary = self._summary_or_none()
        if summary is None:
            return head + ")"
        names = [n for n in self.headline if n in summary]
        names += [n for n in summary if n not in names]
        parts = [f"{n}={text}" for n in names
                 if (text := _repr_value(summary[n], self.summary_unit(n))) is not None]
        out = head
        for k, part in enumerate(parts):
            rest = f", ... {len(parts) - k} more)"
            if len(out) + 2 + len(part) + len(rest) > REPR_LIMIT:
                return out + rest
            out += ", " + part
        return out + ")"

    def _repr_html_(self) -> str:
        """The summary as an HTML table: entry, value, SI unit (notebooks show it)."""
        caption = html.escape(f"{type(self).__name__} (kind {self.kind!r})")
        summary = self._summary_or_none()
        rows = "".join(
            f"<tr><th>{html.escape(str(name))}</th><td>{html.escape(_cell(value))}</td>"
            f"<td>{html.escape(self.summary_unit(name) or '')}</td></tr>"
            for name, value in (summary or {}).items())
        return (f"<table><caption>{caption}</caption><thead><tr><th>entry</th><th>value"
                f"</th><th>unit</th></tr></thead><tbody>{rows}</tbody></table>")

    def to_frame(self):
        """The result as a :class:`pandas.DataFrame` (kinds that are tables)."""
        raise ParameterError(f"a {type(self).__name__} is not a table: save it as .nc")

    @classmethod
    def is_table(cls) -> bool:
        """Whether the kind is a table: it defines :meth:`to_frame`, so :meth:`save` also
        writes it as CSV or Parquet (known before any result of the kind exists)."""
        return cls.to_frame is not Result.to_frame

    def save(self, path: str | os.PathLike[str], *, params=None) -> Path:
        """Write NetCDF (``.nc``), or CSV / Parquet (``.csv``, ``.parquet``) for tables.

        The file is written whole or not at all; :func:`gyroshell.load` reads a NetCDF file
        back as an equal object. ``params`` as in :meth:`to_xarray`. Returns the path.
        """
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix in NETCDF_SUFFIXES:
            write_netcdf(self.to_xarray(params=params), path)
        elif suffix in TABLE_SUFFIXES:
            write_table(self.to_frame(), path)
        else:
            raise ParameterError(f"unknown file type {path.suffix!r}: use one of "
                                 f"{', '.join(NETCDF_SUFFIXES + TABLE_SUFFIXES)}")
        return path


def _number(value) -> str:
    if isinstance(value, bool | np.bool_):
        return str(bool(value))
    if isinstance(value, int | np.integer):
        return str(int(value))
    return f"{float(value):.4g}"


def _numbers(values: list) -> str | None:
    """A list of numbers, its middle elided past :data:`SHOWN_ITEMS`; None otherwise."""
    if not all(isinstance(v, int | float | np.number) and not isinstance(v, bool)
               for v in values):
        return None
    if len(values) <= SHOWN_ITEMS:
        return "[" + ", ".join(map(_number, values)) + "]"
    return (f"[{', '.join(map(_number, values[:SHOWN_ITEMS - 1]))}, ..., "
            f"{_number(values[-1])}] ({len(values)} values)")


def _repr_value(value, unit: str | None) -> str | None:
    """An entry as a repr shows it (None: left out: None, nested lists and dicts)."""
    suffix = f" {unit}" if unit and unit != "1" else ""
    if value is None or isinstance(value, dict):
        return None
    if isinstance(value, str):
        return repr(value) if len(value) <= CELL_LIMIT else None
    if isinstance(value, list | tuple | np.ndarray):
        text = _numbers(list(value))
        if text is None and all(isinstance(v, str) for v in value):  # names (a table's)
            text = repr(list(value))
            return text if len(text) <= CELL_LIMIT else None
        return None if text is None else text + (suffix if len(value) else "")
    if isinstance(value, int | float | np.number | bool | np.bool_):
        return _number(value) + suffix
    return None


def _cell(value) -> str:
    """An entry as an HTML cell shows it: numbers to 6 digits, lists shortened, nested
    entries as JSON of at most :data:`CELL_LIMIT` characters."""
    if value is None:
        return ""
    if isinstance(value, float | np.floating):
        return f"{float(value):.6g}"
    if isinstance(value, int | np.number | bool | np.bool_):
        return _number(value)
    if isinstance(value, list | tuple | np.ndarray):
        text = _numbers(list(value))
        if text is not None:
            return text
    text = value if isinstance(value, str) else to_json(value)
    return text if len(text) <= CELL_LIMIT else text[:CELL_LIMIT - 3] + "..."


def kinds() -> dict[str, type[Result]]:
    """The registered result kinds, name -> class (those whose modules are imported)."""
    return dict(Result._kinds)


def _result_class(attrs: Mapping, source: str) -> type[Result]:
    kind = attrs.get(KIND_ATTRIBUTE)
    cls = Result._kinds.get(kind) if isinstance(kind, str) else None
    if cls is None:
        known = ", ".join(sorted(Result._kinds))
        raise InputFileError(f"{source} is not a gyroshell result file ({KIND_ATTRIBUTE} "
                             f"{kind!r}; known kinds: {known})")
    return cls


def from_dataset(ds, *, source: str = "the dataset"):
    """The object of the kind stored in ``ds.attrs['gyroshell_type']``.

    The metadata and the kind's :attr:`Result.file_layout` are checked first
    (:func:`gyroshell.results.layout.check_dataset`).

    Raises
    ------
    InputFileError
        Naming ``source`` and what is wrong: an unknown kind, a newer version, broken
        metadata, a missing variable, text where numbers belong, NaN, a value out of range,
        or what the kind refuses while rebuilding its object (a saved bearing model's
        speed, head or air out of range).
    """
    cls = _result_class(ds.attrs, source)
    check_dataset(ds, cls.file_layout, source)
    try:
        return cls.from_xarray(ds)
    except InputFileError:
        raise
    except ParameterError as exc:  # the stored settings rebuild no valid object
        raise InputFileError(f"{source}: {exc}") from None


def read(path: str | os.PathLike[str]):
    """The result stored in a NetCDF file, as the object of its kind (checked as in
    :func:`from_dataset`).

    The kind, version and metadata of a NetCDF-4 file are checked from its attributes
    alone (h5py) before any array is read, so a file whose grid claims 10⁷ intervals is
    refused without reading it."""
    source = os.fspath(check_input(path, what="NetCDF file"))
    attrs = _header(Path(source))
    if attrs is not None:
        _result_class(attrs, source)
        check_version(attrs, source)
        check_metadata(attrs, source)
    return from_dataset(open_netcdf(path), source=source)


def _header(path: Path) -> dict | None:
    """The global attributes of a NetCDF-4 (HDF5) file through h5py (None for another
    format or without h5py)."""
    if _engine_for(path) != "h5netcdf":
        return None
    import h5py

    try:
        with h5py.File(path, "r") as fh:
            return {name: _text(value) for name, value in fh.attrs.items()}
    except OSError as exc:
        raise InputFileError(f"{path}: cannot be read as NetCDF (truncated or damaged?): "
                             f"{_reason(exc)}") from None


def _text(value):
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.shape == ():
        return value.item()
    return value


# ----- files -------------------------------------------------------------------------------
def netcdf_engine() -> str:
    """The NetCDF engine xarray should use: h5netcdf, else netCDF4."""
    for name, module in (("h5netcdf", "h5netcdf"), ("netcdf4", "netCDF4")):
        try:
            __import__(module)
            return name
        except ImportError:
            continue
    raise ParameterError('NetCDF needs h5netcdf or netCDF4: pip install "gyroshell[io]"')


def write_netcdf(ds, path: str | os.PathLike[str]) -> Path:
    """Write a Dataset to ``path`` whole or not at all."""
    engine = netcdf_engine()
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine=engine)
    return Path(path)


#: The first bytes of the files NetCDF readers open: HDF5 (NetCDF-4), and classic NetCDF
#: (CDF-1, CDF-2, CDF-5), which xarray reads with scipy.
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
CLASSIC_SIGNATURES = (b"CDF\x01", b"CDF\x02", b"CDF\x05")


def _engine_for(path: Path) -> str:
    """The xarray engine for the file's format, from its first bytes (refused if neither)."""
    with open(path, "rb") as fh:
        head = fh.read(len(HDF5_SIGNATURE))
    if not head:
        raise InputFileError(f"{path}: empty file, not a NetCDF file")
    if head.startswith(HDF5_SIGNATURE):
        return netcdf_engine()
    if head.startswith(CLASSIC_SIGNATURES):
        return "scipy"
    raise InputFileError(f"{path}: not a NetCDF file (it starts with {head[:4]!r}, not the "
                         "NetCDF or HDF5 signature)")


def open_netcdf(path: str | os.PathLike[str]):
    """A NetCDF file's Dataset, loaded into memory and closed.

    Raises
    ------
    MissingFileError
        No such file (also a ``FileNotFoundError``).
    InputFileError
        A folder, an empty, truncated or damaged file, or one that is not NetCDF; the
        message names the file.
    """
    import xarray as xr

    path = check_input(path, what="NetCDF file")
    try:
        engine = _engine_for(path)
        with xr.open_dataset(path, engine=engine) as ds:
            return ds.load()
    except OSError as exc:  # h5py / netCDF4 / scipy on a truncated or damaged file
        raise InputFileError(f"{path}: cannot be read as NetCDF (truncated or damaged?): "
                             f"{_reason(exc)}") from None


def _reason(exc: OSError) -> str:
    text = str(exc.strerror or exc)
    return text if len(text) <= 160 else text[:157] + "..."


def write_table(frame, path: str | os.PathLike[str], *, option: str = "output") -> Path:
    """Write a DataFrame as CSV (exact floats, ``NaN`` for missing) or, for a ``.parquet``
    path, Parquet, whole or not at all: the one table writer, so that every table reads back
    through :func:`gyroshell.load` with its missing values as NaN. ``option`` names the
    path in an error message (e.g. ``--out``)."""
    path = Path(path)
    with atomic_path(path, option=option) as tmp:
        if path.suffix.lower() == ".parquet":
            frame.to_parquet(tmp, index=False)
        else:
            frame.to_csv(tmp, index=False, na_rep="NaN")
    return path


# ----- JSON metadata -----------------------------------------------------------------------
def _encode(value: Any) -> Any:
    if isinstance(value, complex | np.complexfloating):
        return {"__complex__": [float(value.real), float(value.imag)]}
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.ndarray):
        return [_encode(v) for v in value.tolist()]
    if isinstance(value, tuple):
        return [_encode(v) for v in value]
    return str(value)


def to_json(value: Any) -> str:
    """JSON text of metadata; complex numbers and numpy scalars survive."""
    return json.dumps(value, default=_encode, allow_nan=True)


def params_json(params) -> str:
    """JSON of a :class:`~gyroshell.TapeParameters` (``null`` for None)."""
    if params is None:
        return "null"
    from ..tape.config import parameter_fields

    return to_json(parameter_fields(params))


def params_from(attrs: dict):
    """The :class:`~gyroshell.TapeParameters` stored in a file's attributes, or None."""
    from ..tape.parameters import TapeParameters

    data = from_json(attrs.get("parameters", "null"))
    return None if data is None else TapeParameters(**data)


def grid_from(attrs: dict):
    """The :class:`~gyroshell.Grid` stored in a file's attributes, or None."""
    from ..tape.grid import Grid

    data = from_json(attrs.get("grid", "null"))
    return None if data is None else Grid(**data)


# ----- datasets ----------------------------------------------------------------------------
def put(data_vars: dict, name: str, dims, values, attrs: dict | None = None) -> None:
    """Add a variable to ``data_vars``; a complex one becomes ``name_real`` and ``name_imag``."""
    values = np.asarray(values)
    attrs = dict(attrs or {})
    if np.iscomplexobj(values):
        for part, array in (("real", values.real), ("imag", values.imag)):
            data_vars[f"{name}_{part}"] = (dims, np.ascontiguousarray(array),
                                           {**attrs, "complex_of": name, "complex_part": part})
    else:
        data_vars[name] = (dims, values, attrs)


def get(ds, name: str) -> np.ndarray:
    """A variable written by :func:`put`, complex again if it was complex."""
    if name in ds.variables:
        return ds[name].values
    return ds[f"{name}_real"].values + 1j * ds[f"{name}_imag"].values


def dataset(data_vars: dict, coords: dict, kind: str, *, params=None, grid=None,
            info: dict | None = None, **extra_attrs):
    """A Dataset with the metadata attributes every file carries (see the module docstring);
    ``extra_attrs`` that are not text are stored as JSON."""
    import xarray as xr

    attrs = {KIND_ATTRIBUTE: kind, "gyroshell_version": __version__,
             "parameters": params_json(params),
             "grid": to_json(None if grid is None else dataclasses.asdict(grid)),
             "info": to_json(info or {}), "complex_convention": COMPLEX_CONVENTION}
    attrs.update({k: (to_json(v) if not isinstance(v, str) else v)
                  for k, v in extra_attrs.items()})
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def xy_coords(grid) -> dict:
    """The node coordinates of a :class:`~gyroshell.Grid` as Dataset coordinates (m)."""
    return {"x": ("x", grid.x, {"units": "m", "long_name": "along the tape"}),
            "y": ("y", grid.y, {"units": "m", "long_name": "across the tape"})}


def table_dataset(frame, kind: str, *, params=None, **attrs):
    """A table as a Dataset on dimension ``row``, its columns' SI units as attributes."""
    import xarray as xr

    frame = frame.reset_index(drop=True)
    ds = xr.Dataset.from_dataframe(frame.rename_axis("row"))
    for name in ds.variables:
        unit = unit_of(str(name))
        if unit:
            ds[name].attrs["units"] = unit
    base = dataset({}, {}, kind, params=params, columns=list(frame.columns), **attrs)
    ds.attrs.update(base.attrs)
    return ds


def table_from(ds):
    """The DataFrame stored by :func:`table_dataset`, its columns in their order."""
    columns = from_json(ds.attrs["columns"])
    return ds.to_dataframe().reset_index(drop=True)[columns]


def metadata(path_or_dataset) -> dict:
    """``gyroshell_type``, ``gyroshell_version``, ``parameters`` (TapeParameters or None),
    ``grid`` (Grid or None) and ``info`` of a saved NetCDF file or a Dataset."""
    ds = path_or_dataset
    attrs = dict(ds.attrs) if hasattr(ds, "attrs") else dict(open_netcdf(ds).attrs)
    return {KIND_ATTRIBUTE: attrs.get(KIND_ATTRIBUTE),
            "gyroshell_version": attrs.get("gyroshell_version"),
            "parameters": params_from(attrs), "grid": grid_from(attrs),
            "info": from_json(attrs.get("info", "{}"))}
