"""Every kind of saved result, and :func:`load` / :func:`save` over all of them.

This module stands above the layers: it imports each module that defines a result kind, so
that the registry of :mod:`gyroshell.results.base` knows every kind before a file is read.
The base never names a kind; this list does, and a test checks that it names them all.
"""

from __future__ import annotations

import dataclasses
import os
from importlib import import_module
from pathlib import Path

import numpy as np

from .core.errors import InputFileError, ParameterError
from .core.files import check_input, read_csv_exact
from .results import base, layout
from .results.layout import Layout

#: The modules that define result kinds (each registers its kinds when imported).
KIND_MODULES: tuple[str, ...] = (
    "gyroshell.results.static",
    "gyroshell.results.transient",
    "gyroshell.results.modes",
    "gyroshell.results.critical",
    "gyroshell.results.frequency_response",
    "gyroshell.results.tables",
    "gyroshell.engines.frequency_response",
    "gyroshell.studies.sweep",
    "gyroshell.studies.campbell",
    "gyroshell.studies.parameter_study",
    "gyroshell.bearing.results",
)


def _keys_of(name: str, cls: type, value) -> None:
    """A JSON object whose keys are fields of dataclass ``cls``, with every field that has
    no default (what ``cls(**value)`` needs to be called at all)."""
    if not isinstance(value, dict):
        raise ParameterError(f"{name} must be a JSON object, got {value!r}")
    fields = dataclasses.fields(cls)
    unknown = sorted(set(value) - {f.name for f in fields})
    if unknown:
        raise ParameterError(f"{name}: unknown field(s) {', '.join(unknown)}")
    missing = [f.name for f in fields if f.name not in value
               and f.default is dataclasses.MISSING
               and f.default_factory is dataclasses.MISSING]
    if missing:
        raise ParameterError(f"{name}: missing field(s) {', '.join(missing)}")


def _bearing_attrs(ds) -> None:
    """The bearing's JSON attributes, their keys those its classes accept."""
    from .bearing.air import AirParameters
    from .bearing.mesh import Grading
    from .bearing.results import NewtonInfo

    attrs = {name: base.from_json(ds.attrs[name]) for name in ("air", "model", "info")}
    _keys_of("attribute air", AirParameters, attrs["air"])
    _keys_of("attribute info", NewtonInfo, attrs["info"])
    model = attrs["model"]
    settings = ("velocity", "wrap_angle", "infinitely_wide", "span", "nx", "ny", "grading",
                "head", "dry")
    if not isinstance(model, dict) or set(model) - set(settings):
        raise ParameterError(f"attribute model must be a JSON object of {', '.join(settings)}")
    if "grading" in model:
        _keys_of("attribute model: grading", Grading, model["grading"])


def _layouts() -> dict[str, Layout]:
    """The file layouts of the kinds whose modules declare none (checked on load)."""
    obj = layout.Attr(layout.of_type("value", dict, "a JSON object"))
    number = layout.Attr(layout.of_type("value", (int, float), "a number"))
    bearing_state = {name: layout.Variable(("x", "y")) for name in
                     ("spacing", "pressure", "departure", "contact")}
    coords = {"x": layout.X, "y": layout.Variable(("y",))}
    series = {name: layout.Variable(("t",)) for name in
              ("tension", "central_spacing", "minimum_spacing", "contact_force",
               "newton_iterations")}
    poles = {f"{p}_{what}": layout.Variable(dims, "complex") for p in ("full", "nested")
             for what, dims in (("poles", (f"{p}_pole",)),
                                ("residues", ("point", f"{p}_pole")))}
    return {
        "sweep": Layout({"velocities": layout.Variable(("speed",), check=layout.speed())},
                        {"count": layout.Attr(layout.count("count", 1)),
                         "min_correlation": number,
                         "continuation": layout.Attr(layout.of_type(
                             "continuation", bool, "true or false")),
                         "info": layout.INFO}, check=_sweep_table),
        "campbell": Layout(attrs={"tables": obj, "info": layout.INFO,
                                  "critical_speed": layout.Attr(layout.of_type(
                                      "critical_speed", (int, float, type(None)),
                                      "a speed in m/s or null"))}, check=_campbell_tables),
        "study": Layout(attrs={"velocity": number, "count": layout.Attr(layout.count(
                            "count", 1)),
                               "varied": layout.Attr(layout.of_type("varied", list, "a list")),
                               "compute": layout.Attr(layout.of_type("compute", list,
                                                                     "a list"))},
                        check=_study_table),
        "reduced_model": Layout({**poles, "velocity": layout.Variable((), check=layout.speed()),
                                 "points": layout.Variable(("point", "axis")),
                                 "interpolation_points": layout.Variable(
                                     ("interpolation_point",),
                                     check=layout.nonnegative("interpolation_points"))},
                                {"moments": layout.Attr(layout.count("moments", 2)),
                                 "basis_size": layout.Attr(layout.count("basis_size", 0)),
                                 "info": layout.INFO}),
        "bearing": Layout({**bearing_state, **coords}, {"air": obj, "model": obj,
                                                        "info": layout.INFO},
                          check=_bearing_attrs),
        "bearing_transient": Layout(
            {**{f"final_{k}": v for k, v in bearing_state.items()}, **coords, **series,
             "t": layout.Variable(("t",), check=layout.monotonic("t")),
             "centreline": layout.Variable(("t", "x")),
             "x_record": layout.Variable(("x",))},
            {"air": obj, "model": obj, "info": layout.INFO}, check=_bearing_attrs),
    }


