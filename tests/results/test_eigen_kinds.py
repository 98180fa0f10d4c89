"""The eigen-solver's result kinds (modes, gyroscopic_modes, critical, divergence): save ->
read gives every field back bit for bit; summaries are plain values; old files still load."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from examples_eigen import EXAMPLES, PARAMS, damped_modes_example

from gyroshell.results.base import from_dataset, kinds, metadata, read
from gyroshell.results.critical import CriticalSpeeds, Divergence
from gyroshell.results.modes import GyroscopicModes, Modes

CLASSES = {"modes": Modes, "gyroscopic_modes": GyroscopicModes, "critical": CriticalSpeeds,
           "divergence": Divergence}


@pytest.fixture(scope="module")
def built():
    return {kind: build() for kind, build in EXAMPLES.items()}


def same_field(a, b, name):
    if isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray), name
        assert a.shape == b.shape and a.dtype == b.dtype, name
        assert np.array_equal(a, b), name
    else:
        assert type(a) is type(b) and a == b, name


def same_result(a, b):
    assert type(a) is type(b)
    for f in dataclasses.fields(a):
        same_field(getattr(a, f.name), getattr(b, f.name), f.name)


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(EXAMPLES))
def test_every_kind_round_trips_exactly(built, kind, tmp_path):
    result = built[kind]
    assert isinstance(result, CLASSES[kind]) and result.kind == kind
    assert kinds()[kind] is CLASSES[kind]
    path = result.save(tmp_path / f"{kind}.nc", params=PARAMS)
    back = read(path)
    same_result(result, back)
    assert metadata(path)["parameters"] == PARAMS


@pytest.mark.slow
def test_damped_modes_round_trip(tmp_path):
    result = damped_modes_example()
    assert result.damped
    same_result(result, read(result.save(tmp_path / "damped.nc")))


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(EXAMPLES))
def test_summaries_are_plain_json(built, kind):
    summary = built[kind].summary()
    assert json.loads(json.dumps(summary, allow_nan=True)).keys() == summary.keys()


def test_modes_summary_is_what_the_cli_printed(built):
    res = built["modes"]
    s = res.summary()
    assert s["omega"] == res.omega.tolist() and s["stability"] == "stable"
    assert s["unknowns"] == res.grid.unknowns and s["velocity"] == res.velocity
    assert s["period"] == res.period.tolist()


def test_critical_summary_carries_the_routes(built):
    c = built["critical"]
    s = c.summary()
    assert s["critical_speed"] == c.critical_speed
    assert s["eigen_solves"] == c.info["evaluations"] and s["mu"] == c.info["mu"]
    assert from_dataset(c.to_xarray()).info["bracket"] == c.info["bracket"]
    assert isinstance(from_dataset(c.to_xarray()).info["bracket"], tuple)


def test_frames_and_plots(built):
    frame = built["modes"].to_frame()
    assert list(frame["omega"]) == built["modes"].omega.tolist()
    assert len(built["gyroscopic_modes"].to_frame()) == built["gyroscopic_modes"].count
    ax = built["modes"].plot()
    assert "mode 1" in ax.get_title()
    ax = built["divergence"].plot()
    assert "V_div" in ax.get_title()


def test_a_divergence_without_grid_still_saves_but_has_no_field(built, tmp_path):
    from gyroshell.core.errors import ParameterError

    d = built["divergence"]
    bare = Divergence(d.speed, d.mu, d.mode)
    same_result(bare, read(bare.save(tmp_path / "bare.nc")))
    with pytest.raises(ParameterError, match="no grid"):
        bare.plot()
