"""gyroshell.load of broken files (issue 18, causes 4, 6 and 10): each is refused with an
InputFileError (a ParameterError) naming the file and what is wrong.

The files are real: a result is saved, then the file is damaged as a user or another tool
would (truncated, emptied, replaced, its attributes edited with h5py, its variables edited
with xarray and written again).
"""

from __future__ import annotations

import json
import os

import h5py
import numpy as np
import pytest
import xarray as xr
from conftest import WIDTH
from kind_examples import every_example

import gyroshell
import gyroshell.kinds
from gyroshell import ParameterError, TapeModel, TapeParameters, solve_static
from gyroshell.core.errors import InputFileError, MissingFileError
from gyroshell.results import base

TINY = TapeParameters(length_ratio=2, spacing=WIDTH / 8)


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    """A real static result's file (16 x 8 intervals), copied fresh for each test."""
    folder = tmp_path_factory.mktemp("saved")
    path = folder / "static.nc"
    solve_static(TapeModel(TINY), 10.0).save(path)
    return path.read_bytes()


@pytest.fixture
def static_file(saved, tmp_path):
    path = tmp_path / "static.nc"
    path.write_bytes(saved)
    return path


def refused(path, match: str) -> InputFileError:
    with pytest.raises(InputFileError) as info:
        gyroshell.load(path)
    message = str(info.value)
    assert match in message, message
    assert os.fspath(path) in message, message
    assert "\n" not in message
    return info.value


# ----- the file itself --------------------------------------------------------------------
def test_empty_file(tmp_path):
    path = tmp_path / "empty.nc"
    path.write_bytes(b"")
    refused(path, "empty file, not a NetCDF file")


@pytest.mark.parametrize("keep", [8, 100, 0.5, 0.99])
def test_truncated_file(static_file, keep):
    data = static_file.read_bytes()
    n = keep if isinstance(keep, int) else int(keep * len(data))
    static_file.write_bytes(data[:n])
    refused(static_file, "cannot be read as NetCDF (truncated or damaged?)")


@pytest.mark.parametrize("content", [b"hello, this is text\n" * 20, bytes(range(256)),
                                     b"\x89PNG\r\n\x1a\n" + bytes(100)])
def test_not_netcdf(tmp_path, content):
    path = tmp_path / "other.nc"
    path.write_bytes(content)
    refused(path, "not a NetCDF file")


def test_folder_is_a_directory_not_no_such_file(tmp_path):
    (tmp_path / "run.nc").mkdir()
    refused(tmp_path / "run.nc", "is a directory, not a NetCDF file")
    (tmp_path / "table.csv").mkdir()
    refused(tmp_path / "table.csv", "is a directory, not a CSV file")


def test_missing_file_is_a_file_not_found_error_too(tmp_path):
    with pytest.raises(MissingFileError, match="no such NetCDF file") as info:
        gyroshell.load(tmp_path / "none.nc")
    assert isinstance(info.value, FileNotFoundError) and isinstance(info.value, ParameterError)


@pytest.mark.parametrize("content, match", [
    (b"", "empty file, not a CSV table"),
    (b"\n\n", "no columns: an empty CSV table"),
    (bytes(range(128, 256)) * 4, "not UTF-8 text"),
    (b'a,b\n1,2\n"3,4\n', "not a CSV table"),
])
def test_broken_csv(tmp_path, content, match):
    path = tmp_path / "table.csv"
    path.write_bytes(content)
    refused(path, match)


def test_broken_parquet(tmp_path):
    path = tmp_path / "table.parquet"
    path.write_bytes(b"PAR1 but not really" * 10)
    refused(path, "not a Parquet table")


# ----- metadata, edited with h5py ---------------------------------------------------------
def edit_attrs(path, **changes) -> None:
    with h5py.File(path, "r+") as fh:
        for name, value in changes.items():
            if value is None:
                del fh.attrs[name]
            else:
                fh.attrs[name] = value


def edit_json(path, name: str, change) -> None:
    with h5py.File(path, "r+") as fh:
        data = json.loads(fh.attrs[name])
        change(data)
        fh.attrs[name] = json.dumps(data)


