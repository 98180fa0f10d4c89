"""``--save FILE.nc``: the one option every result-producing sub-command shares."""

from __future__ import annotations

import argparse
from pathlib import Path


def add_save_option(parser: argparse.ArgumentParser, *, what: str = "the result") -> None:
    parser.add_argument("--save", metavar="FILE.nc", default=None,
                        help=f"save {what} with its parameters, grid and version "
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


#: The --plot files' formats and their resolution, dots per inch.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")
PLOT_DPI = 120


def add_plot_option(parser: argparse.ArgumentParser, what: str) -> None:
    """``--plot FILE.png``: the result's figure (``what`` it shows, for the help)."""
    parser.add_argument("--plot", metavar="FILE.png", default=None,
                        help=f"write a figure of {what} (PNG, or PDF, SVG)")


def check_plot_path(path: str | None) -> None:
    """Fail before computing if the figure could never be written there."""
    if path is None:
        return
    from ..core.files import PLOT, check_output
    from .common import UserError

    if Path(path).suffix.lower() not in PLOT_SUFFIXES:
        raise UserError(f"--plot: use a {' or '.join(PLOT_SUFFIXES)} file, got {path}")
    check_output(path, option="--plot", kind=PLOT)


def write_plot(path: str | None, result) -> None:
    """The figure of ``result.plot()`` into ``path`` (if given), whole or not at all."""
    if path is None:
        return
    from ..plot import save_figure

    ax = result.plot()
    save_figure(ax.figure, path, dpi=PLOT_DPI, option="--plot")
