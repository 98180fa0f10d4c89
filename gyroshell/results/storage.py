"""Saved results: one module that every result goes through.

Every result (static deflection, transient run, modes, critical speeds, a sweep table, a
parameter study) becomes an :class:`xarray.Dataset` with named dimensions (``x``, ``y`` in m,
``t`` in s, ``mode``, ``row``), SI units as ``units`` attributes, and metadata attributes:

``gyroshell_type``
    What the file holds (``static``, ``transient``, ``modes``, ``critical``, ``table``,
    ``study``); :func:`load` rebuilds that object from it.
``gyroshell_version``
    The package version that wrote it.
``parameters``, ``grid``, ``info``
    JSON text: the :class:`~gyroshell.parameters.TapeParameters` fields (when known), the
    :class:`~gyroshell.grid.Grid` fields, and the result's diagnostics.

Complex numbers. NetCDF has no complex type, so a complex variable ``z`` is stored as two
float64 variables ``z_real`` and ``z_imag`` with attributes ``complex_of = "z"`` and
``complex_part = "real"`` / ``"imag"``; :func:`load` joins them again. Any NetCDF reader
(ncdump, netCDF4, MATLAB) sees two ordinary real arrays.

Tables (sweeps, studies) also go to CSV (floats in Python's shortest round-trip form, NaN
written as ``NaN`` so that empty text stays empty text; read back exactly) or Parquet
(``.parquet``, needs pyarrow).

Files are written whole or not at all (a temporary file moved into place). xarray and a
NetCDF engine (h5netcdf, or netCDF4) are imported only when a NetCDF file is written or read:
``pip install "gyroshell[io]"``.
"""

from __future__ import annotations

import dataclasses
import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..core.errors import ParameterError

#: Suffixes of the formats :func:`save` writes.
NETCDF_SUFFIXES = (".nc", ".nc4", ".netcdf")
TABLE_SUFFIXES = (".csv", ".parquet")



# ----- JSON for metadata ------------------------------------------------------------------
def _encode(value: Any) -> Any:
    if isinstance(value, complex | np.complexfloating):
        return {"__complex__": [float(value.real), float(value.imag)]}
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.ndarray):
        return [_encode(v) for v in value.tolist()]
    if isinstance(value, tuple):
        return [_encode(v) for v in value]
    return str(value)


def _decode(obj: dict) -> Any:
    if set(obj) == {"__complex__"}:
        re, im = obj["__complex__"]
        return complex(re, im)
    return obj


def to_json(value: Any) -> str:
    """JSON text of a dict of metadata; complex numbers and numpy scalars survive."""
    return json.dumps(value, default=_encode, allow_nan=True)


def from_json(text: str) -> Any:
    return json.loads(text, object_hook=_decode)


def _params_json(params) -> str:
    if params is None:
        return "null"
    return to_json({f.name: getattr(params, f.name) for f in dataclasses.fields(params)})


def _params_from(attrs: dict):
    from ..tape.parameters import TapeParameters

    data = from_json(attrs.get("parameters", "null"))
    return None if data is None else TapeParameters(**data)


def _grid_json(grid) -> str:
    return to_json(None if grid is None else dataclasses.asdict(grid))


def _grid_from(attrs: dict):
    from ..tape.grid import Grid

    data = from_json(attrs.get("grid", "null"))
    return None if data is None else Grid(**data)


def _version() -> str:
    from ..core.version import __version__

    return __version__


# ----- complex <-> real pairs -------------------------------------------------------------
def _put(data_vars: dict, name: str, dims, values, attrs: dict | None = None) -> None:
    """Add a variable; a complex one becomes ``name_real`` and ``name_imag``."""
    values = np.asarray(values)
    attrs = dict(attrs or {})
    if np.iscomplexobj(values):
        for part, array in (("real", values.real), ("imag", values.imag)):
            data_vars[f"{name}_{part}"] = (dims, np.ascontiguousarray(array),
                                           {**attrs, "complex_of": name, "complex_part": part})
    else:
        data_vars[name] = (dims, values, attrs)


