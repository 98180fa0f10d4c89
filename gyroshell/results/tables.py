"""A table (a speed sweep, or any :class:`pandas.DataFrame`) as the saved kind ``"table"``.

File layout (unchanged from the previous release): one variable per column on dimension
``row``, the columns' SI units as ``units`` attributes and their order as the JSON
attribute ``columns``.

For compatibility with the code of the previous release, :func:`gyroshell.load` gives a
``"table"`` file back as the plain :class:`pandas.DataFrame` (``Table.from_xarray`` gives the
:class:`Table`, whose ``frame`` it is), columns in their saved order.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..core.errors import ParameterError
from ..plot import study_lines
from ..tape.parameters import TapeParameters
from .base import Result, params_from, table_dataset, table_from
from .layout import Layout, table_columns

if TYPE_CHECKING:
    import pandas as pd


@dataclass(frozen=True, eq=False)
class Table(Result, kind="table"):
    """A DataFrame on the result protocol.

    Attributes
    ----------
    frame : pandas.DataFrame
        The table; columns are named quantities in SI units (see :mod:`gyroshell.core.units`).
    params : TapeParameters or None
        The tape the table was computed for, saved as metadata.
    """

    frame: pd.DataFrame
    params: TapeParameters | None = None

    file_layout = Layout(check=table_columns)

    def to_frame(self):
        """The wrapped DataFrame."""
        return self.frame

    def to_xarray(self, *, params=None):
        """Dataset on dimension ``row``, one variable per column; ``params`` overrides the
        tape carried by the table."""
        return table_dataset(self.frame, self.kind,
                             params=self.params if params is None else params)

    @classmethod
    def from_xarray(cls, ds) -> Table:
        """The stored table, columns in their saved order, with its tape if one was saved."""
        return cls(table_from(ds), params_from(ds.attrs))

    def summary(self) -> dict:
        """The number of rows and the column names."""
        return {"rows": int(len(self.frame)), "columns": [str(c) for c in self.frame.columns]}

    def plot(self, ax=None):
        """The second numeric column against the first (:func:`gyroshell.plot.study_lines`);
        returns the Axes."""
        numeric = [c for c in self.frame.columns if self.frame[c].dtype.kind in "fiu"]
        if len(numeric) < 2:
            raise ParameterError("plotting a table needs two numeric columns")
        return study_lines(self.frame, x=numeric[0], quantity=numeric[1], ax=ax)
