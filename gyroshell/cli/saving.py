"""``--save FILE.nc``: the one option every result-producing sub-command shares."""

from __future__ import annotations

import argparse
from pathlib import Path


def add_save_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--save", metavar="FILE.nc", default=None,
                        help="save the result with its parameters, grid and version "
                             "(NetCDF; read it back with gyroshell.load)")


def check_save_path(path: str | None, kind: type | None = None) -> None:
    """Fail before computing if the result could never be written there: a suffix that is
    not NetCDF (nor CSV / Parquet for a table), a table format for a ``kind`` (a
    :class:`~gyroshell.results.base.Result` subclass) that is no table
    (:meth:`~gyroshell.results.base.Result.is_table`), an unwritable path. ``kind`` None:
    a table."""
    if path is None:
        return
    from ..core.files import check_output
    from ..results.base import NETCDF_SUFFIXES, TABLE_SUFFIXES
    from .common import UserError

    suffix = Path(path).suffix.lower()
    if suffix not in NETCDF_SUFFIXES + TABLE_SUFFIXES:
        raise UserError(f"--save: use a .nc file (or .csv/.parquet for tables), got {path}")
    if suffix in TABLE_SUFFIXES and kind is not None and not kind.is_table():
        raise UserError(f"--save: a {kind.__name__} is not a table: use a .nc file, got "
                        f"{path}")
    check_output(path, option="--save")


def save_result(path: str | None, result, params) -> None:
    """Write ``result`` to ``path`` (if given) with ``params`` as metadata
    (:func:`gyroshell.save`: a result of any kind, or a table)."""
    if path is not None:
        from ..kinds import save

        save(result, path, params=params)
