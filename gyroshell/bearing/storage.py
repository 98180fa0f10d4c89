"""Saving and loading steady bearing states through :mod:`gyroshell.persistence`.

A :class:`~gyroshell.bearing.steady.BearingSolution` becomes an xarray Dataset with the
spacing, departure u, pressure and contact-force fields on the (x, y) nodes (their
coordinates, uniform or graded, as the dataset's coordinates), the scalar outputs of
:meth:`~gyroshell.bearing.steady.BearingSolution.summary` and everything needed to rebuild
the model (tape parameters, air, speed, wrap, span, grid counts and grading), so that
:func:`load` returns a solution equal to the saved one; it checks that the rebuilt grid's
nodes are the stored coordinates. Needs the ``io`` extra (xarray, h5netcdf).
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import numpy as np

from ..core.errors import ParameterError
from ..results import storage
from .air import AirParameters
from .mesh import Grading
from .model import BearingModel
from .steady import BearingSolution, NewtonInfo

KIND = "bearing"


def to_xarray(sol: BearingSolution):
    """The steady state as an :class:`xarray.Dataset`: ``spacing`` and ``departure``
    (m), ``pressure`` (Pa) and ``contact`` (N, N/m if infinitely wide) on dimensions
    (x, y), x from the middle of the wrap (m); the summary, air and model settings as
    attributes."""
    m = sol.model
    y = np.zeros(1) if m.infinitely_wide else m.y
    def nodal(values):                 # tape unknowns -> every node (0 at the span ends)
        out = np.zeros((m.nx + 1, m.nc))
        out[1:-1, :] = values.reshape(m.nx - 1, m.nc)
        return out
    coords = {"x": ("x", sol.x, {"units": "m", "long_name": "from the middle of the wrap"}),
              "y": ("y", y, {"units": "m", "long_name": "across the tape"})}
    data = {"spacing": (("x", "y"), sol.spacing, {"units": "m"}),
            "pressure": (("x", "y"), sol.pressure, {"units": "Pa"}),
            "departure": (("x", "y"), nodal(sol.u),
                          {"units": "m", "long_name": "from the dry wrapped configuration"}),
            "contact": (("x", "y"), nodal(sol.contact), {"units": "N"})}
    summary = {k: v for k, v in sol.summary().items() if k != "newton_step_norms"}
    model = {"velocity": m.velocity, "wrap_angle": m.wrap_angle,
             "infinitely_wide": m.infinitely_wide, "span": m.span, "nx": m.nx, "ny": m.ny,
             "grading": m.grading.as_dict()}
    return storage._dataset(
        data, coords, KIND, params=m.params, info=dataclasses.asdict(sol.info),
        air=dataclasses.asdict(m.air), model=model, summary=summary)


def save(sol: BearingSolution, path: str | os.PathLike[str]) -> Path:
    """Write ``sol`` to a NetCDF file (``.nc``), whole or not at all. Returns the path."""
    from ..core.files import atomic_path

    path = Path(path)
    if path.suffix.lower() not in storage.NETCDF_SUFFIXES:
        raise ParameterError(f"a bearing state is saved as NetCDF "
                             f"({', '.join(storage.NETCDF_SUFFIXES)}), got {path.name!r}")
    ds = to_xarray(sol)
    engine = storage._engine()
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine=engine)
    return path


def load(path: str | os.PathLike[str]) -> BearingSolution:
    """Read a state written by :func:`save`: the model is rebuilt from the stored
    settings and the unknowns taken from the stored fields."""
    import xarray as xr

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    with xr.open_dataset(path, engine=storage._engine()) as ds:
        ds = ds.load()
    if ds.attrs.get("gyroshell_type") != KIND:
        raise ParameterError(f"{path} is not a saved bearing state (gyroshell_type "
                             f"{ds.attrs.get('gyroshell_type')!r})")
    a = ds.attrs
    settings = storage.from_json(a["model"])
    # files written before graded grids: uniform
    settings["grading"] = Grading(**settings.get("grading", {}))
    model = BearingModel(storage._params_from(a),
                         AirParameters(**storage.from_json(a["air"])), **settings)
    stored_y = ds["y"].values
    if not (np.allclose(ds["x"].values, model.x - 0.5 * model.length, rtol=0,
                        atol=1e-12 * model.length)
            and (model.infinitely_wide or np.allclose(stored_y, model.y, rtol=0,
                                                      atol=1e-12 * model.params.width))):
        raise ParameterError(f"{path}: the stored node coordinates do not match the grid "
                             "rebuilt from its settings")
    U, P, C = (ds[k].values for k in ("departure", "pressure", "contact"))
    info = NewtonInfo(**storage.from_json(a["info"]))
    return BearingSolution(model, U[1:-1, :].ravel(), P[model.film.interior],
                           C[1:-1, :].ravel(), info)
