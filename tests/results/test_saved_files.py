"""Saved results: save -> load gives back the same object, bit for bit, with its metadata."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import gyroshell
from gyroshell import (
    TapeModel,
    TapeParameters,
    critical_speeds,
    march,
    modes,
    run_study,
    solve_static,
    sweep,
)
from gyroshell.core.errors import ParameterError
from gyroshell.results.base import metadata

PARAMS = TapeParameters(length_ratio=4, spacing=6.35e-3 / 10)


@pytest.fixture(scope="module")
def model() -> TapeModel:
    return TapeModel(PARAMS)


def same_array(a, b):
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape and a.dtype == b.dtype
    assert np.array_equal(a, b, equal_nan=True)


def test_static_round_trip(model, tmp_path):
    sol = solve_static(model, 50.0)
    path = sol.save(tmp_path / "static.nc", params=PARAMS)
    back = gyroshell.load(path)
    assert back.grid == sol.grid and back.velocity == sol.velocity
    same_array(back.w, sol.w)
    assert back.load_point_deflection == sol.load_point_deflection
    meta = metadata(path)
    assert meta["parameters"] == PARAMS and meta["grid"] == model.grid
    assert meta["gyroshell_version"] == gyroshell.__version__


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [30.0, 120.0])  # ±iω pairs, and complex/real above
def test_modes_round_trip_keeps_complex_values(model, tmp_path, velocity):
    res = modes(model, velocity, 4)
    back = gyroshell.load(res.save(tmp_path / "modes.nc"))
    assert (back.grid, back.velocity, back.supercritical) == (
        res.grid, res.velocity, res.supercritical)
    same_array(back.eigenvalues, res.eigenvalues)
    same_array(back.vectors, res.vectors)
    same_array(back.residuals, res.residuals)
    assert back.info == res.info  # complex shift survives the JSON metadata


@pytest.mark.slow
def test_damped_modes_round_trip(model, tmp_path):
    res = modes(model, 30.0, 3, damping=20.0)
    back = gyroshell.load(res.save(tmp_path / "damped.nc"))
    assert back.damped and res.damped
    same_array(back.eigenvalues, res.eigenvalues)
    same_array(back.decay_rate, res.decay_rate)


@pytest.mark.slow
def test_netcdf_stores_complex_as_real_and_imaginary_parts(model, tmp_path):
    res = modes(model, 120.0, 3)
    path = res.save(tmp_path / "m.nc")
    with xr.open_dataset(path) as ds:  # any reader: two real arrays with their roles
        re, im = ds["eigenvalue_real"], ds["eigenvalue_imag"]
        assert re.attrs["complex_part"] == "real" and im.attrs["complex_of"] == "eigenvalue"
        same_array(re.values + 1j * im.values, res.eigenvalues)
        assert ds["mode_shape_real"].dims == ("x", "y", "mode")
        assert ds["x"].attrs["units"] == "m"


@pytest.mark.slow
def test_critical_round_trip(model, tmp_path):
    crit = critical_speeds(model)
    back = gyroshell.load(crit.save(tmp_path / "crit.nc", params=PARAMS))
    assert back.as_dict() == crit.as_dict()
    assert back.info["bracket"] == crit.info["bracket"]


@pytest.mark.slow
@pytest.mark.parametrize("energy, keep", [(True, True), (False, True), (False, False)])
def test_transient_round_trip(model, tmp_path, energy, keep):
    extra = {"snapshot_every": 20, "centerline_times": [2e-5, 4e-5]} if keep else {}
    run = march(model, 50.0, dt=2e-6, steps=40, record_energy=energy, progress=False,
                **extra)
    back = gyroshell.load(run.save(tmp_path / "run.nc"))
    for name in ("times", "load_point", "w", "v", "a"):
        same_array(getattr(back, name), getattr(run, name))
    for name in ("x", "y", "times", "fields", "centerline_times", "centerlines"):
        same_array(getattr(back.snapshots, name), getattr(run.snapshots, name))
    assert (back.energy is None) == (run.energy is None)
    if energy:
        same_array(back.energy, run.energy)
    assert (back.velocity, back.dt, back.beta, back.gamma) == (50.0, 2e-6, 0.25, 0.5)
    assert back.info == run.info


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".nc", ".csv", ".parquet"])
def test_sweep_table_round_trip(model, tmp_path, suffix):
    frame = sweep(model, [0.0, 60.0, 110.0], 3, progress=False).table
    back = gyroshell.load(gyroshell.save(frame, tmp_path / f"sweep{suffix}"))
    pd.testing.assert_frame_equal(back, frame, check_exact=True)


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".nc", ".csv", ".parquet"])
def test_study_round_trip(tmp_path, suffix):
    study = run_study(PARAMS, vary={"velocity": [0.0, 100.5], "tension": [70.0, 90.0]},
                      compute=["modes", "static"], count=2, workers=1)
    assert study.failed.shape[0] == 2  # static above critical: reported in the row
    path = study.save(tmp_path / f"study{suffix}")
    back = gyroshell.load(path)
    if suffix == ".nc":
        pd.testing.assert_frame_equal(back.table, study.table, check_exact=True)
        assert back.base == PARAMS and back.varied == ("velocity", "tension")
        assert back.compute == ("modes", "static") and back.count == 2
    else:  # a plain table
        pd.testing.assert_frame_equal(back, study.table, check_exact=True)


def test_refusals(tmp_path, model):
    with pytest.raises(ParameterError, match="unknown file type"):
        solve_static(model, 0.0).save(tmp_path / "x.txt")
    with pytest.raises(ParameterError, match="not a table"):
        gyroshell.save(solve_static(model, 0.0), tmp_path / "x.csv")
    with pytest.raises(FileNotFoundError):
        gyroshell.load(tmp_path / "missing.nc")
    xr.Dataset({"a": ("x", [1.0])}).to_netcdf(tmp_path / "other.nc", engine="h5netcdf")
    with pytest.raises(ParameterError, match="not a gyroshell result"):
        gyroshell.load(tmp_path / "other.nc")
    assert not list(tmp_path.glob(".*")), "temporary files left behind"


@pytest.mark.slow
def test_study_gridded_view_has_one_dimension_per_varied_parameter():
    study = run_study(PARAMS, vary={"velocity": [0.0, 50.0, 100.5], "tension": [70.0, 90.0]},
                      compute="modes", count=1, workers=1)
    ds = study.gridded()
    assert ds["stability"].dims == ("velocity", "tension")
    assert ds["omega_1"].attrs["units"] == "rad/s" and ds["velocity"].attrs["units"] == "m/s"
    for row in study.table.itertuples():
        cell = ds.sel(velocity=row.velocity, tension=row.tension)
        assert cell["omega_1"].item() == row.omega_1
        assert cell["stability"].item() == row.stability
    assert study.to_xarray()["omega_1"].attrs["units"] == "rad/s"
    twice = run_study(PARAMS, points=[{"tension": 80.0}, {"tension": 80.0}],
                      compute="modes", count=1, workers=1)
    with pytest.raises(ParameterError, match="no grid"):
        twice.gridded()
