"""Every kind of saved result, and :func:`load` / :func:`save` over all of them.

This module stands above the layers: it imports each module that defines a result kind, so
that the registry of :mod:`gyroshell.results.base` knows every kind before a file is read.
The base never names a kind; this list does, and a test checks that it names them all.
What each kind's file holds is declared once, on its class (``file_layout``).
"""

from __future__ import annotations

import os
from importlib import import_module
from pathlib import Path

from .core.errors import InputFileError, ParameterError
from .core.files import check_input, read_csv_exact
from .results import base

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
    result = base.read(path)
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
