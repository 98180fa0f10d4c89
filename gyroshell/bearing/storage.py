"""Saving and loading steady bearing states: thin wrappers over the result protocol.

A :class:`~gyroshell.bearing.results.BearingSolution` is a result kind (``"bearing"``):
``sol.save(path)`` writes it, :func:`gyroshell.results.base.read` reads it back (see
:mod:`gyroshell.bearing.results` for the file's contents). These functions keep the
module's previous calls working: a steady state goes to NetCDF only, and :func:`load`
refuses files of other kinds. Needs the ``io`` extra (xarray, h5netcdf).
"""

from __future__ import annotations

import os
from pathlib import Path

from ..core.errors import ParameterError
from ..results.base import NETCDF_SUFFIXES, from_dataset, open_netcdf
from .results import BearingSolution

KIND = BearingSolution.kind


def to_xarray(sol: BearingSolution):
    """The steady state as an :class:`xarray.Dataset` (:meth:`BearingSolution.to_xarray`)."""
    return sol.to_xarray()


def save(sol: BearingSolution, path: str | os.PathLike[str]) -> Path:
    """Write ``sol`` to a NetCDF file (``.nc``), whole or not at all. Returns the path."""
    path = Path(path)
    if path.suffix.lower() not in NETCDF_SUFFIXES:
        raise ParameterError(f"a bearing state is saved as NetCDF "
                             f"({', '.join(NETCDF_SUFFIXES)}), got {path.name!r}")
    return sol.save(path)


def load(path: str | os.PathLike[str]) -> BearingSolution:
    """Read a state written by :func:`save`: the model is rebuilt from the stored
    settings and the unknowns taken from the stored fields."""
    ds = open_netcdf(path)
    kind = ds.attrs.get("gyroshell_type")
    if kind != KIND:
        raise ParameterError(f"{path} is not a saved bearing state (gyroshell_type "
                             f"{kind!r})")
    try:
        return from_dataset(ds, source=str(path))
    except ParameterError as exc:   # each message names the file once
        if str(exc).startswith(str(path)):
            raise
        raise ParameterError(f"{path}: {exc}") from None
