"""Every kind of saved result, and :func:`load` / :func:`save` over all of them.

This module stands above the layers: it imports each module that defines a result kind, so
that the registry of :mod:`gyroshell.results.base` knows every kind before a file is read.
The base never names a kind; this list does, and a test checks that it names them all.
"""

from __future__ import annotations

import os
from importlib import import_module
from pathlib import Path

from .core.errors import ParameterError
from .core.files import read_csv_exact
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
    """
    import_kinds()
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in base.TABLE_SUFFIXES:
        if not path.is_file():
            raise FileNotFoundError(f"no such file: {path}")
        if suffix == ".parquet":
            import pandas as pd

            return pd.read_parquet(path)
        return read_csv_exact(path, keep_default_na=False, na_values=["NaN"])
    result = base.read(path)
    table = base.kinds().get("table")
    return result.frame if table is not None and isinstance(result, table) else result


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