METADATA = [
    ("unknown kind", lambda p: edit_attrs(p, gyroshell_type="banana"),
     "is not a gyroshell result file (gyroshell_type 'banana'"),
    ("no kind", lambda p: edit_attrs(p, gyroshell_type=None),
     "is not a gyroshell result file (gyroshell_type None"),
    ("newer version", lambda p: edit_attrs(p, gyroshell_version="9.0.0"),
     "written by gyroshell 9.0.0, newer than this gyroshell"),
    ("not a version", lambda p: edit_attrs(p, gyroshell_version="banana"),
     "gyroshell_version 'banana' is not a version"),
    ("no version", lambda p: edit_attrs(p, gyroshell_version=None),
     "no gyroshell_version attribute"),
    ("parameters: extra key", lambda p: edit_json(p, "parameters",
                                                  lambda d: d.update(colour="red")),
     "parameters: unknown field(s) colour"),
    ("parameters: missing key", lambda p: edit_json(p, "parameters",
                                                    lambda d: d.pop("tension")),
     "parameters: missing field(s) tension"),
    ("parameters: null tension", lambda p: edit_json(p, "parameters",
                                                     lambda d: d.update(tension=None)),
     "parameters: tension must be a real number N/m, got None"),
    ("parameters: negative tension", lambda p: edit_json(p, "parameters",
                                                         lambda d: d.update(tension=-5)),
     "parameters: tension must be >= 0 N/m, got -5"),
    ("parameters: text thickness", lambda p: edit_json(p, "parameters",
                                                       lambda d: d.update(thickness="thin")),
     "parameters: thickness must be a real number m, got 'thin'"),
    ("parameters: not JSON", lambda p: edit_attrs(p, parameters="{tension: 90"),
     "attribute parameters is not valid JSON"),
    ("parameters: a list", lambda p: edit_attrs(p, parameters="[1, 2]"),
     "parameters must be a JSON object of TapeParameters fields, got list"),
    ("grid: null", lambda p: edit_attrs(p, grid="null"), "grid is missing or null"),
    ("grid: extra key", lambda p: edit_json(p, "grid", lambda d: d.update(nz=4)),
     "grid: unknown field(s) nz"),
    ("grid: 10**7 intervals", lambda p: edit_json(p, "grid", lambda d: d.update(ny=10**7)),
     "grid: the grid of 16 x 10000000 intervals"),
    ("grid: fractional count", lambda p: edit_json(p, "grid", lambda d: d.update(nx=16.5)),
     "grid: nx must be an integer, got 16.5"),
    ("grid: other grid", lambda p: edit_json(p, "grid", lambda d: d.update(nx=32)),
     "dimension x has 17 entries but the stored grid (32 x 8 intervals"),
    ("grid: other length", lambda p: edit_json(p, "grid", lambda d: d.update(length=1.0)),
     "grid length 1 m differs from the tape's length 0.0127 m"),
    # a grid that does not span the stored tape (the grid's x, y still match each other)
    ("parameters: other width", lambda p: edit_json(p, "parameters",
                                                    lambda d: d.update(width=0.01)),
     "grid length 0.0127 m differs from the tape's length 0.02 m"),  # L_x = ratio x L_y
    ("grid: other edges", lambda p: edit_json(p, "grid",
                                              lambda d: d.update(edges="simply-supported")),
     "grid edges 'simply-supported' differ from the tape's edges 'free'"),
    ("info: not an object", lambda p: edit_attrs(p, info="[]"),
     "info must be a JSON object, got list"),
]


@pytest.mark.parametrize("case, edit, match", METADATA, ids=[c[0] for c in METADATA])
def test_broken_metadata(static_file, case, edit, match):
    edit(static_file)
    refused(static_file, match)


# ----- variables, edited with xarray ------------------------------------------------------
def edit_dataset(path, change) -> None:
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        ds = ds.load()
    ds = change(ds)
    os.remove(path)
    ds.to_netcdf(path, engine="h5netcdf")


def _text(ds, name):
    ds[name] = ds[name].dims, np.full(ds[name].shape, "fast", dtype=object)
    return ds


def _nan(ds, name):
    values = ds[name].values.copy()
    values.flat[0] = np.nan
    ds[name] = ds[name].dims, values
    return ds