def _get(ds, name: str) -> np.ndarray:
    """A variable written by :func:`_put`, complex again if it was complex."""
    if name in ds.variables:
        return ds[name].values
    return ds[f"{name}_real"].values + 1j * ds[f"{name}_imag"].values


def _dataset(data_vars: dict, coords: dict, kind: str, *, params=None, grid=None,
             info: dict | None = None, **extra_attrs):
    import xarray as xr

    attrs = {"gyroshell_type": kind, "gyroshell_version": _version(),
             "parameters": _params_json(params), "grid": _grid_json(grid),
             "info": to_json(info or {}), "complex_convention":
             "complex z stored as z_real, z_imag (attributes complex_of, complex_part)"}
    attrs.update({k: (to_json(v) if not isinstance(v, str) else v)
                  for k, v in extra_attrs.items()})
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def _xy(grid) -> dict:
    return {"x": ("x", grid.x, {"units": "m", "long_name": "along the tape"}),
            "y": ("y", grid.y, {"units": "m", "long_name": "across the tape"})}


# ----- one converter per result type ------------------------------------------------------
def _static(result, params):
    dv: dict = {}
    _put(dv, "w", ("x", "y"), result.field, {"units": "m", "long_name": "deflection"})
    dv["velocity"] = ((), result.velocity, {"units": "m/s"})
    dv["load_point_deflection"] = ((), result.load_point_deflection, {"units": "m"})
    return _dataset(dv, _xy(result.grid), "static", params=params, grid=result.grid)


def _modes(result, params):
    dv: dict = {}
    coords = {**_xy(result.grid), "mode": ("mode", np.arange(result.count))}
    _put(dv, "eigenvalue", ("mode",), result.eigenvalues,
         {"units": "1/s", "long_name": "lambda (omega = |Im lambda|)"})
    _put(dv, "mode_shape", ("x", "y", "mode"), result.fields,
         {"units": "1", "long_name": "complex mode shape, largest entry 1"})
    dv["omega"] = (("mode",), result.omega, {"units": "rad/s"})
    dv["residual"] = (("mode",), result.residuals, {"units": "1"})
    dv["velocity"] = ((), result.velocity, {"units": "m/s"})
    return _dataset(dv, coords, "modes", params=params, grid=result.grid, info=result.info,
                    supercritical=int(result.supercritical),
                    damped=int(getattr(result, "damped", False)))


def _critical(result, params):
    dv = {name: ((), value, {"units": "m/s"}) for name, value in (
        ("critical_speed", result.critical_speed),
        ("divergence_speed", result.divergence_speed),
        ("string_speed", result.string_speed), ("strip_speed", result.strip_speed),
        ("sundaram_benson_speed", result.sundaram_benson_speed),
        ("paper_speed", result.paper_speed))}
    return _dataset(dv, {}, "critical", params=params, info=result.info)


def _transient(result, params):
    s = result.snapshots
    dv: dict = {}
    coords = {"t": ("t", result.times, {"units": "s"}),
              "x": ("x", s.x, {"units": "m"}), "y": ("y", s.y, {"units": "m"}),
              "snapshot_time": ("snapshot_time", s.times, {"units": "s"}),
              "centerline_time": ("centerline_time", s.centerline_times, {"units": "s"})}
    dv["load_point"] = (("t",), result.load_point, {"units": "m",
                                                   "long_name": "load-point displacement"})
    dv["fields"] = (("snapshot_time", "x", "y"), s.fields, {"units": "m"})
    dv["centerlines"] = (("centerline_time", "x"), s.centerlines, {"units": "m"})
    for name, unit in (("w", "m"), ("v", "m/s"), ("a", "m/s^2")):
        dv[f"final_{name}"] = (("unknown",), getattr(result, name), {"units": unit})
    if result.energy is not None:
        dv["energy"] = (("t",), result.energy, {"units": "J"})
    for name, unit in (("velocity", "m/s"), ("dt", "s"), ("beta", "1"), ("gamma", "1")):
        dv[name] = ((), getattr(result, name), {"units": unit})
    return _dataset(dv, coords, "transient", params=params, info=result.info)


