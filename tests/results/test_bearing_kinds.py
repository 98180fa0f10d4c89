"""The bearing's result kinds on the result protocol: save -> read gives back every field
bit for bit (values, dtype, shape), the model settings, grading, air, tape and Newton
record; files of the previous release's layout still load; summary, table and plot."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

pytest.importorskip("xarray")

from examples_bearing import EXAMPLES, steady, steady_2d, steady_legacy  # noqa: E402

from gyroshell import TapeParameters  # noqa: E402
from gyroshell.bearing import (  # noqa: E402
    BearingModel,
    BearingSolution,
    storage,  # noqa: E402
)
from gyroshell.bearing.results import BearingTransient  # noqa: E402
from gyroshell.core.errors import ParameterError  # noqa: E402
from gyroshell.results.base import from_dataset, kinds, read  # noqa: E402

ARRAYS = ("u", "p", "contact")
SERIES = ("t", "central_spacing", "minimum_spacing", "contact_force", "tension", "x",
          "centreline", "newton_iterations")


def _same_array(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b)


def _assert_same_model(a: BearingModel, b: BearingModel) -> None:
    assert a.params == b.params and a.air == b.air and a.grading == b.grading
    for name in ("velocity", "wrap_angle", "infinitely_wide", "span", "nx", "ny", "length"):
        assert getattr(a, name) == getattr(b, name), name
    assert _same_array(a.x, b.x)
    assert (a.y is None and b.y is None) or _same_array(a.y, b.y)


def _assert_same_solution(a: BearingSolution, b: BearingSolution) -> None:
    _assert_same_model(a.model, b.model)
    for name in ARRAYS:
        assert _same_array(getattr(a, name), getattr(b, name)), name
    assert dataclasses.asdict(a.info) == dataclasses.asdict(b.info)
    assert a.summary() == b.summary()


def test_kinds_are_registered():
    assert kinds()["bearing"] is BearingSolution
    assert kinds()["bearing_transient"] is BearingTransient
    assert set(EXAMPLES) == {"bearing", "bearing_transient"}


@pytest.mark.slow
@pytest.mark.parametrize("build", [steady, steady_2d], ids=["1-D", "2-D-graded"])
def test_steady_round_trip_is_bit_exact(tmp_path, build):
    sol = build()
    back = read(sol.save(tmp_path / "s.nc"))
    assert type(back) is BearingSolution
    _assert_same_solution(sol, back)
    assert back.info.step_norms and back.info.residual_norms


@pytest.mark.slow
def test_transient_round_trip_is_bit_exact(tmp_path):
    run = EXAMPLES["bearing_transient"]()
    back = read(run.save(tmp_path / "t.nc"))
    assert type(back) is BearingTransient
    for name in SERIES:
        assert _same_array(getattr(run, name), getattr(back, name)), name
    _assert_same_solution(run.final, back.final)
    assert back.summary() == run.summary()
    ds = run.to_xarray()
    assert ds["t"].attrs["units"] == "s" and ds["centreline"].dims == ("t", "x")


def _previous_release_dataset(sol: BearingSolution, *, with_grading: bool = True):
    """A steady state laid out as ``gyroshell.bearing.storage.save`` wrote it before the
    result protocol (and, without ``with_grading``, before graded grids)."""
    import xarray as xr

    m = sol.model
    y = np.zeros(1) if m.infinitely_wide else m.y

    def nodal(values):
        out = np.zeros((m.nx + 1, m.nc))
        out[1:-1, :] = values.reshape(m.nx - 1, m.nc)
        return out

    settings = {"velocity": m.velocity, "wrap_angle": m.wrap_angle,
                "infinitely_wide": m.infinitely_wide, "span": m.span, "nx": m.nx,
                "ny": m.ny}
    if with_grading:
        settings["grading"] = m.grading.as_dict()
    params = {f.name: getattr(m.params, f.name) for f in dataclasses.fields(m.params)}
    attrs = {"gyroshell_type": "bearing", "gyroshell_version": "0.0",
             "parameters": json.dumps(params), "grid": "null",
             "info": json.dumps(dataclasses.asdict(sol.info)),
             "air": json.dumps({k: v for k, v in dataclasses.asdict(m.air).items()
                                if k not in ("rarefaction", "flow_factors")}),
             "model": json.dumps(settings),
             "summary": json.dumps({})}
    data = {"spacing": (("x", "y"), sol.spacing), "pressure": (("x", "y"), sol.pressure),
            "departure": (("x", "y"), nodal(sol.u)),
            "contact": (("x", "y"), nodal(sol.contact))}
    return xr.Dataset(data, coords={"x": ("x", sol.x), "y": ("y", y)}, attrs=attrs)


@pytest.mark.slow
def test_previous_release_files_load(tmp_path):
    """A file of a release before contact laws (no rarefaction, flow factors or contact
    stored) loads as the first-order film over the hard wall it was computed with."""
    sol = steady_legacy()
    ds = _previous_release_dataset(sol)
    path = tmp_path / "old.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    _assert_same_solution(sol, read(path))
    _assert_same_solution(sol, storage.load(path))
    # before graded grids the settings had no grading: uniform
    _assert_same_solution(sol, from_dataset(_previous_release_dataset(sol,
                                                                      with_grading=False)))


@pytest.mark.slow
def test_mismatched_coordinates_are_refused():
    sol = steady()
    ds = sol.to_xarray()
    ds = ds.assign_coords(x=ds["x"].values * 1.01)
    with pytest.raises(ParameterError, match="node coordinates"):
        from_dataset(ds)


@pytest.mark.slow
def test_storage_wrappers(tmp_path):
    sol = steady()
    back = storage.load(storage.save(sol, tmp_path / "b.nc"))
    _assert_same_solution(sol, back)
    with pytest.raises(ParameterError, match="NetCDF"):
        storage.save(sol, tmp_path / "b.csv")
    EXAMPLES["bearing_transient"]().save(tmp_path / "t.nc")
    with pytest.raises(ParameterError, match="not a saved bearing state"):
        storage.load(tmp_path / "t.nc")


@pytest.mark.slow
def test_summary_table_and_plot(tmp_path):
    import matplotlib.axes

    sol = steady_2d()
    s = sol.summary()
    assert s["unknowns"] == sol.model.unknowns
    assert s["wrap_angle_degrees"] == pytest.approx(15.0, rel=1e-12)
    frame = sol.to_frame()
    assert list(frame.columns) == ["x", "y", "spacing", "pressure", "shear_stress",
                                   "contact_pressure"]
    assert len(frame) == (sol.model.nx + 1) * sol.model.nc
    assert np.array_equal(frame["spacing"].to_numpy(), sol.spacing.ravel())
    assert isinstance(sol.plot(), matplotlib.axes.Axes)
    run = EXAMPLES["bearing_transient"]()
    table = run.to_frame()
    assert np.array_equal(table["t"].to_numpy(), run.t)
    assert isinstance(run.plot(), matplotlib.axes.Axes)
    assert run.save(tmp_path / "t.csv").stat().st_size > 0


def test_size_is_a_deprecated_alias_of_unknowns():
    model = BearingModel(TapeParameters(), velocity=4.0, wrap_angle=math.radians(15),
                         infinitely_wide=True, nx=60)
    assert model.unknowns == model.n_u + model.n_p
    with pytest.warns(DeprecationWarning, match="unknowns"):
        assert model.size == model.unknowns