def _sweep_table(ds) -> None:
    """A sweep's table: its columns stored, its speeds those of ``velocities``, and at most
    ``count`` modes at each speed, ``count`` at one at least (a solve returns ``count``
    modes; fewer only where a tiny model has no more)."""
    layout.table_columns(ds)
    if "velocity" not in ds.variables:
        raise ParameterError("column velocity is missing")
    count = int(ds.attrs["count"])
    rows = ds["velocity"].values
    speeds = np.asarray(ds["velocities"].values).ravel()
    stray = np.setdiff1d(rows, speeds)
    if stray.size:
        raise ParameterError(f"the table has rows at {stray[0]:g} m/s, not one of the "
                             "stored velocities")
    per_speed = np.array([np.count_nonzero(rows == v) for v in np.unique(speeds)])
    if per_speed.size and (per_speed.max() > count or per_speed.max() < count
                           or per_speed.min() == 0):
        raise ParameterError(f"count is {count} but the table holds {per_speed.min()} to "
                             f"{per_speed.max()} modes per speed")


def _study_table(ds) -> None:
    """A study's table: its columns stored, among them every varied name."""
    layout.table_columns(ds)
    columns = base.from_json(ds.attrs["columns"])
    varied = base.from_json(ds.attrs.get("varied", "[]"))
    missing = [name for name in varied if name not in columns] if isinstance(
        varied, list) else []
    if missing:
        raise ParameterError(f"varied lists {', '.join(map(str, missing))}, which the table "
                             "has no column for")


def _campbell_tables(ds) -> None:
    """The diagram's ``tables`` attribute: each table's columns stored on its dimension."""
    tables = base.from_json(ds.attrs["tables"])
    stored = {"frame": ("", "row"), "crossings": ("crossing_", "crossing"),
              "veerings": ("veering_", "veering")}
    if set(tables) != set(stored) or not all(isinstance(t, dict) for t in tables.values()):
        raise ParameterError(f"attribute tables must map {', '.join(stored)} to their columns")
    for name, columns in tables.items():
        prefix, dim = stored[name]
        for column in columns:
            variable = prefix + column
            if variable not in ds.variables or tuple(ds[variable].dims) != (dim,):
                raise ParameterError(f"column {column} of the {name} table is missing "
                                     f"(variable {variable} on {dim})")


#: kind -> its file layout, for the kinds whose classes declare no ``file_layout``.
FILE_LAYOUTS: dict[str, Layout] = _layouts()


def import_kinds() -> None:
    """Import every module of :data:`KIND_MODULES` (each registers its kinds)."""
    for name in KIND_MODULES:
        import_module(name)


def load(path: str | os.PathLike[str]):
    """Read a saved result: the object of the kind the file stores, equal to the original.

    Parameters
    ----------
    path : path
        A NetCDF file written by a result's ``save`` (or :func:`save`): the object of its
        ``gyroshell_type`` (a :class:`pandas.DataFrame` for a ``table``, as the previous
        release gave); or a ``.csv`` / ``.parquet`` table: a DataFrame, floats exact.

    Raises
    ------
    MissingFileError
        No such file (also a ``FileNotFoundError``).
    InputFileError
        A folder; an empty, truncated or non-NetCDF file; an unknown kind or a newer
        version; metadata with an unknown, missing or null field or a value out of range
        (parameters are validated by TapeParameters, as when typed); a missing variable,
        text where numbers belong, NaN where it has no meaning, arrays whose sizes do not
        match the stored grid; an empty or unreadable table. The message names the file.
    """
    import_kinds()
    suffix = Path(os.fspath(path)).suffix.lower() if isinstance(path, (str, os.PathLike)) \
        else ""
    if suffix in base.TABLE_SUFFIXES:
        return load_table(path)
    result = base.read(path, layouts=FILE_LAYOUTS)
    table = base.kinds().get("table")
    return result.frame if table is not None and isinstance(result, table) else result


def load_table(path: str | os.PathLike[str]):
    """A ``.csv`` (floats exact, ``NaN`` for missing) or ``.parquet`` table as a DataFrame.

    Raises
    ------
    InputFileError
        Naming the file: a folder, an empty file, not UTF-8 text, not a table.
    """
    what = "Parquet file" if Path(os.fspath(path)).suffix.lower() == ".parquet" else "CSV file"
    checked = check_input(path, what=what)
    if checked.stat().st_size == 0:
        raise InputFileError(f"{checked}: empty file, not a {what[:-5]} table")
    if what == "Parquet file":
        return _read_parquet(checked)
    import pandas as pd

    try:
        return read_csv_exact(checked, keep_default_na=False, na_values=["NaN"],
                              encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise InputFileError(f"{checked}: not UTF-8 text (byte at offset {exc.start}): not "
                             "a CSV table") from None
    except pd.errors.EmptyDataError:
        raise InputFileError(f"{checked}: no columns: an empty CSV table") from None
    except pd.errors.ParserError as exc:
        raise InputFileError(f"{checked}: not a CSV table: {str(exc).strip()}") from None


def _read_parquet(path: Path):
    import pandas as pd
    import pyarrow

    try:
        return pd.read_parquet(path)
    except pyarrow.ArrowException as exc:
        raise InputFileError(f"{path}: not a Parquet table: {exc}") from None


def save(result, path: str | os.PathLike[str], *, params=None) -> Path:
    """Write a result, or a :class:`pandas.DataFrame`, to ``path``: NetCDF (``.nc``) for
    any result, CSV or Parquet for tables; whole or not at all. Returns the path.

    ``params`` (a :class:`~gyroshell.TapeParameters`) is stored with results that do not
    carry their tape."""
    import pandas as pd

    if isinstance(result, pd.DataFrame):
        import_kinds()
        result = base.kinds()["table"](result)
    if not isinstance(result, base.Result):
        raise ParameterError(f"cannot save a {type(result).__name__}: not a gyroshell result")
    return result.save(path, params=params)
