"""A table (a speed sweep, or any :class:`pandas.DataFrame`) as the saved kind ``"table"``.

File layout (unchanged from the previous release): one variable per column on dimension
``row``, the columns' SI units as ``units`` attributes and their order as the JSON
attribute ``columns``.

For compatibility with the files and code of the previous release, reading a ``"table"``
file gives back the plain :class:`pandas.DataFrame` (``Table.from_xarray`` returns a
DataFrame, not a :class:`Table`), columns in their saved order; wrap it in :class:`Table`
for the result protocol.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..core.errors import ParameterError
from ..plot import study_lines
from ..tape.parameters import TapeParameters
from .base import Result, table_dataset, table_from

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

    def to_frame(self):
        """The wrapped DataFrame."""
        return self.frame

    def to_xarray(self, *, params=None):
        """Dataset on dimension ``row``, one variable per column; ``params`` overrides the
        tape carried by the table."""
        return table_dataset(self.frame, self.kind,
                             params=self.params if params is None else params)

    @classmethod
    def from_xarray(cls, ds):
        """The stored table as a :class:`pandas.DataFrame` (not a Table: see the module
        docstring), columns in their saved order."""
        return table_from(ds)

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