#: Units of the table columns that studies and sweeps write.
_UNITS_OF = {"velocity": "m/s", "tension": "N/m", "thickness": "m", "youngs_modulus": "Pa",
             "radius": "m", "width": "m", "spacing": "m", "density": "kg/m^2", "load": "Pa",
             "load_x": "m", "load_y": "m", "bending_rigidity": "N*m",
             "foundation_stiffness": "N/m^3", "critical_speed": "m/s",
             "divergence_speed": "m/s", "growth_rate": "1/s", "omega": "rad/s",
             "frequency": "Hz", "period": "s", "load_point_deflection": "m",
             "max_deflection": "m", "poisson": "1", "length_ratio": "1"}


def _column_units(ds) -> None:
    for name in ds.variables:
        unit = "rad/s" if str(name).startswith("omega_") else _UNITS_OF.get(str(name))
        if unit:
            ds[name].attrs["units"] = unit


def _table(frame, kind: str = "table", params=None, **attrs):
    import xarray as xr

    frame = frame.reset_index(drop=True)
    ds = xr.Dataset.from_dataframe(frame.rename_axis("row"))
    _column_units(ds)
    columns = list(frame.columns)
    base = _dataset({}, {}, kind, params=params, columns=columns, **attrs)
    ds.attrs.update(base.attrs)
    return ds


def to_xarray(result, *, params=None):
    """The result as an :class:`xarray.Dataset` (named dimensions, units, metadata).

    Parameters
    ----------
    result : StaticSolution, TransientResult, Modes, CriticalSpeeds, StudyResult or
        pandas.DataFrame (a sweep or any table)
    params : TapeParameters, optional
        The tape the result was computed for, stored as metadata (a study knows its own).
    """
    from ..engines.critical import CriticalSpeeds
    from ..engines.eigen import Modes
    from ..engines.static import StaticSolution
    from .transient import TransientResult

    if isinstance(result, StaticSolution):
        return _static(result, params)
    if isinstance(result, Modes):
        return _modes(result, params)
    if isinstance(result, CriticalSpeeds):
        return _critical(result, params)
    if isinstance(result, TransientResult):
        return _transient(result, params)
    if hasattr(result, "_persistence_attrs"):  # StudyResult
        return _table(result.table, "study", **result._persistence_attrs())
    import pandas as pd

    if isinstance(result, pd.DataFrame):
        return _table(result, params=params)
    raise ParameterError(f"cannot convert a {type(result).__name__} to xarray")


# ----- writing and reading files ----------------------------------------------------------
def _engine() -> str:
    for name, module in (("h5netcdf", "h5netcdf"), ("netcdf4", "netCDF4")):
        try:
            __import__(module)
            return name
        except ImportError:
            continue
    raise ParameterError('NetCDF needs h5netcdf or netCDF4: pip install "gyroshell[io]"')


def _table_of(result):
    import pandas as pd

    if isinstance(result, pd.DataFrame):
        return result
    if hasattr(result, "table"):
        return result.table
    raise ParameterError(f"a {type(result).__name__} is not a table: save it as .nc")


def save(result, path: str | os.PathLike[str], *, params=None) -> Path:
    """Write a result to ``path``: NetCDF (``.nc``) for any result, CSV or Parquet for tables.

    The file is written whole or not at all. Returns the path.
    """
    from ..core.files import atomic_path

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in NETCDF_SUFFIXES:
        ds = to_xarray(result, params=params)
        engine = _engine()
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp, engine=engine)
    elif suffix == ".csv":
        frame = _table_of(result)
        with atomic_path(path) as tmp:
            frame.to_csv(tmp, index=False, na_rep="NaN")
    elif suffix == ".parquet":
        frame = _table_of(result)
        with atomic_path(path) as tmp:
            frame.to_parquet(tmp, index=False)
    else:
        raise ParameterError(f"unknown file type {path.suffix!r}: use one of "
                             f"{', '.join(NETCDF_SUFFIXES + TABLE_SUFFIXES)}")
    return path