VARIABLES = [
    ("negative speed", lambda ds: ds.assign(velocity=-5.0),
     "velocity must be >= 0 m/s, got -5"),
    ("speed as text", lambda ds: _text(ds, "velocity"),
     "variable velocity holds text"),
    ("deflection as text", lambda ds: _text(ds, "w"),
     "variable w holds text"),
    ("NaN deflection", lambda ds: _nan(ds, "w"), "variable w has NaN or infinite values"),
    ("infinite speed", lambda ds: ds.assign(velocity=np.inf),
     "variable velocity has NaN or infinite values"),
    ("missing deflection", lambda ds: ds.drop_vars("w"), "missing variable w"),
    ("missing speed", lambda ds: ds.drop_vars("velocity"), "missing variable velocity"),
    ("deflection transposed", lambda ds: ds.assign(w=ds["w"].T),
     "variable w has dimensions ('y', 'x'), expected ('x', 'y')"),
    ("deflection on the wrong grid",
     lambda ds: ds.drop_vars("w").assign(w=(("x", "y"), np.zeros((17, 9)))).isel(x=slice(8)),
     "dimension x has 8 entries but the stored grid"),
    ("coordinates reversed", lambda ds: ds.assign_coords(x=ds["x"].values[::-1]),
     "x must be strictly increasing"),
]


@pytest.mark.parametrize("case, change, match", VARIABLES, ids=[c[0] for c in VARIABLES])
def test_broken_variables(static_file, case, change, match):
    edit_dataset(static_file, change)
    refused(static_file, match)


def test_a_plain_text_edit_of_a_csv_table_still_loads_as_a_table(tmp_path):
    # CSV tables are any DataFrame: an edited value is data, not a broken file.
    path = tmp_path / "table.csv"
    path.write_text("velocity,omega\n0,1.5\n10,NaN\n")
    frame = gyroshell.load(path)
    assert list(frame.columns) == ["velocity", "omega"] and np.isnan(frame["omega"][1])


# ----- every kind -------------------------------------------------------------------------
gyroshell.kinds.import_kinds()
KINDS = sorted(base.kinds())


def _layout(kind: str):
    return base.kinds()[kind].file_layout


def test_every_kind_declares_what_its_file_holds():
    assert [kind for kind in KINDS if _layout(kind) is None] == []


@pytest.fixture(scope="module")
def example_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("kinds")
    examples, files = every_example(), {}
    for kind in KINDS:
        files[kind] = folder / f"{kind}.nc"
        examples[kind]().save(files[kind])
    return files


def _first_variable(kind: str, ds, *, numeric: bool) -> str | None:
    for name, variable in _layout(kind).variables.items():
        stored = f"{name}_real" if variable.kind == "complex" else name
        if variable.optional or stored not in ds.variables:
            continue
        if not numeric or variable.kind in ("float", "complex"):
            return stored
    return None


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_refuses_a_missing_variable(example_files, tmp_path, kind):
    path = tmp_path / f"{kind}.nc"
    path.write_bytes(example_files[kind].read_bytes())
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        name = _first_variable(kind, ds, numeric=False)
    if name is None:
        pytest.skip(f"a {kind} file holds only attributes and table columns")
    edit_dataset(path, lambda ds: ds.drop_vars(name))
    refused(path, f"missing variable {name}")


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_refuses_text_where_numbers_belong(example_files, tmp_path, kind):
    path = tmp_path / f"{kind}.nc"
    path.write_bytes(example_files[kind].read_bytes())
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        name = _first_variable(kind, ds, numeric=True)
    if name is None:
        pytest.skip(f"a {kind} file has no numeric variable of its own")
    edit_dataset(path, lambda ds: _text(ds, name))
    refused(path, f"variable {name} holds text")


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_refuses_broken_metadata(example_files, tmp_path, kind):
    path = tmp_path / f"{kind}.nc"
    path.write_bytes(example_files[kind].read_bytes())
    edit_attrs(path, info="{not json")
    refused(path, "attribute info is not valid JSON")
    path.write_bytes(example_files[kind].read_bytes())
    edit_attrs(path, gyroshell_version="99.0")
    refused(path, "newer than this gyroshell")


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_with_negative_stored_parameters_is_refused(example_files, tmp_path,
                                                               kind):
    path = tmp_path / f"{kind}.nc"
    path.write_bytes(example_files[kind].read_bytes())
    with h5py.File(path, "r") as fh:
        stored = json.loads(fh.attrs.get("parameters", "null"))
    if stored is None:
        pytest.skip(f"this {kind} example carries no tape")
    edit_json(path, "parameters", lambda d: d.update(thickness=-2e-5))
    refused(path, "parameters: thickness must be > 0 m, got -2e-05")


