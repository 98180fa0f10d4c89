"""A steady bearing state survives save/load (NetCDF, the result protocol): the same
fields, summary and model, and the reloaded state is still a steady state."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("xarray")

from gyroshell import TapeParameters  # noqa: E402
from gyroshell.bearing import AirParameters, BearingModel, solve_steady  # noqa: E402
from gyroshell.bearing.steady import _Residual  # noqa: E402
from gyroshell.bearing.storage import load, save, to_xarray  # noqa: E402
from gyroshell.core.errors import ParameterError  # noqa: E402


@pytest.mark.slow
@pytest.mark.parametrize("wide", [True, False])
def test_round_trip_is_exact_and_still_steady(tmp_path, wide):
    params = TapeParameters(width=3e-3, foundation_stiffness=0.0)
    model = BearingModel(params, AirParameters(mean_free_path=50e-9), velocity=3.0,
                         wrap_angle=math.radians(12), infinitely_wide=wide, nx=60,
                         ny=None if wide else 16, span=2e-3)
    sol = solve_steady(model)
    back = load(save(sol, tmp_path / "b.nc"))
    assert back.model.params == params and back.model.air == model.air
    assert np.array_equal(back.u, sol.u) and np.array_equal(back.p, sol.p)
    assert np.array_equal(back.contact, sol.contact)
    assert back.summary() == sol.summary()
    res, _, _ = _Residual(back.model, None, None)(np.concatenate([back.u, back.p]),
                                                  jacobian=False)
    free = back.contact == 0
    scale = _Residual(back.model, None, None).row_scale
    assert np.max(np.abs((res * scale)[:back.model.n_u][free])) < 1e-6
    assert np.max(np.abs((res * scale)[back.model.n_u:])) < 1e-6
    ds = to_xarray(sol)
    assert ds["spacing"].attrs["units"] == "m" and ds.sizes["x"] == model.nx + 1
    # the node coordinates are stored as they are (graded in 2-D by default)
    assert np.array_equal(ds["x"].values, sol.x)
    assert back.model.grading == model.grading and np.array_equal(back.model.x, model.x)
    if not wide:
        assert model.graded and np.array_equal(ds["y"].values, model.y)
        assert np.ptp(np.diff(model.y)) > 0.3 * np.diff(model.y).max()


def test_refuses_other_suffixes_and_files(tmp_path):
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0,
                         wrap_angle=math.radians(15), infinitely_wide=True, nx=60)
    sol = solve_steady(model)
    with pytest.raises(ParameterError, match="NetCDF"):
        save(sol, tmp_path / "b.csv")
    assert not (tmp_path / "b.csv").exists()