def load(path: str | os.PathLike[str]):
    """Read a result written by :func:`save`: the same kind of object, equal to the original.

    A ``.csv`` or ``.parquet`` file gives a pandas DataFrame; a NetCDF file gives the
    object named by its ``gyroshell_type`` attribute (a DataFrame for ``table``).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    import pandas as pd

    if suffix == ".csv":
        exact = {} if int(pd.__version__.split(".")[0]) >= 3 else {
            "float_precision": "round_trip"}  # pandas 3 parses floats exactly by default
        return pd.read_csv(path, keep_default_na=False, na_values=["NaN"], **exact)
    if suffix == ".parquet":
        return pd.read_parquet(path)
    import xarray as xr

    with xr.open_dataset(path, engine=_engine()) as ds:
        ds = ds.load()
    kind = ds.attrs.get("gyroshell_type")
    readers = {"static": _read_static, "modes": _read_modes, "critical": _read_critical,
               "transient": _read_transient, "table": _read_table, "study": _read_study}
    if kind not in readers:
        raise ParameterError(f"{path} is not a gyroshell result file (gyroshell_type "
                             f"{kind!r})")
    return readers[kind](ds)


def metadata(path_or_dataset) -> dict:
    """``gyroshell_type``, ``gyroshell_version``, ``parameters`` (TapeParameters or None),
    ``grid`` (Grid or None) and ``info`` of a saved NetCDF file or a Dataset."""
    ds = path_or_dataset
    if not hasattr(ds, "attrs"):
        import xarray as xr

        with xr.open_dataset(path_or_dataset, engine=_engine()) as opened:
            attrs = dict(opened.attrs)
    else:
        attrs = dict(ds.attrs)
    return {"gyroshell_type": attrs.get("gyroshell_type"),
            "gyroshell_version": attrs.get("gyroshell_version"),
            "parameters": _params_from(attrs), "grid": _grid_from(attrs),
            "info": from_json(attrs.get("info", "{}"))}


def _read_static(ds):
    from ..engines.static import StaticSolution

    grid = _grid_from(ds.attrs)
    return StaticSolution(grid, float(ds["velocity"]), grid.from_field(_get(ds, "w")),
                          float(ds["load_point_deflection"]))


def _read_modes(ds):
    from ..engines.eigen import Modes

    grid = _grid_from(ds.attrs)
    return Modes(grid, float(ds["velocity"]), _get(ds, "eigenvalue"),
                 grid.from_field(_get(ds, "mode_shape")), ds["residual"].values,
                 bool(int(ds.attrs["supercritical"])), from_json(ds.attrs["info"]),
                 bool(int(ds.attrs.get("damped", 0))))


def _read_critical(ds):
    from ..engines.critical import CriticalSpeeds

    names = ("critical_speed", "divergence_speed", "string_speed", "strip_speed",
             "sundaram_benson_speed", "paper_speed")
    return CriticalSpeeds(*(float(ds[n]) for n in names), info=from_json(ds.attrs["info"]))


def _read_transient(ds):
    from .transient import Snapshots, TransientResult

    snaps = Snapshots(ds["x"].values, ds["y"].values, ds["snapshot_time"].values,
                      ds["fields"].values, ds["centerline_time"].values,
                      ds["centerlines"].values)
    return TransientResult(
        ds["t"].values, ds["load_point"].values, snaps, ds["final_w"].values,
        ds["final_v"].values, ds["final_a"].values, float(ds["velocity"]), float(ds["dt"]),
        float(ds["beta"]), float(ds["gamma"]),
        ds["energy"].values if "energy" in ds else None, from_json(ds.attrs["info"]))


def _read_table(ds):
    columns = from_json(ds.attrs["columns"])
    frame = ds.to_dataframe().reset_index(drop=True)
    return frame[columns]


def _read_study(ds):
    from ..studies.parameter_study import StudyResult

    return StudyResult._from_saved(_read_table(ds), ds.attrs)
