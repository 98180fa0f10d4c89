"""Every kind of saved result, and :func:`load` / :func:`save` over all of them.

This module stands above the layers: it imports each module that defines a result kind, so
that the registry of :mod:`gyroshell.results.base` knows every kind before a file is read.
The base never names a kind; this list does, and a test checks that it names them all.
"""

from __future__ import annotations

import os
from importlib import import_module
from pathlib import Path

from .results import base, storage

#: The modules that define result kinds (each registers its kinds when imported).
KIND_MODULES: tuple[str, ...] = ()


def import_kinds() -> None:
    """Import every module of :data:`KIND_MODULES` (each registers its kinds)."""
    for name in KIND_MODULES:
        import_module(name)


def load(path: str | os.PathLike[str]):
    """Read a result written by ``save``: the same kind of object, equal to the original.

    A ``.csv`` or ``.parquet`` file gives a pandas DataFrame; a NetCDF file gives the
    object named by its ``gyroshell_type`` attribute (a DataFrame for ``table``).
    """
    import_kinds()
    return storage.load(path)


def save(result, path: str | os.PathLike[str], *, params=None) -> Path:
    """Write a result (or a pandas DataFrame) to ``path``: NetCDF (``.nc``) for any result,
    CSV or Parquet for tables; whole or not at all. Returns the path."""
    if isinstance(result, base.Result):
        return result.save(path, params=params)
    return storage.save(result, path, params=params)