KIND_EDITS = [
    ("transient", lambda ds: ds.assign(dt=0.0), "dt must be > 0 s, got 0"),
    ("transient", lambda ds: _nan(ds, "t"), "variable t has NaN"),
    ("modes", lambda ds: ds.assign(residual=-ds["residual"] - 1), "residual must be >= 0"),
    ("modes", lambda ds: ds.assign(velocity=-1.0), "velocity must be >= 0 m/s"),
    ("gyroscopic_modes", lambda ds: ds.drop_vars("vector_imag"),
     "missing variable vector_imag"),
    ("critical", lambda ds: ds.assign(divergence_speed=np.nan),
     "variable divergence_speed has NaN or infinite values"),
    ("frequency_response", lambda ds: ds.assign_coords(omega=-ds["omega"]),
     "omega must be >= 0 rad/s"),
    ("frequency_response", lambda ds: _text(ds, "points"), "variable points holds text"),
    ("sweep", lambda ds: ds.assign(velocities=-ds["velocities"] - 1),
     "velocity must be >= 0 m/s"),
    ("table", lambda ds: ds.drop_vars("omega"), "column omega (listed in columns) is missing"),
    ("study", lambda ds: ds.drop_vars("point"), "column point (listed in columns) is missing"),
    ("reduced_model", lambda ds: ds.assign(velocity=-3.0), "velocity must be >= 0 m/s"),
]


@pytest.mark.slow
@pytest.mark.parametrize("kind, change, match", KIND_EDITS,
                         ids=[f"{k}: {m}" for k, _, m in KIND_EDITS])
def test_kind_specific_fields_are_checked(example_files, tmp_path, kind, change, match):
    path = tmp_path / f"{kind}.nc"
    path.write_bytes(example_files[kind].read_bytes())
    edit_dataset(path, change)
    refused(path, match)


@pytest.mark.slow
@pytest.mark.parametrize("case, change, match", [
    ("count 2.5", lambda p: edit_attrs(p, count="2.5"), "count must be an integer >= 1"),
    ("count true", lambda p: edit_attrs(p, count="true"), "count must be an integer >= 1"),
    ("continuation text", lambda p: edit_attrs(p, continuation='"yes"'),
     "continuation must be true or false"),
    ("count missing", lambda p: edit_attrs(p, count=None), "missing attribute count"),
])
def test_sweep_settings_are_checked(example_files, tmp_path, case, change, match):
    path = tmp_path / "sweep.nc"
    path.write_bytes(example_files["sweep"].read_bytes())
    change(path)
    refused(path, match)


def test_cli_free_python_refusal_is_the_package_error(static_file):
    # The Python API raises the package's own exception, never an h5py/pandas one.
    static_file.write_bytes(static_file.read_bytes()[:500])
    with pytest.raises(ParameterError):
        gyroshell.load(static_file)


def _with_attr(ds, name: str, value: str):
    ds.attrs[name] = value
    return ds


def _count_plus(ds, step: int):
    return _with_attr(ds, "count", json.dumps(int(json.loads(ds.attrs["count"])) + step))


def _stray_speed(ds):
    velocity = ds["velocity"].values.copy()
    velocity[0] = 1e3
    return ds.assign(velocity=(ds["velocity"].dims, velocity))


@pytest.mark.slow
@pytest.mark.parametrize("kind, change, match", [
    ("sweep", lambda ds: _count_plus(ds, 4), "modes per speed"),
    ("sweep", lambda ds: _count_plus(ds, -1), "modes per speed"),
    ("sweep", _stray_speed, "rows at 1000 m/s, not one of the stored velocities"),
    ("study", lambda ds: _with_attr(ds, "varied", '["no_such_column"]'),
     "varied lists no_such_column"),
], ids=["sweep count above", "sweep count below", "sweep stray speed", "study varied"])
def test_a_table_that_contradicts_its_own_settings_is_refused(example_files, tmp_path, kind,
                                                              change, match):
    """The settings a sweep or study file stores describe its table: a hand edit that
    makes them disagree (seven modes said, three held) is refused on load, not loaded and
    plotted as if it were consistent."""
    path = tmp_path / f"{kind}.nc"
    path.write_bytes(example_files[kind].read_bytes())
    edit_dataset(path, change)
    refused(path, match)
